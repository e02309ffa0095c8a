#include "scene/option_reader.hpp"

#include <fmt/format.h>

#include <cmath>

#include "scene/yaml_reader.hpp"

namespace fissure {

OptionReader::OptionReader(const YamlReader& reader, const YAML::Node& node, std::string path)
    : reader_(reader), node_(node), path_(std::move(path)) {}

const std::string& OptionReader::file() const { return reader_.file(); }

std::string OptionReader::path(const std::string& key) const { return join(path_, key); }

void OptionReader::fail(const std::string& key, const std::string& reason) const {
  reader_.fail(path(key), reason);
}

bool OptionReader::has(const std::string& key) const {
  return node_.IsMap() && static_cast<bool>(node_[key]);
}

double OptionReader::number(const std::string& key, double fallback) const {
  return has(key) ? reader_.number(node_[key], path(key)) : fallback;
}

double OptionReader::positive(const std::string& key, double fallback) const {
  return has(key) ? reader_.positive(node_[key], path(key)) : fallback;
}

double OptionReader::non_negative(const std::string& key, double fallback) const {
  return has(key) ? reader_.non_negative(node_[key], path(key)) : fallback;
}

int OptionReader::whole(const std::string& key, int fallback, int low, int high) const {
  if (!has(key)) return fallback;
  const double value = low > 0 ? positive(key, 0) : non_negative(key, 0);
  if (value != std::floor(value) || value < low || value > high)
    fail(key, fmt::format("must be a whole number from {} to {}, got {}", low, high, value));
  return static_cast<int>(value);
}

bool OptionReader::boolean(const std::string& key, bool fallback) const {
  return has(key) ? reader_.boolean(node_[key], path(key)) : fallback;
}

std::string OptionReader::string(const std::string& key, const std::string& fallback) const {
  return has(key) ? reader_.string(node_[key], path(key)) : fallback;
}

double OptionReader::positive(const std::string& key) const {
  return reader_.positive(node_.IsMap() ? node_[key] : YAML::Node(), path(key));
}

std::array<double, 3> OptionReader::vec3(const std::string& key) const {
  return reader_.vec3(node_.IsMap() ? node_[key] : YAML::Node(), path(key));
}

}  // namespace fissure
