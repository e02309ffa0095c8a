#pragma once
// The options of one part of a scene (an integrator, a model, a collider's shape) as its own parser
// reads them: typed getters with defaults, range checks and choices, every error an InputError
// naming the file, the key path and the reason. No YAML: the parsers live next to the parts they
// configure (integrators/, model/), and only the config layer constructs a reader.
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "scene/unknown_choice.hpp"

namespace YAML {
class Node;
}

namespace fissure {

class YamlReader;

class OptionReader {
 public:
  // The map `node` at key path `path` (e.g. "integrator", "bodies[0].material"), valid while
  // both live: a parser reads its options during the call that hands it the reader.
  OptionReader(const YamlReader& reader, const YAML::Node& node, std::string path);

  const std::string& file() const;
  // "path.key": what an error about `key` names.
  std::string path(const std::string& key) const;
  [[noreturn]] void fail(const std::string& key, const std::string& reason) const;

  bool has(const std::string& key) const;
  // Each returns `fallback` when the key is absent.
  double number(const std::string& key, double fallback) const;
  double positive(const std::string& key, double fallback) const;
  double non_negative(const std::string& key, double fallback) const;
  // A whole number in [low, high] (low ≥ 0): "must be a whole number from low to high".
  int whole(const std::string& key, int fallback, int low, int high) const;
  bool boolean(const std::string& key, bool fallback) const;
  std::string string(const std::string& key, const std::string& fallback) const;
  // Required ones: an absent key fails as "missing" (a number) or "expected [x, y, z]".
  double positive(const std::string& key) const;
  std::array<double, 3> vec3(const std::string& key) const;
  // One of `choices` by name, as its value; a name not among them fails with the nearest one.
  template <class Choice>
  Choice choice(const std::string& key, Choice fallback,
                const std::vector<std::pair<std::string, Choice>>& choices) const {
    if (!has(key)) return fallback;
    const std::string value = string(key, "");
    std::vector<std::string> names;
    for (const auto& [name, choice] : choices) {
      if (name == value) return choice;
      names.push_back(name);
    }
    fail(key, unknown_choice(key, value, names));
  }

 private:
  const YamlReader& reader_;
  const YAML::Node& node_;
  std::string path_;
};

// The name of `value` in `choices` (as the config spells it), "" if it has none.
template <class Choice>
std::string choice_name(Choice value, const std::vector<std::pair<std::string, Choice>>& choices) {
  for (const auto& [name, choice] : choices)
    if (choice == value) return name;
  return {};
}

}  // namespace fissure
