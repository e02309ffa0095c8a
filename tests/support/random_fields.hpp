#pragma once
// Random deformations and the isotropic continuum's energy density, for the tests of the
// second-order model (tests/model/test_second_order_*.cpp).
#include <Eigen/Dense>
#include <array>
#include <random>

namespace fissure::test {

// Entries uniform in [−1, 1].
inline Eigen::Matrix3d random_matrix(std::mt19937& rng) {
  std::uniform_real_distribution<double> value(-1, 1);
  Eigen::Matrix3d A;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) A(r, c) = value(rng);
  return A;
}

// Second derivatives Γ_a = ∂²u_a/∂x∂x of a random quadratic displacement: symmetric, entries up
// to 2 × scale.
inline std::array<Eigen::Matrix3d, 3> random_curvature(std::mt19937& rng, double scale) {
  std::array<Eigen::Matrix3d, 3> gamma;
  for (auto& g : gamma) {
    const Eigen::Matrix3d A = random_matrix(rng);
    g = scale * (A + A.transpose());
  }
  return gamma;
}

// ½ ε:C:ε, C isotropic with bulk modulus κ and shear modulus μ.
inline double isotropic_energy_density(const Eigen::Matrix3d& e, double bulk, double shear) {
  const double lame = bulk - 2 * shear / 3;
  return 0.5 * lame * e.trace() * e.trace() + shear * (e.array() * e.array()).sum();
}

}  // namespace fissure::test
