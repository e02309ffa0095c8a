#pragma once
// A small block in a general deformation, for the stiffness tests (tests/model/test_stiffness.cpp,
// test_tangent_product.cpp).
#include <Eigen/Dense>
#include <cmath>
#include <string>
#include <vector>

#include "linear/sparse_symmetric.hpp"
#include "support/scenes.hpp"

namespace fissure::test {

// A 0.06 m block at λ = 0.02 m (a few hundred particles, every one near a surface, where the
// calibrated weights differ most from the uncorrected ones), ν = 0.125 like the paper's bar.
// material_options is appended to the material map, e.g. ", plasticity: {yield_stress: 5.0e3}".
inline Scene small_block(const std::string& material_options = "") {
  return block_scene({.size = {0.06, 0.06, 0.06},
                      .resolution = 0.02,
                      .bulk = 1.0e6,
                      .shear = 1.2e6,
                      .material = material_options});
}

// A general deformation: stretch, shear and a rotation, plus a smooth non-affine ripple so that
// bonds are neither all stretched nor all alike.
inline std::vector<double> deformed(const Particles& p, double strain) {
  const double c = std::cos(0.4), s = std::sin(0.4);
  const double F[9] = {c * (1 + strain), -s, strain,          s, c * (1 - 0.5 * strain), 0,
                       0.3 * strain,     0,  1 + 0.8 * strain};
  auto y = deform(p, F);
  for (int i = 0; i < p.count(); ++i)
    y[3 * i + 2] += 0.2 * strain * 0.02 * std::sin(150.0 * p.reference[3 * i]);
  return y;
}

inline Eigen::MatrixXd dense(const SparseSymmetric& a) {
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(a.rows, a.rows);
  for (int r = 0; r < a.rows; ++r)
    for (int k = a.offsets[r]; k < a.offsets[r + 1]; ++k) d(r, a.columns[k]) = a.values[k];
  return d;
}

}  // namespace fissure::test
