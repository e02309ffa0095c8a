#pragma once
// Finite-difference check that a model's forces are the negative gradient of its energy.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
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

// Forces are pair-wise equal and opposite, so they sum to zero up to round-off: each force is a
// sum of about a hundred bond terms (64 ε × the largest force), and the sum of all of them can be
// off by that times their count.
inline void expect_forces_sum_to_zero(const std::vector<double>& f, const std::string& label) {
  double scale = 0, sum[3] = {0, 0, 0};
  for (std::size_t k = 0; k < f.size(); ++k) {
    scale = std::max(scale, std::abs(f[k]));
    sum[k % 3] += f[k];
  }
  const double round_off = 64 * std::numeric_limits<double>::epsilon() * scale * f.size();
  for (double s : sum) EXPECT_LT(std::abs(s), round_off) << label;
}

// The reference positions moved by a small deterministic pattern (2e-4 m), a generic state.
inline std::vector<double> perturbed(std::vector<double> y) {
  for (std::size_t k = 0; k < y.size(); ++k) y[k] += 2e-4 * std::sin(1.7 * k);
  return y;
}

}  // namespace fissure::test
