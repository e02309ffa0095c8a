// Stiffness for the implicit integrators (notes §3): the exact tangent against finite
// differences of the force, and the bond-wise majoriser against the exact tangent.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "linear/sparse_symmetric.hpp"
#include "model/model.hpp"
#include "support/eigenvalues.hpp"
#include "support/stiffness_block.hpp"

namespace fissure {
namespace {

using test::deformed;
using test::dense;
using test::small_block;

// K v against the central difference −(F(y + hv) − F(y − hv)) / 2h, for 4 directions. With h
// 1e-7 of the bond length, truncation (O(h²)) and round-off (1e-16/1e-7 of the force) stay well
// below the 1e-6 bound.
void expect_tangent_matches_force_differences(Model& model, const Families& families,
                                              const std::vector<double>& y) {
  SparseSymmetric K = two_hop_pattern(families);
  model.stiffness()->assemble_tangent(y.data(), K, false);
  const std::size_t n = y.size();
  std::vector<double> up(n), down(n), Kv(n), yp(n), ym(n);
  const double h = 0.02 * 1e-7;
  for (int probe = 0; probe < 4; ++probe) {
    std::vector<double> v(n);
    for (std::size_t k = 0; k < n; ++k) v[k] = std::sin(1.7 * k + 3.1 * probe);
    for (std::size_t k = 0; k < n; ++k) yp[k] = y[k] + h * v[k], ym[k] = y[k] - h * v[k];
    model.forces(yp.data(), up.data());
    model.forces(ym.data(), down.data());
    K.multiply(v.data(), Kv.data());
    double error = 0, norm = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const double fd = -(up[k] - down[k]) / (2 * h);
      error += (Kv[k] - fd) * (Kv[k] - fd);
      norm += fd * fd;
    }
    const double relative = std::sqrt(error / norm);
    std::printf("direction %d: |Kv - FD| / |FD| = %.2e\n", probe, relative);
    EXPECT_LT(relative, 1e-6);
  }
}

TEST(Stiffness, ExactTangentMatchesForceDifferencesElastic) {
  const Scene scene = small_block();
  auto model = make_model(scene);
  ASSERT_NE(model->stiffness(), nullptr);
  expect_tangent_matches_force_differences(*model, scene.families, deformed(scene.particles, 0.02));
  expect_tangent_matches_force_differences(*model, scene.families,
                                           deformed(scene.particles, -0.03));
}

TEST(Stiffness, ExactTangentMatchesForceDifferencesWithFrozenPlasticExtension) {
  const Scene scene = small_block(", plasticity: {yield_stress: 5.0e3}");
  auto model = make_model(scene);
  ASSERT_NE(model->plastic_flow(), nullptr);
  EXPECT_GT(model->plastic_flow()->update_plasticity(deformed(scene.particles, 0.05).data()), 0u);
  expect_tangent_matches_force_differences(*model, scene.families, deformed(scene.particles, 0.03));
}

// min eig(K^bw) ≥ 0 and min eig(K^bw − K) ≥ 0, to round-off (1e-12 of the largest eigenvalue),
// in stretched and compressed states; in compression the exact tangent itself is indefinite,
// which is why Newton uses the majoriser.
TEST(Stiffness, MajoriserIsPositiveSemidefiniteAndDominatesTheTangent) {
  const Scene scene = small_block();
  auto model = make_model(scene);
  for (const double strain : {0.03, -0.05}) {
    const auto y = deformed(scene.particles, strain);
    SparseSymmetric bw = bond_pattern(scene.families), K = two_hop_pattern(scene.families);
    model->stiffness()->assemble_majoriser(y.data(), bw);
    model->stiffness()->assemble_tangent(y.data(), K, false);
    const Eigen::MatrixXd A = dense(bw), T = dense(K);
    EXPECT_LT((A - A.transpose()).cwiseAbs().maxCoeff(), 1e-12 * A.cwiseAbs().maxCoeff());
    EXPECT_LT((T - T.transpose()).cwiseAbs().maxCoeff(), 1e-9 * T.cwiseAbs().maxCoeff());
    const Eigen::VectorXd eig_bw = test::symmetric_eigenvalues(A),
                          eig_gap = test::symmetric_eigenvalues(A - T),
                          eig_K = test::symmetric_eigenvalues(T);
    const double top = eig_bw.maxCoeff();
    std::printf(
        "strain %+.2f: min eig K^bw %.2e, min eig (K^bw - K) %.2e, min eig K %.2e "
        "(of max %.2e)\n",
        strain, eig_bw.minCoeff() / top, eig_gap.minCoeff() / top, eig_K.minCoeff() / top, top);
    EXPECT_GT(eig_bw.minCoeff(), -1e-12 * top);
    EXPECT_GT(eig_gap.minCoeff(), -1e-12 * top);
    // The tangent without the compressed bonds' geometric term: PSD and ⪰ K as well.
    SparseSymmetric projected = two_hop_pattern(scene.families);
    model->stiffness()->assemble_tangent(y.data(), projected, true);
    const Eigen::MatrixXd P = dense(projected);
    const double p_min = test::symmetric_eigenvalues(P).minCoeff(),
                 p_gap = test::symmetric_eigenvalues(P - T).minCoeff();
    std::printf("strain %+.2f: min eig K+ %.2e, min eig (K+ - K) %.2e\n", strain, p_min / top,
                p_gap / top);
    EXPECT_GT(p_min, -1e-12 * top);
    EXPECT_GT(p_gap, -1e-12 * top);
    // The majoriser is not uselessly loose: it stays within 10× of the tangent's largest mode.
    EXPECT_LT(top, 10 * eig_K.maxCoeff());
  }
}

}  // namespace
}  // namespace fissure
