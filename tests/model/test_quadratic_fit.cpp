// The weighted quadratic fit (model/quadratic_fit.hpp) that fictitious particles and the
// second-order correction share.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "model/quadratic_fit.hpp"

namespace fissure {
namespace {

// Points of a jittered cubic lattice within a ball of radius 1.5 about the origin, without it.
std::vector<Eigen::Vector3d> ball_points(std::mt19937& rng) {
  std::uniform_real_distribution<double> jitter(-0.2, 0.2);
  std::vector<Eigen::Vector3d> points;
  for (int x = -2; x <= 2; ++x)
    for (int y = -2; y <= 2; ++y)
      for (int z = -2; z <= 2; ++z) {
        const Eigen::Vector3d p(x + jitter(rng), y + jitter(rng), z + jitter(rng));
        if ((x || y || z) && p.norm() < 1.5 * 1.2) points.push_back(0.01 * p);
      }
  return points;
}

// A quadratic f(x_0 + ξ) − f(x_0) = g·ξ + ½ ξᵀAξ with random g and A gives q = (s g, s² A_xx,
// s² A_yy, s² A_zz, s² A_xy, s² A_xz, s² A_yz) to round-off, for any positive weights: the fit
// reproduces quadratics, and q holds the derivatives the correction reads. A basis with a
// wrong factor (d_x² for ½d_x²) or a transposed solve fails by O(1).
TEST(QuadraticFit, ReproducesEveryQuadraticAndItsDerivatives) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> value(-1, 1), positive(0.5, 2);
  const std::vector<Eigen::Vector3d> xi = ball_points(rng);
  std::vector<double> weight(xi.size());
  for (double& w : weight) w = positive(rng);
  const double scale = 0.0145;
  std::vector<QuadraticBasis> a;
  ASSERT_TRUE(quadratic_fit(xi, weight, scale, a));
  ASSERT_EQ(a.size(), xi.size());
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::Vector3d g(value(rng), value(rng), value(rng));
    Eigen::Matrix3d A;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c <= r; ++c) A(r, c) = A(c, r) = 100 * value(rng);
    QuadraticBasis q = QuadraticBasis::Zero();
    for (std::size_t j = 0; j < xi.size(); ++j)
      q += a[j] * (g.dot(xi[j]) + 0.5 * xi[j].dot(A * xi[j]));
    QuadraticBasis expected;
    expected << scale * g, scale * scale * A(0, 0), scale * scale * A(1, 1),
        scale * scale * A(2, 2), scale * scale * A(0, 1), scale * scale * A(0, 2),
        scale * scale * A(1, 2);
    EXPECT_LT((q - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.cwiseAbs().maxCoeff())
        << "trial " << trial;
  }
}

// Points in one plane do not determine the curvature across it: the fit says so instead of
// returning coefficients from a singular system; so do fewer than 9 points.
TEST(QuadraticFit, RefusesPointsThatDoNotDetermineAQuadratic) {
  std::mt19937 rng(11);
  std::vector<Eigen::Vector3d> planar;
  for (const Eigen::Vector3d& p : ball_points(rng)) planar.push_back({p[0], p[1], 0.0});
  std::vector<double> weight(planar.size(), 1.0);
  std::vector<QuadraticBasis> a;
  EXPECT_FALSE(quadratic_fit(planar, weight, 0.0145, a));
  EXPECT_TRUE(a.empty());
  const std::vector<Eigen::Vector3d> points = ball_points(rng);
  const std::vector<Eigen::Vector3d> few(points.begin(), points.begin() + 8);
  EXPECT_FALSE(quadratic_fit(few, std::vector<double>(8, 1.0), 0.0145, a));
}

}  // namespace
}  // namespace fissure
