#pragma once
// Finite-difference check that a model's forces are the negative gradient of its energy.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "model/model.hpp"

namespace fissure::test {

// Central differences (h = 1e-7 m) of Π on 12 spread-out components of y must match −F within
// 1e-6 of the largest force: the O(h²) truncation and the round-off of the energy sum are both
// orders of magnitude below that at the strains the tests use.
inline void expect_force_is_energy_gradient(Model& model, std::vector<double> y) {
  std::vector<double> f(y.size());
  model.forces(y.data(), f.data());
  double scale = 0;
  for (double v : f) scale = std::max(scale, std::abs(v));
  const double h = 1e-7;
  for (int probe = 0; probe < 12; ++probe) {
    const std::size_t k = (probe * 7919) % y.size();
    const double saved = y[k];
    y[k] = saved + h;
    const double up = model.elastic_energy(y.data());
    y[k] = saved - h;
    const double down = model.elastic_energy(y.data());
    y[k] = saved;
    EXPECT_NEAR(-(up - down) / (2 * h), f[k], 1e-6 * scale) << "component " << k;
  }
}

}  // namespace fissure::test
