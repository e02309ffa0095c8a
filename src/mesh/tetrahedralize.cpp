// tetrahedralize_surface: checks and refines a closed surface, then meshes it with TetGen.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "mesh/geometry.hpp"
#include "mesh/mesh_util.hpp"

namespace fissure {

namespace {

// Surface edges longer than this multiple of λ are split before meshing.
constexpr double kSurfaceEdgeRatio = 1.5;

// Every edge must be shared by exactly two triangles.
void check_closed(const SurfaceMesh& surface, const std::string& file) {
  std::vector<std::pair<int, int>> edges;
  edges.reserve(surface.triangles.size());
  for (size_t t = 0; t < surface.triangles.size(); t += 3) {
    for (int k = 0; k < 3; ++k) {
      const int a = surface.triangles[t + k];
      const int b = surface.triangles[t + (k + 1) % 3];
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(edges.begin(), edges.end());
  size_t boundary = 0, non_manifold = 0;
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    boundary += (j - i == 1);
    non_manifold += (j - i > 2);
    i = j;
  }
  if (boundary > 0) {
    throw InputError(file, "",
                     fmt::format("surface is not closed: {} boundary edges (edges used by only one "
                                 "triangle)",
                                 boundary));
  }
  if (non_manifold > 0) {
    throw InputError(file, "",
                     fmt::format("surface is not manifold: {} edges are shared by more than two "
                                 "triangles",
                                 non_manifold));
  }
}

double surface_area(const SurfaceMesh& surface) {
  double area = 0.0;
  for (size_t t = 0; t < surface.triangles.size(); t += 3) {
    const double* a = &surface.vertices[3 * surface.triangles[t]];
    const double* b = &surface.vertices[3 * surface.triangles[t + 1]];
    const double* c = &surface.vertices[3 * surface.triangles[t + 2]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    area += 0.5 * std::hypot(u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                             u[0] * v[1] - u[1] * v[0]);
  }
  return area;
}

// The vertices' bounding box (at least one vertex).
struct BoundingBox {
  std::array<double, 3> lo, hi;
  double volume() const { return (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]); }
};

BoundingBox bounding_box(const std::vector<double>& vertices) {
  BoundingBox box{{vertices[0], vertices[1], vertices[2]}, {vertices[0], vertices[1], vertices[2]}};
  for (size_t i = 0; i < vertices.size(); ++i) {
    box.lo[i % 3] = std::min(box.lo[i % 3], vertices[i]);
    box.hi[i % 3] = std::max(box.hi[i % 3], vertices[i]);
  }
  return box;
}

void move(std::vector<double>& vertices, const std::array<double, 3>& by) {
  for (size_t i = 0; i < vertices.size(); ++i) vertices[i] += by[i % 3];
}

TetMesh mesh_surface(const SurfaceMesh& surface, double edge_length, const std::string& source_file,
                     bool check_intersections) {
  if (!(edge_length > 0.0) || !std::isfinite(edge_length)) {
    throw InputError(source_file, "",
                     fmt::format("edge length must be positive and finite, got {}", edge_length));
  }
  SurfaceMesh closed = surface;
  mesh_detail::validate_surface(closed, source_file);
  mesh_detail::weld_vertices(closed);
  mesh_detail::validate_surface(closed, source_file);
  check_closed(closed, source_file);
  const double box_volume = bounding_box(closed.vertices).volume();
  // TetGen asserts (aborts) on input without extent in some axis.
  if (!(box_volume > 0.0)) {
    throw InputError(source_file, "", "surface is flat: it encloses no volume");
  }
  mesh_detail::check_tet_budget(box_volume, surface_area(closed), edge_length, source_file);
  mesh_detail::refine_surface(closed, kSurfaceEdgeRatio * edge_length);
  return mesh_detail::tetgen_quality_mesh(closed, mesh_detail::regular_tet_volume(edge_length),
                                          source_file, check_intersections);
}

}  // namespace

// A surface read from a file is meshed with its bounding box's lowest corner at the origin, as the
// primitives are (tetrahedralize_primitive).
TetMesh tetrahedralize_surface(const SurfaceMesh& surface, double edge_length,
                               const std::string& source_file) {
  mesh_detail::validate_surface(surface, source_file);
  const std::array<double, 3> corner = bounding_box(surface.vertices).lo;
  SurfaceMesh local = surface;
  move(local.vertices, {-corner[0], -corner[1], -corner[2]});
  TetMesh mesh = mesh_surface(local, edge_length, source_file, true);
  move(mesh.vertices, corner);
  return mesh;
}

TetMesh mesh_detail::tetrahedralize_primitive(const SurfaceMesh& surface, double edge_length,
                                              const std::array<double, 3>& origin) {
  TetMesh mesh = mesh_surface(surface, edge_length, "", false);
  move(mesh.vertices, origin);
  return mesh;
}

}  // namespace fissure
