// The stable-step estimate is a bound: it never exceeds the exact critical step 2/√λ_max of
// M⁻¹K (K the exact tangent at rest), on a well-sampled block and on a bar one particle layer
// thick whose families hold 9 to 26 members. The earlier per-bond micromodulus formula gave
// 2.9× the critical step on that bar, so symplectic Euler at dt: auto blew up. And it is not
// uselessly small: it is exactly the Gershgorin step of the assembled bond-wise majoriser K^bw,
// which lies within a proven factor of K^bw's own critical step.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "linear/sparse_symmetric.hpp"
#include "model/model.hpp"
#include "scene/config.hpp"
#include "scene/scene.hpp"
#include "support/eigenvalues.hpp"

namespace fissure {
namespace {

struct Sample {
  const char* label;
  const char* geometry;
  double resolution;
  double bulk, shear;
};

class StableStepBound : public ::testing::TestWithParam<Sample> {};

// S = M^-1/2 K M^-1/2 as a dense matrix, read off K's compressed rows (both triangles stored).
Eigen::MatrixXd mass_scaled(const SparseSymmetric& K, const Particles& p) {
  const int n = 3 * p.count();
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(n, n);
  for (int r = 0; r < n; ++r)
    for (int k = K.offsets[r]; k < K.offsets[r + 1]; ++k) {
      const int c = K.columns[k];
      S(r, c) = K.values[k] / std::sqrt(p.mass[r / 3] * p.mass[c / 3]);
    }
  return S;
}

// The eigenvalues alone (no eigenvectors accumulated): the same tridiagonal QR, several times
// cheaper.
double largest_eigenvalue(const Eigen::MatrixXd& S) {
  return test::symmetric_eigenvalues(S).maxCoeff();
}

// The two Gershgorin bounds on λ_max(S^bw) that docs/model.md states, read off the assembled
// matrix at rest rather than from the per-bond formula. Each bond (i, j) puts k nnᵀ/m_i in the
// diagonal block S_ii and −k nnᵀ/√(m_i m_j) in S_ij (rank one). By blocks: λ ≤ max_i (‖S_ii‖ +
// Σ_j ‖S_ij‖) ≤ max_i (tr S_ii + Σ_j ‖S_ij‖₂), as S_ii ⪰ 0. By scalar rows (i, d): the row sum
// Σ_e |S_ii(d, e)| ≤ Σ_j √(m_j/m_i) Σ_e |S_ij(d, e)| (each bond's k|n_d n_e|/m_i), so
// λ ≤ max_{i,d} Σ_j (1 + √(m_j/m_i)) Σ_e |S_ij(d, e)|. Also returned: r = max over bonds of
// √(m_i/m_j), for the factor below.
struct Gershgorin {
  double bound, mass_ratio;
};
Gershgorin majoriser_gershgorin(const Eigen::MatrixXd& S, const Particles& p) {
  const int n = p.count();
  double by_blocks = 0, by_rows = 0, mass_ratio = 1;
  for (int i = 0; i < n; ++i) {
    double block = S.block<3, 3>(3 * i, 3 * i).trace(), row[3] = {0, 0, 0};
    for (int j = 0; j < n; ++j) {
      if (j == i) continue;
      const Eigen::Matrix3d off = S.block<3, 3>(3 * i, 3 * j);
      if (off.isZero(0)) continue;
      block += Eigen::JacobiSVD<Eigen::Matrix3d>(off).singularValues()(0);
      const double weight = 1 + std::sqrt(p.mass[j] / p.mass[i]);
      for (int d = 0; d < 3; ++d) row[d] += weight * off.row(d).cwiseAbs().sum();
      mass_ratio = std::max(mass_ratio, std::sqrt(p.mass[i] / p.mass[j]));
    }
    by_blocks = std::max(by_blocks, block);
    by_rows = std::max({by_rows, row[0], row[1], row[2]});
  }
  return {std::min(by_blocks, by_rows), mass_ratio};
}

TEST_P(StableStepBound, EstimateLiesBetweenTheExactCriticalStepAndAProvenFractionOfIt) {
  const Sample& s = GetParam();
  const std::string yaml = fmt::format(
      "time: {{end: 1.0}}\nbodies:\n  - geometry: {}\n    resolution: {}\n"
      "    material: {{density: 1000, bulk_modulus: {}, shear_modulus: {}}}\n",
      s.geometry, s.resolution, s.bulk, s.shear);
  const Scene scene = build_scene(parse_config(yaml, "bound.yaml"));
  auto model = make_model(scene);
  const Particles& p = scene.particles;
  SparseSymmetric K = two_hop_pattern(scene.families);
  model->stiffness()->assemble_tangent(p.reference.data(), K, false);
  const double critical = 2 / std::sqrt(largest_eigenvalue(mass_scaled(K, p)));
  SparseSymmetric K_bw = bond_pattern(scene.families);
  model->stiffness()->assemble_majoriser(p.reference.data(), K_bw);
  const Eigen::MatrixXd S_bw = mass_scaled(K_bw, p);
  const double critical_bw = 2 / std::sqrt(largest_eigenvalue(S_bw));
  const Gershgorin g = majoriser_gershgorin(S_bw, p);
  const double estimate = model->stable_time_step();
  std::printf(
      "%s: %d particles, estimate %.4g s, exact critical step %.4g s (ratio %.2f), majoriser's "
      "%.4g s (ratio %.2f), Gershgorin of the majoriser %.4g s, mass ratio r %.3f\n",
      s.label, p.count(), estimate, critical, critical / estimate, critical_bw,
      critical_bw / estimate, 2 / std::sqrt(g.bound), g.mass_ratio);
  EXPECT_LE(estimate, critical);
  // The estimate is the Gershgorin step of K^bw: no larger, no smaller (to round-off of the sums).
  EXPECT_NEAR(estimate * std::sqrt(g.bound) / 2, 1.0, 1e-12);
  // Not uselessly small: the block bound exceeds λ_max(S^bw) by at most 3(1 + r), since
  // tr S_ii ≤ 3‖S_ii‖ ≤ 3λ_max(S^bw) (S_ii a principal block) and Σ_j ‖S_ij‖ = Σ_j k/√(m_i m_j)
  // ≤ r tr S_ii; so the estimate is at least the majoriser's critical step / √(3(1 + r)).
  EXPECT_GE(estimate, critical_bw / std::sqrt(3 * (1 + g.mass_ratio)));
}

INSTANTIATE_TEST_SUITE_P(
    Samplings, StableStepBound,
    ::testing::Values(
        Sample{"block", "{box: {min: [0, 0, 0], max: [0.06, 0.06, 0.06]}}", 0.02, 2.0e6, 1.0e6},
        Sample{"one_layer_bar", "{box: {min: [0, 0, 0], max: [1.0, 0.1, 0.1]}}", 0.1, 5.0e6, 5.0e6},
        Sample{"near_incompressible", "{box: {min: [0, 0, 0], max: [0.06, 0.06, 0.06]}}", 0.02,
               3.3e7, 1.0e6}),
    [](const auto& info) { return std::string(info.param.label); });

}  // namespace
}  // namespace fissure
