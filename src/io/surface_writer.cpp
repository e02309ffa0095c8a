#include "io/surface_writer.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <filesystem>
#include <ostream>

#include "io/atomic_file.hpp"
#include "io/vtu_writer.hpp"
#include "mesh/surface_extract.hpp"

namespace fissure {

namespace {

struct CellArrays {
  std::vector<double> damage;
  std::vector<std::int32_t> body;
};

// φ and body of the particle of each listed tet.
CellArrays cell_arrays(const EmbeddedMesh& mesh, const std::vector<int>& tets,
                       const std::vector<double>& damage, const std::vector<int>& body) {
  CellArrays a;
  a.damage.reserve(tets.size());
  a.body.reserve(tets.size());
  for (int t : tets) {
    const int p = mesh.particle()[t];
    a.damage.push_back(damage.empty() ? 0.0 : damage[p]);
    a.body.push_back(body[p]);
  }
  return a;
}

VtuArray damage_array(const CellArrays& a) {
  return {"Float64", "damage", 1, a.damage.data(), a.damage.size() * sizeof(double)};
}

VtuArray int_array(const char* name, const std::vector<std::int32_t>& values) {
  return {"Int32", name, 1, values.data(), values.size() * sizeof(std::int32_t)};
}

// The surface's vertices renumbered 0.. in order of first use.
struct CompactSurface {
  std::vector<double> points;
  std::vector<std::int32_t> triangles;
};

CompactSurface compact(const SplitMesh& mesh, const BoundarySurface& s) {
  CompactSurface c;
  std::vector<std::int32_t> index(mesh.vertex_count(), -1);
  c.triangles.reserve(s.triangles.size());
  for (int v : s.triangles) {
    if (index[v] < 0) {
      index[v] = static_cast<std::int32_t>(c.points.size() / 3);
      for (int k = 0; k < 3; ++k)
        c.points.push_back(mesh.position[3 * static_cast<std::size_t>(v) + k]);
    }
    c.triangles.push_back(index[v]);
  }
  return c;
}

// Wavefront OBJ: the original surface in group `boundary`, the crack faces in group `crack`.
void write_obj(const std::string& path, const CompactSurface& c, const BoundarySurface& s,
               double time) {
  write_atomically(path, [&](std::ostream& out) {
    out << fmt::format("# Fissure embedded-mesh surface at t = {:.9g} s\n", time);
    for (std::size_t v = 0; v < c.points.size(); v += 3)
      out << fmt::format("v {:.9g} {:.9g} {:.9g}\n", c.points[v], c.points[v + 1], c.points[v + 2]);
    for (int group = 0; group < 2; ++group) {
      out << (group == 0 ? "g boundary\n" : "g crack\n");
      for (int f = 0; f < s.triangle_count(); ++f)
        if (s.crack[f] == group)
          out << fmt::format("f {} {} {}\n", c.triangles[3 * f] + 1, c.triangles[3 * f + 1] + 1,
                             c.triangles[3 * f + 2] + 1);
    }
  });
}

}  // namespace

SurfaceWriter::SurfaceWriter(std::string dir, bool surface, bool tets)
    : dir_(std::move(dir)),
      surface_(surface),
      tets_(tets),
      surface_pvd_(dir_ + "/surface.pvd"),
      tets_pvd_(dir_ + "/tets.pvd") {}

void SurfaceWriter::write(int frame, double time, const EmbeddedMesh& mesh,
                          const std::vector<double>& damage, const std::vector<int>& body) {
  const SplitMesh& m = mesh.mesh();
  if (surface_) {
    const BoundarySurface s = extract_boundary(m);
    const CompactSurface c = compact(m, s);
    const CellArrays cells = cell_arrays(mesh, s.tet, damage, body);
    const std::vector<std::int32_t> crack(s.crack.begin(), s.crack.end());
    const std::string name = fmt::format("surface_{:06d}", frame);
    write_vtu(dir_ + "/" + name + ".vtu", c.points, c.triangles, 3, 5 /* VTK_TRIANGLE */, {},
              {damage_array(cells), int_array("body", cells.body), int_array("crack", crack)});
    write_obj(dir_ + "/" + name + ".obj", c, s, time);
    surface_pvd_.add(time, name + ".vtu");
  }
  if (tets_) {
    std::vector<int> all(m.tet_count());
    for (int t = 0; t < m.tet_count(); ++t) all[t] = t;
    const CellArrays cells = cell_arrays(mesh, all, damage, body);
    const std::vector<std::int32_t> corners(m.mesh.tets.begin(), m.mesh.tets.end());
    const std::string name = fmt::format("tets_{:06d}.vtu", frame);
    write_vtu(dir_ + "/" + name, m.position, corners, 4, 10 /* VTK_TETRA */, {},
              {damage_array(cells), int_array("body", cells.body)});
    tets_pvd_.add(time, name);
  }
}

void remove_surface_output(const std::string& dir) {
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    const std::string ext = entry.path().extension().string();
    const bool frame = (name.rfind("surface_", 0) == 0 && (ext == ".vtu" || ext == ".obj")) ||
                       (name.rfind("tets_", 0) == 0 && ext == ".vtu");
    if (frame || name == "surface.pvd" || name == "tets.pvd") std::filesystem::remove(entry.path());
  }
}

void SurfaceWriter::reset(const std::vector<double>& times) {
  std::vector<std::pair<double, std::string>> surface, tets;
  for (std::size_t k = 0; k < times.size(); ++k) {
    surface.emplace_back(times[k], fmt::format("surface_{:06d}.vtu", k));
    tets.emplace_back(times[k], fmt::format("tets_{:06d}.vtu", k));
  }
  if (surface_) surface_pvd_.reset(surface);
  if (tets_) tets_pvd_.reset(tets);
}

}  // namespace fissure
