// Closed triangulated surface -> quality tet mesh through TetGen.
#include <fmt/format.h>
#include <tetgen.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/error.hpp"
#include "mesh/geometry.hpp"
#include "mesh/mesh_util.hpp"

namespace fissure {

namespace {

using mesh_detail::regular_tet_volume;
using mesh_detail::tet_signed_volume;

// Surfaces whose edges are all below this multiple of λ are kept as they are.
constexpr double kKeepSurfaceRatio = 2.0;

// TetGen's exit codes (terminatetetgen) as user-facing reasons.
std::string tetgen_failure(int code) {
  switch (code) {
    case 1:
      return "out of memory";
    case 2:
      return "internal error";
    case 3:
      return "the surface intersects itself";
    case 4:
      return "the surface has a feature too small for the mesh";
    case 5:
      return "two facets of the surface are very close to each other";
    case 10:
      return "invalid input";
    default:
      return fmt::format("error code {}", code);
  }
}

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

double longest_edge(const SurfaceMesh& surface) {
  double longest = 0.0;
  for (size_t t = 0; t < surface.triangles.size(); t += 3) {
    for (int k = 0; k < 3; ++k) {
      const double* p = &surface.vertices[3 * surface.triangles[t + k]];
      const double* q = &surface.vertices[3 * surface.triangles[t + (k + 1) % 3]];
      longest = std::max(longest, std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]));
    }
  }
  return longest;
}

double bounding_box_volume(const std::vector<double>& vertices) {
  double volume = 1.0;
  for (int axis = 0; axis < 3; ++axis) {
    double lo = vertices[axis], hi = vertices[axis];
    for (size_t i = axis; i < vertices.size(); i += 3) {
      lo = std::min(lo, vertices[i]);
      hi = std::max(hi, vertices[i]);
    }
    volume *= hi - lo;
  }
  return volume;
}

void fill_tetgen_input(const SurfaceMesh& surface, tetgenio& in) {
  in.firstnumber = 0;
  in.pointlist = new REAL[surface.vertices.size()];
  std::copy(surface.vertices.begin(), surface.vertices.end(), in.pointlist);
  in.numberofpoints = static_cast<int>(surface.vertices.size() / 3);
  const int triangle_count = static_cast<int>(surface.triangles.size() / 3);
  in.facetlist = new tetgenio::facet[triangle_count]();
  in.numberoffacets = triangle_count;
  for (int t = 0; t < triangle_count; ++t) {
    tetgenio::facet& f = in.facetlist[t];
    f.polygonlist = new tetgenio::polygon[1]();
    f.numberofpolygons = 1;
    f.polygonlist[0].vertexlist = new int[3];
    f.polygonlist[0].numberofvertices = 3;
    std::copy_n(&surface.triangles[3 * t], 3, f.polygonlist[0].vertexlist);
  }
}

}  // namespace

TetMesh tetrahedralize_surface(const SurfaceMesh& surface, double edge_length,
                               const std::string& source_file) {
  if (!(edge_length > 0.0) || !std::isfinite(edge_length)) {
    throw InputError(source_file, "",
                     fmt::format("edge length must be positive and finite, got {}", edge_length));
  }
  SurfaceMesh closed = surface;
  mesh_detail::validate_surface(closed, source_file);
  mesh_detail::weld_vertices(closed);
  mesh_detail::validate_surface(closed, source_file);
  check_closed(closed, source_file);
  mesh_detail::check_tet_budget(bounding_box_volume(closed.vertices), edge_length, source_file);

  tetgenio in, out;
  fill_tetgen_input(closed, in);
  // p: mesh the surface, q: radius-edge ratio bound, a: max volume, z: 0-based, Q: quiet.
  // Y keeps the input triangles: right when they are already about λ (TetGen would refine
  // them to ~0.7λ), wrong for coarse surfaces, which Y would leave unrefined.
  const bool keep_surface = longest_edge(closed) <= kKeepSurfaceRatio * edge_length;
  std::string switches = fmt::format("pq1.414a{}zQ{}", regular_tet_volume(edge_length),
                                     keep_surface ? "Y" : "");
  try {
    tetrahedralize(switches.data(), &in, &out);
  } catch (int code) {
    throw InputError(source_file, "", "TetGen failed: " + tetgen_failure(code));
  }
  if (out.numberoftetrahedra <= 0) throw InputError(source_file, "", "TetGen produced no tets");

  TetMesh mesh;
  mesh.vertices.assign(out.pointlist, out.pointlist + 3 * out.numberofpoints);
  mesh.tets.resize(4 * static_cast<size_t>(out.numberoftetrahedra));
  for (int t = 0; t < out.numberoftetrahedra; ++t) {
    int* tet = &mesh.tets[4 * static_cast<size_t>(t)];
    std::copy_n(out.tetrahedronlist + static_cast<size_t>(t) * out.numberofcorners, 4, tet);
    if (tet_signed_volume(mesh.vertices.data(), tet) < 0.0) std::swap(tet[2], tet[3]);
  }
  return mesh;
}

}  // namespace fissure
