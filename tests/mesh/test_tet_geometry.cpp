// A tet mesh's boundary and its tets' second moments (mesh/tet_geometry.hpp), on a box.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "mesh/geometry.hpp"
#include "mesh/mesh_util.hpp"
#include "mesh/tet_geometry.hpp"

namespace fissure {
namespace {

constexpr double kSize[3] = {0.3, 0.1, 0.2};

// The boundary of a tetrahedralised box is its surface, oriented outwards: the triangles' areas
// sum to the box's, their area vectors to zero (a closed surface), and ∮ x·n dA / 3 to its volume
// (divergence theorem), which a triangle missing, doubled or turned inwards breaks.
TEST(TetGeometry, BoundaryTrianglesCloseTheBoxOutwards) {
  const TetMesh mesh = tetrahedralize_box({0, 0, 0}, {kSize[0], kSize[1], kSize[2]}, 0.05);
  const auto triangles = boundary_triangles(mesh);
  ASSERT_GT(triangles.size(), 12u);
  double area = 0, flux = 0, closure[3] = {0, 0, 0};
  for (const auto& t : triangles) {
    double u[3], v[3], n[3], centroid[3];
    for (int a = 0; a < 3; ++a) {
      u[a] = t[3 + a] - t[a], v[a] = t[6 + a] - t[a];
      centroid[a] = (t[a] + t[3 + a] + t[6 + a]) / 3;
    }
    n[0] = 0.5 * (u[1] * v[2] - u[2] * v[1]);  // area vector
    n[1] = 0.5 * (u[2] * v[0] - u[0] * v[2]);
    n[2] = 0.5 * (u[0] * v[1] - u[1] * v[0]);
    area += std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int a = 0; a < 3; ++a) flux += centroid[a] * n[a] / 3, closure[a] += n[a];
  }
  const double box_area = 2 * (kSize[0] * kSize[1] + kSize[1] * kSize[2] + kSize[0] * kSize[2]);
  const double volume = kSize[0] * kSize[1] * kSize[2];
  EXPECT_NEAR(area / box_area, 1.0, 1e-12);
  EXPECT_NEAR(flux / volume, 1.0, 1e-12);
  for (double c : closure) EXPECT_LT(std::abs(c), 1e-14);
}

// By the parallel-axis theorem the tets' second moments about their barycentres plus V_t c_t c_tᵀ
// (about the box's centre) sum to the box's own, V/12 diag(a², b², c²): exact, so a wrong factor
// (1/12 or 1/10 for 1/20) or a missed off-diagonal term fails.
TEST(TetGeometry, SecondMomentsAddUpToTheBoxOwn) {
  const TetMesh mesh = tetrahedralize_box({0, 0, 0}, {kSize[0], kSize[1], kSize[2]}, 0.05);
  std::array<double, 6> sum{};
  for (int t = 0; t < mesh.tet_count(); ++t) {
    const std::array<double, 6> m = tet_second_moment(mesh, t);
    const int* tet = &mesh.tets[4 * t];
    double c[3] = {0, 0, 0};
    for (int k = 0; k < 4; ++k)
      for (int a = 0; a < 3; ++a) c[a] += 0.25 * mesh.vertices[3 * tet[k] + a];
    for (int a = 0; a < 3; ++a) c[a] -= 0.5 * kSize[a];
    const double V = std::abs(mesh_detail::tet_signed_volume(mesh.vertices.data(), tet));
    const double shift[6] = {c[0] * c[0], c[1] * c[1], c[2] * c[2],
                             c[0] * c[1], c[0] * c[2], c[1] * c[2]};
    for (int k = 0; k < 6; ++k) sum[k] += m[k] + V * shift[k];
  }
  const double volume = kSize[0] * kSize[1] * kSize[2];
  for (int a = 0; a < 3; ++a)
    EXPECT_NEAR(sum[a] / (volume / 12 * kSize[a] * kSize[a]), 1.0, 1e-12) << "axis " << a;
  for (int k = 3; k < 6; ++k) EXPECT_LT(std::abs(sum[k]), 1e-12 * volume * 0.01);
}

}  // namespace
}  // namespace fissure
