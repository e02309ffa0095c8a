#pragma once
// Reading a scene file as YAML, with `base:`: a scene file may name another one whose keys it
// starts from and overrides (configs/compare/ runs one scene with each integrator this way).
#include <yaml-cpp/yaml.h>

#include <string>

namespace fissure {

// The YAML map in `text`; InputError naming `file`, line and column if it is not valid YAML.
YAML::Node parse_yaml(const std::string& text, const std::string& file);

// The YAML map in the file at `path` with its `base:` chain resolved: the base file (a path
// relative to the including file's folder) is read first, and this file's keys replace its keys
// (maps merge key by key, lists and values are replaced). The result has no `base` key.
YAML::Node load_yaml_with_base(const std::string& path);

}  // namespace fissure
