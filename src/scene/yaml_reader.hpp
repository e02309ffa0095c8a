#pragma once
// Strict reading of a YAML tree: every error names the file, the key path and the reason.
#include <yaml-cpp/yaml.h>

#include <array>
#include <string>
#include <vector>

#include "scene/unknown_choice.hpp"

namespace fissure {

class YamlReader {
 public:
  explicit YamlReader(std::string file) : file_(std::move(file)) {}
  const std::string& file() const { return file_; }

  [[noreturn]] void fail(const std::string& key, const std::string& reason) const;

  // Rejects keys of `node` (a map at `path`) not in `allowed`, suggesting the nearest one.
  void check_keys(const YAML::Node& node, const std::string& path,
                  const std::vector<std::string>& allowed) const;
  void require_map(const YAML::Node& node, const std::string& path) const;

  double number(const YAML::Node& node, const std::string& path) const;
  double positive(const YAML::Node& node, const std::string& path) const;
  double non_negative(const YAML::Node& node, const std::string& path) const;
  bool boolean(const YAML::Node& node, const std::string& path) const;
  std::string string(const YAML::Node& node, const std::string& path) const;
  std::array<double, 3> vec3(const YAML::Node& node, const std::string& path) const;

 private:
  std::string file_;
};

// Joins a key path: join("bodies[0]", "material") == "bodies[0].material".
std::string join(const std::string& path, const std::string& key);

// Applies "a.b[0].c=value" (value parsed as YAML) to `root`; `file` names errors.
void apply_override(YAML::Node& root, const std::string& assignment, const std::string& file);

}  // namespace fissure
