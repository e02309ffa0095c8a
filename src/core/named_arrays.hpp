#pragma once
// Named arrays of numbers: how the parts of a run hand their state to a checkpoint and take it
// back (app/checkpoint.hpp), without knowing the file format.
#include <string>
#include <utility>
#include <vector>

namespace fissure {

using NamedArrays = std::vector<std::pair<std::string, std::vector<double>>>;

// The array called `name`, or nullptr.
inline const std::vector<double>* find_array(const NamedArrays& arrays, const std::string& name) {
  for (const auto& [key, values] : arrays)
    if (key == name) return &values;
  return nullptr;
}

}  // namespace fissure
