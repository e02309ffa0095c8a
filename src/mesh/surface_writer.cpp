#include "mesh/surface_writer.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <filesystem>
#include <ostream>

#include "io/atomic_file.hpp"
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

struct IntField {
  const char* name;
  const std::vector<std::int32_t>* values;
};

// An unstructured grid of `points` (xyz) and cells of `corners` points each (VTK type
// `vtk_type`), with per-cell `damage` and integer fields; binary, appended raw.
void write_cells_vtu(const std::string& path, const std::vector<double>& points,
                     const std::vector<std::int32_t>& connectivity, int corners,
                     std::uint8_t vtk_type, const std::vector<double>& damage,
                     const std::vector<IntField>& int_fields) {
  const std::size_t cells = connectivity.size() / corners;
  std::vector<std::int32_t> offsets(cells);
  for (std::size_t c = 0; c < cells; ++c) offsets[c] = static_cast<std::int32_t>((c + 1) * corners);
  const std::vector<std::uint8_t> types(cells, vtk_type);
  struct Block {
    const void* data;
    std::uint64_t bytes;
  };
  std::vector<Block> blocks;
  std::uint64_t offset = 0;
  std::string header = fmt::format(
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
      "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<UnstructuredGrid>\n"
      "<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n",
      points.size() / 3, cells);
  auto array = [&](const char* type, const char* name, int components, const void* data,
                   std::uint64_t bytes) {
    header += fmt::format(
        "<DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"appended\" "
        "offset=\"{}\"/>\n",
        type, name, components, offset);
    blocks.push_back({data, bytes});
    offset += sizeof(std::uint64_t) + bytes;
  };
  header += "<Points>\n";
  array("Float64", "position", 3, points.data(), points.size() * sizeof(double));
  header += "</Points>\n<Cells>\n";
  array("Int32", "connectivity", 1, connectivity.data(), connectivity.size() * 4);
  array("Int32", "offsets", 1, offsets.data(), offsets.size() * 4);
  array("UInt8", "types", 1, types.data(), types.size());
  header += "</Cells>\n<CellData>\n";
  array("Float64", "damage", 1, damage.data(), damage.size() * sizeof(double));
  for (const IntField& f : int_fields) array("Int32", f.name, 1, f.values->data(), cells * 4);
  header += "</CellData>\n</Piece>\n</UnstructuredGrid>\n<AppendedData encoding=\"raw\">\n_";
  write_atomically(path, [&](std::ostream& out) {
    out << header;
    for (const Block& b : blocks) {
      out.write(reinterpret_cast<const char*>(&b.bytes), sizeof(b.bytes));
      out.write(static_cast<const char*>(b.data), static_cast<std::streamsize>(b.bytes));
    }
    out << "\n</AppendedData>\n</VTKFile>\n";
  });
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
    write_cells_vtu(dir_ + "/" + name + ".vtu", c.points, c.triangles, 3, 5, cells.damage,
                    {{"body", &cells.body}, {"crack", &crack}});
    write_obj(dir_ + "/" + name + ".obj", c, s, time);
    surface_pvd_.add(time, name + ".vtu");
  }
  if (tets_) {
    std::vector<int> all(m.tet_count());
    for (int t = 0; t < m.tet_count(); ++t) all[t] = t;
    const CellArrays cells = cell_arrays(mesh, all, damage, body);
    const std::vector<std::int32_t> corners(m.mesh.tets.begin(), m.mesh.tets.end());
    const std::string name = fmt::format("tets_{:06d}.vtu", frame);
    write_cells_vtu(dir_ + "/" + name, m.position, corners, 4, 10, cells.damage,
                    {{"body", &cells.body}});
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

}  // namespace fissure
