// tetrahedralize_surface: closed surfaces mesh exactly; open or broken ones are rejected.
#include <gtest/gtest.h>

#include "mesh/geometry.hpp"
#include "mesh_test_util.hpp"

namespace fissure::test {
namespace {

TEST(TetrahedralizeSurface, CoarseCubeIsRefinedToTargetEdge) {
  const double edge = 0.25;
  const TetMesh mesh = tetrahedralize_surface(cube_surface(), edge, "cube.obj");
  EXPECT_NEAR(total_volume(mesh), 1.0, 1e-9);
  EXPECT_GT(min_volume(mesh), 0.0);
  EXPECT_NEAR(mean_edge_length(mesh), edge, 0.3 * edge);
}

TEST(TetrahedralizeSurface, DuplicateVerticesAreWelded) {
  SurfaceMesh s = cube_surface();
  // Give triangle 0 its own copies of its corners.
  for (int k = 0; k < 3; ++k) {
    const int v = s.triangles[k];
    s.vertices.insert(s.vertices.end(),
                      {s.vertices[3 * v], s.vertices[3 * v + 1], s.vertices[3 * v + 2]});
    s.triangles[k] = static_cast<int>(s.vertices.size() / 3) - 1;
  }
  EXPECT_NEAR(total_volume(tetrahedralize_surface(s, 0.5, "cube.obj")), 1.0, 1e-9);
}

TEST(TetrahedralizeSurface, OpenSurfaceRejected) {
  SurfaceMesh s = cube_surface();
  s.triangles.resize(s.triangles.size() - 3);
  expect_input_error([&] { tetrahedralize_surface(s, 0.5, "open.obj"); }, "open.obj",
                     "surface is not closed: 3 boundary edges");
}

TEST(TetrahedralizeSurface, NonManifoldSurfaceRejected) {
  SurfaceMesh s = cube_surface();
  s.triangles.insert(s.triangles.end(), {0, 1, 6});
  s.triangles.insert(s.triangles.end(), {0, 6, 1});
  expect_input_error([&] { tetrahedralize_surface(s, 0.5, "fan.obj"); }, "fan.obj", "not manifold");
}

// Two unit cubes overlapping by `shift`, one surface.
SurfaceMesh overlapping_cubes(double shift_x, double shift_yz) {
  SurfaceMesh s = cube_surface();
  SurfaceMesh moved = cube_surface();
  for (size_t i = 0; i < moved.vertices.size(); ++i) {
    moved.vertices[i] += i % 3 == 0 ? shift_x : shift_yz;
  }
  const int offset = static_cast<int>(s.vertices.size() / 3);
  s.vertices.insert(s.vertices.end(), moved.vertices.begin(), moved.vertices.end());
  for (int v : moved.triangles) s.triangles.push_back(v + offset);
  return s;
}

TEST(TetrahedralizeSurface, SelfIntersectionRejected) {
  for (const auto& [x, yz] : {std::pair{0.5, 0.25}, std::pair{0.3, 0.0}}) {
    expect_input_error([&] { tetrahedralize_surface(overlapping_cubes(x, yz), 2.0, "two.obj"); },
                       "two.obj", "the surface intersects itself");
  }
}

// Two back-to-back triangles: closed, but flat.
SurfaceMesh pillow(double tilt) {
  SurfaceMesh s;
  s.vertices = {0, 0, 0, 1, 0, tilt, 0, 1, tilt};
  s.triangles = {0, 1, 2, 0, 2, 1};
  return s;
}

TEST(TetrahedralizeSurface, FlatSurfaceRejected) {
  expect_input_error([] { tetrahedralize_surface(pillow(0.0), 0.5, "flat.obj"); }, "flat.obj",
                     "surface is flat");
}

TEST(TetrahedralizeSurface, TetGenFailureBecomesInputError) {
  expect_input_error([] { tetrahedralize_surface(pillow(1.0), 0.5, "tilted.obj"); }, "tilted.obj",
                     "TetGen failed: invalid input");
}

TEST(TetrahedralizeSurface, SeparateClosedPartsMeshTogether) {
  EXPECT_NEAR(total_volume(tetrahedralize_surface(overlapping_cubes(2.0, 0.0), 0.5, "two.obj")),
              2.0, 1e-9);
}

TEST(TetrahedralizeSurface, InvalidEdgeLength) {
  expect_input_error([&] { tetrahedralize_surface(cube_surface(), 0.0, "cube.obj"); }, "cube.obj",
                     "edge length must be positive");
}

TEST(TetrahedralizeSurface, AbsurdTetCountRejected) {
  expect_input_error([&] { tetrahedralize_surface(cube_surface(), 1e-4, "cube.obj"); }, "cube.obj",
                     "use a larger edge length");
}

}  // namespace
}  // namespace fissure::test
