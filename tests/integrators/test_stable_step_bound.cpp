// The stable-step estimate is a bound: it never exceeds the exact critical step 2/√λ_max of
// M⁻¹K (K the exact tangent at rest), on a well-sampled block and on a bar one particle layer
// thick whose families hold 9 to 26 members. The earlier per-bond micromodulus formula gave
// 2.9× the critical step on that bar, so symplectic Euler at dt: auto blew up.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "linear/sparse_symmetric.hpp"
#include "model/model.hpp"
#include "scene/config.hpp"
#include "scene/scene.hpp"

namespace fissure {
namespace {

struct Sample {
  const char* label;
  const char* geometry;
  double resolution;
  double bulk, shear;
};

class StableStepBound : public ::testing::TestWithParam<Sample> {};

TEST_P(StableStepBound, EstimateIsBelowTheExactCriticalStep) {
  const Sample& s = GetParam();
  const std::string yaml = fmt::format(
      "time: {{end: 1.0}}\nbodies:\n  - geometry: {}\n    resolution: {}\n"
      "    material: {{density: 1000, bulk_modulus: {}, shear_modulus: {}}}\n",
      s.geometry, s.resolution, s.bulk, s.shear);
  const Scene scene = build_scene(parse_config(yaml, "bound.yaml"));
  auto model = make_model(scene);
  const Particles& p = scene.particles;
  const int n = 3 * p.count();
  SparseSymmetric K = two_hop_pattern(scene.families);
  model->assemble_tangent(p.reference.data(), K, false);
  Eigen::MatrixXd S(n, n);
  std::vector<double> unit(n), column(n);
  for (int c = 0; c < n; ++c) {
    std::fill(unit.begin(), unit.end(), 0.0);
    unit[c] = 1;
    K.multiply(unit.data(), column.data());
    for (int r = 0; r < n; ++r) S(r, c) = column[r] / std::sqrt(p.mass[r / 3] * p.mass[c / 3]);
  }
  const double lambda_max =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S).eigenvalues().maxCoeff();
  const double critical = 2 / std::sqrt(lambda_max);
  const double estimate = model->stable_time_step();
  std::printf("%s: %d particles, estimate %.4g s, exact critical step %.4g s (ratio %.2f)\n",
              s.label, p.count(), estimate, critical, critical / estimate);
  EXPECT_LE(estimate, critical);
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
