#pragma once
// θ_i of every particle at positions y, as a vector.
#include <vector>

#include "model/model.hpp"

namespace fissure::test {

inline std::vector<double> dilatation(const Model& model, const std::vector<double>& y) {
  std::vector<double> theta(y.size() / 3);
  model.dilatation(y.data(), theta.data());
  return theta;
}

}  // namespace fissure::test
