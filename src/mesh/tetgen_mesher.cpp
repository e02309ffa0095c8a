// TetGen on a closed surface: a self-intersection check, then a quality mesh.
#include <fmt/format.h>
#include <tetgen.h>

#include <algorithm>
#include <utility>

#include "core/error.hpp"
#include "mesh/mesh_util.hpp"

namespace fissure::mesh_detail {

namespace {

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
      return "invalid input (for example a surface enclosing no volume)";
    default:
      return fmt::format("error code {}", code);
  }
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

// Runs TetGen's steps for a PLC (-p) with `switches`, then `finish` on the mesh. This replaces
// TetGen 1.5's tetrahedralize(), whose failure path frees its mesh twice (terminatetetgen frees
// it, then unwinding destroys it again) and corrupts the heap.
template <class Finish>
void run_tetgen(std::string switches, tetgenio& in, Finish&& finish) {
  tetgenbehavior behavior;
  behavior.parse_commandline(switches.data());
  auto* mesh = new tetgenmesh;
  try {
    mesh->b = &behavior;
    mesh->in = &in;
    mesh->initializepools();
    mesh->transfernodes();
    exactinit(behavior.verbose, behavior.noexact, behavior.nostaticfilter, mesh->xmax - mesh->xmin,
              mesh->ymax - mesh->ymin, mesh->zmax - mesh->zmin);
    long clock_ticks = 0;
    mesh->incrementaldelaunay(clock_ticks);
    mesh->meshsurface();
    finish(*mesh);
  } catch (int) {
    // terminatetetgen has freed the mesh's memory: release the object without its destructor.
    ::operator delete(mesh);
    throw;
  }
  delete mesh;
}

// Throws if TetGen finds intersecting facets (which it would otherwise mesh, or fail on).
void check_self_intersections(tetgenio& in, const std::string& file) {
  long intersecting = 0;
  // d: detect intersecting facets only.
  run_tetgen("pdzQ", in, [&](tetgenmesh& m) {
    m.detectinterfaces();
    intersecting = m.subfaces->items;
  });
  if (intersecting > 0) {
    throw InputError(
        file, "",
        fmt::format("the surface intersects itself ({} triangles involved)", intersecting));
  }
}

// p: mesh the surface, q: radius-edge ratio bound, a: max volume, z: 0-based, Q: quiet,
// Y: keep the surface triangles, which TetGen would otherwise refine to ~0.7λ.
void mesh_volume(tetgenio& in, double max_volume, tetgenio& out) {
  run_tetgen(fmt::format("pq1.414a{}zQY", max_volume), in, [&](tetgenmesh& m) {
    long clock_ticks = 0;
    m.recoverboundary(clock_ticks);
    m.carveholes();
    if (m.subvertstack->objects > 0) m.suppresssteinerpoints();
    m.recoverdelaunay();
    m.delaunayrefinement();
    m.optimizemesh();
    if (m.dupverts > 0 || m.unuverts > 0) m.jettisonnodes();
    m.outnodes(&out);
    if (m.tetrahedrons->items > 0) m.outelements(&out);
  });
}

}  // namespace

TetMesh tetgen_quality_mesh(const SurfaceMesh& surface, double max_volume, const std::string& file,
                            bool check_intersections) {
  tetgenio in, out;
  fill_tetgen_input(surface, in);
  try {
    if (check_intersections) check_self_intersections(in, file);
    mesh_volume(in, max_volume, out);
  } catch (int code) {
    throw InputError(file, "", "TetGen failed: " + tetgen_failure(code));
  }
  if (out.numberoftetrahedra <= 0) throw InputError(file, "", "TetGen produced no tets");

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

}  // namespace fissure::mesh_detail
