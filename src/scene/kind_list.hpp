#pragma once
// The list behind each registry of parts a scene names (integrators, models, collider shapes,
// outputs): kinds with a name, their own keys and their parser, in the order of registration.
// Adding a kind also hands its parser to the config layer (scene/option_parsers.hpp).
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "scene/option_parsers.hpp"

namespace fissure {

// Appends `kind` and registers its option parser; throws std::logic_error if its name is taken
// ("the <what> '<name>' is registered twice").
template <class Kind>
void add_kind(std::vector<Kind>& kinds, Kind kind, const std::string& what) {
  for (const auto& k : kinds)
    if (k.name == kind.name)
      throw std::logic_error("the " + what + " '" + kind.name + "' is registered twice");
  using Parsed = decltype(kind.parse(std::declval<const OptionReader&>()));
  using Options = std::remove_const_t<typename Parsed::element_type>;
  register_option_parser(OptionParser<Options>{kind.name, kind.keys, kind.parse});
  kinds.push_back(std::move(kind));
}

template <class Kind>
std::vector<std::string> kind_names(const std::vector<Kind>& kinds) {
  std::vector<std::string> names;
  for (const auto& kind : kinds) names.push_back(kind.name);
  return names;
}

}  // namespace fissure
