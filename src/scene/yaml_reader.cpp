#include "scene/yaml_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace fissure {

std::string join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

void YamlReader::fail(const std::string& key, const std::string& reason) const {
  throw InputError(file_, key, reason);
}

void YamlReader::require_map(const YAML::Node& node, const std::string& path) const {
  if (!node || node.IsNull()) fail(path, "missing (expected a map)");
  if (!node.IsMap()) fail(path, "expected a map of keys");
}

void YamlReader::check_keys(const YAML::Node& node, const std::string& path,
                            const std::vector<std::string>& allowed) const {
  require_map(node, path);
  std::vector<std::string> seen;
  for (const auto& entry : node) {
    if (!entry.first.IsScalar()) fail(path, "a key must be a plain name, not a list or map");
    const std::string key = entry.first.Scalar();
    if (std::find(seen.begin(), seen.end(), key) != seen.end())
      fail(join(path, key), "duplicate key");
    seen.push_back(key);
    if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
    const std::string hint = nearest(key, allowed);
    std::string valid;
    for (const auto& a : allowed) valid += (valid.empty() ? "" : ", ") + a;
    fail(join(path, key), hint.empty() ? fmt::format("unknown key (valid: {})", valid)
                                       : fmt::format("unknown key; did you mean '{}'?", hint));
  }
}

double YamlReader::number(const YAML::Node& node, const std::string& path) const {
  if (!node || node.IsNull()) fail(path, "missing (expected a number)");
  if (!node.IsScalar()) fail(path, "expected a number");
  double value = 0;
  try {
    value = node.as<double>();
  } catch (const YAML::Exception&) {
    fail(path, fmt::format("expected a number, got '{}'", node.Scalar()));
  }
  if (!std::isfinite(value)) fail(path, "must be finite");
  return value;
}

double YamlReader::positive(const YAML::Node& node, const std::string& path) const {
  const double value = number(node, path);
  if (value <= 0) fail(path, fmt::format("must be positive, got {}", value));
  return value;
}

double YamlReader::non_negative(const YAML::Node& node, const std::string& path) const {
  const double value = number(node, path);
  if (value < 0) fail(path, fmt::format("must not be negative, got {}", value));
  return value;
}

bool YamlReader::boolean(const YAML::Node& node, const std::string& path) const {
  if (!node || !node.IsScalar()) fail(path, "expected true or false");
  try {
    return node.as<bool>();
  } catch (const YAML::Exception&) {
    fail(path, fmt::format("expected true or false, got '{}'", node.Scalar()));
  }
}

std::string YamlReader::string(const YAML::Node& node, const std::string& path) const {
  if (!node || !node.IsScalar()) fail(path, "expected a string");
  return node.Scalar();
}

std::array<double, 3> YamlReader::vec3(const YAML::Node& node, const std::string& path) const {
  if (!node || !node.IsSequence() || node.size() != 3) fail(path, "expected [x, y, z]");
  std::array<double, 3> v{};
  for (std::size_t k = 0; k < 3; ++k) v[k] = number(node[k], fmt::format("{}[{}]", path, k));
  return v;
}

// Splits "a.b[0].c" into {"a", "b", "0", "c"}.
static std::vector<std::string> split_key_path(const std::string& path) {
  std::vector<std::string> parts;
  std::string current;
  for (char c : path) {
    if (c == '.' || c == '[' || c == ']') {
      if (!current.empty()) parts.push_back(current);
      current.clear();
    } else {
      current += c;
    }
  }
  if (!current.empty()) parts.push_back(current);
  return parts;
}

static bool is_index(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

static void set_path(YAML::Node node, const std::vector<std::string>& parts, std::size_t k,
                     const YAML::Node& value, const std::string& file, const std::string& key) {
  const std::string& part = parts[k];
  const bool last = k + 1 == parts.size();
  if (is_index(part) && node.IsSequence()) {
    if (part.size() > 9) throw InputError(file, key, fmt::format("index {} out of range", part));
    const std::size_t index = std::stoul(part);
    if (index >= node.size())
      throw InputError(file, key,
                       fmt::format("index {} out of range (size {})", index, node.size()));
    if (last)
      node[index] = value;
    else
      set_path(node[index], parts, k + 1, value, file, key);
    return;
  }
  if (node.IsDefined() && !node.IsNull() && !node.IsMap())
    throw InputError(file, key, fmt::format("'{}' is not a map or list here", part));
  if (last) {
    node[part] = value;
    return;
  }
  YAML::Node child = node[part];
  if (!child.IsDefined() || child.IsNull()) {
    node[part] = YAML::Node(YAML::NodeType::Map);
    child = node[part];
  }
  set_path(child, parts, k + 1, value, file, key);
}

void apply_override(YAML::Node& root, const std::string& assignment, const std::string& file) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError(file, assignment, "--set expects key.path=value");
  const std::string key = assignment.substr(0, eq);
  YAML::Node value;
  try {
    value = YAML::Load(assignment.substr(eq + 1));
  } catch (const YAML::Exception& e) {
    throw InputError(file, key, fmt::format("--set value is not valid YAML: {}", e.msg));
  }
  const auto parts = split_key_path(key);
  if (parts.empty()) throw InputError(file, key, "--set expects key.path=value");
  set_path(root, parts, 0, value, file, key);
}

}  // namespace fissure
