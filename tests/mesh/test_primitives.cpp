// Box, sphere and cylinder: volume, orientation, shape and target edge length.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mesh/geometry.hpp"
#include "mesh_test_util.hpp"

namespace fissure::test {
namespace {

void expect_edge_near(const TetMesh& mesh, double edge) {
  EXPECT_NEAR(mean_edge_length(mesh), edge, 0.3 * edge);
}

TEST(Box, ExactVolumePositiveTetsAndBarycentresInside) {
  const Vec3 lo{-0.5, 0.0, 1.0}, hi{0.5, 2.0, 1.5};
  const TetMesh mesh = tetrahedralize_box(lo, hi, 0.1);
  EXPECT_NEAR(total_volume(mesh), 1.0, 1e-10);
  EXPECT_GT(min_volume(mesh), 0.0);
  expect_edge_near(mesh, 0.1);
  for (int t = 0; t < mesh.tet_count(); ++t) {
    for (int c = 0; c < 3; ++c) {
      double centre = 0.0;
      for (int k = 0; k < 4; ++k) centre += mesh.vertices[3 * mesh.tets[4 * t + k] + c] / 4.0;
      ASSERT_GT(centre, lo[c]);
      ASSERT_LT(centre, hi[c]);
    }
  }
}

TEST(Box, ThinBarMeetsTargetEdge) {
  const double edge = 0.025;
  const TetMesh mesh = tetrahedralize_box({0, 0, 0}, {1, 0.1, 0.1}, edge);
  EXPECT_NEAR(total_volume(mesh), 0.01, 1e-12);
  EXPECT_GT(min_volume(mesh), 0.0);
  expect_edge_near(mesh, edge);
}

TEST(Sphere, VolumeShapeAndEdge) {
  const Vec3 c{1.0, 2.0, 3.0};
  const TetMesh mesh = tetrahedralize_sphere(c, 1.0, 0.1);
  EXPECT_NEAR(total_volume(mesh), 4.0 / 3.0 * std::numbers::pi, 0.02 * 4.19);
  EXPECT_GT(min_volume(mesh), 0.0);
  expect_edge_near(mesh, 0.1);
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    const double* p = &mesh.vertices[3 * v];
    ASSERT_LE(std::hypot(p[0] - c[0], p[1] - c[1], p[2] - c[2]), 1.0 + 1e-9);
  }
}

TEST(Cylinder, VolumeShapeAndEdge) {
  const Vec3 p0{0.0, 0.0, 0.0}, p1{0.3, 0.2, 1.0};
  const double radius = 0.5, length = std::hypot(0.3, 0.2, 1.0);
  const TetMesh mesh = tetrahedralize_cylinder(p0, p1, radius, 0.1);
  const double exact = std::numbers::pi * radius * radius * length;
  EXPECT_NEAR(total_volume(mesh), exact, 0.02 * exact);
  EXPECT_GT(min_volume(mesh), 0.0);
  expect_edge_near(mesh, 0.1);
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    const double* p = &mesh.vertices[3 * v];
    const double along = (p[0] * p1[0] + p[1] * p1[1] + p[2] * p1[2]) / length;
    const double off_axis =
        std::sqrt(std::max(0.0, p[0] * p[0] + p[1] * p[1] + p[2] * p[2] - along * along));
    ASSERT_GE(along, -1e-9);
    ASSERT_LE(along, length + 1e-9);
    ASSERT_LE(off_axis, radius + 1e-9);
  }
}

TEST(Primitives, SmallShapesStillMesh) {
  EXPECT_NEAR(total_volume(tetrahedralize_box({0, 0, 0}, {0.01, 0.02, 0.03}, 1.0)), 6e-6, 1e-18);
  EXPECT_GT(min_volume(tetrahedralize_sphere({0, 0, 0}, 0.01, 1.0)), 0.0);
  EXPECT_GT(min_volume(tetrahedralize_cylinder({0, 0, 0}, {0, 0, 0.01}, 0.01, 1.0)), 0.0);
}

TEST(Primitives, InvalidArgumentsRejected) {
  expect_input_error(
      [] {
        tetrahedralize_box({0, 0, 0}, {1, 0, 1}, 0.1);
      },
      "", "box max must exceed box min");
  expect_input_error(
      [] {
        tetrahedralize_box({0, 0, 0}, {1, 1, 1}, -0.1);
      },
      "", "edge length must be positive");
  expect_input_error(
      [] {
        tetrahedralize_sphere({0, 0, 0}, 0.0, 0.1);
      },
      "", "sphere radius must be positive");
  expect_input_error(
      [] {
        tetrahedralize_cylinder({0, 0, 0}, {0, 0, 0}, 1.0, 0.1);
      },
      "", "cylinder length");
  expect_input_error(
      [] {
        tetrahedralize_box({0, 0, 0}, {1, 1, 1}, 1e-4);
      },
      "", "use a larger edge length");
}

}  // namespace
}  // namespace fissure::test
