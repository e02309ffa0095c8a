#include "io/vtu_writer.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <ostream>

#include "io/atomic_file.hpp"

namespace fissure {

namespace {

struct Block {
  const void* data;
  std::uint64_t bytes;
};

}  // namespace

void write_vtu(const std::string& path, const std::vector<double>& points,
               const std::vector<std::int32_t>& connectivity, int corners, std::uint8_t vtk_type,
               const std::vector<VtuArray>& point_data, const std::vector<VtuArray>& cell_data) {
  const std::size_t cells = connectivity.size() / corners;
  std::vector<std::int32_t> offsets(cells);
  for (std::size_t c = 0; c < cells; ++c) offsets[c] = static_cast<std::int32_t>((c + 1) * corners);
  const std::vector<std::uint8_t> types(cells, vtk_type);
  std::vector<Block> blocks;
  std::uint64_t offset = 0;
  std::string header = fmt::format(
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
      "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<UnstructuredGrid>\n"
      "<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n",
      points.size() / 3, cells);
  auto array = [&](const VtuArray& a) {
    header += fmt::format(
        "<DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"appended\" "
        "offset=\"{}\"/>\n",
        a.type, a.name, a.components, offset);
    blocks.push_back({a.data, a.bytes});
    offset += sizeof(std::uint64_t) + a.bytes;
  };
  header += "<Points>\n";
  array({"Float64", "position", 3, points.data(), points.size() * sizeof(double)});
  header += "</Points>\n<Cells>\n";
  array({"Int32", "connectivity", 1, connectivity.data(), connectivity.size() * 4});
  array({"Int32", "offsets", 1, offsets.data(), offsets.size() * 4});
  array({"UInt8", "types", 1, types.data(), types.size()});
  header += "</Cells>\n<PointData>\n";
  for (const auto& a : point_data) array(a);
  header += "</PointData>\n<CellData>\n";
  for (const auto& a : cell_data) array(a);
  header += "</CellData>\n</Piece>\n</UnstructuredGrid>\n<AppendedData encoding=\"raw\">\n_";
  write_atomically(path, [&](std::ostream& out) {
    out << header;
    for (const auto& b : blocks) {
      out.write(reinterpret_cast<const char*>(&b.bytes), sizeof(b.bytes));
      out.write(static_cast<const char*>(b.data), static_cast<std::streamsize>(b.bytes));
    }
    out << "\n</AppendedData>\n</VTKFile>\n";
  });
}

void write_particles_vtu(const std::string& path, const std::vector<double>& points,
                         const std::vector<PointField>& fields, const std::vector<int>* body_id) {
  const std::size_t n = points.size() / 3;
  std::vector<std::int32_t> connectivity(n);
  for (std::size_t i = 0; i < n; ++i) connectivity[i] = static_cast<std::int32_t>(i);
  std::vector<VtuArray> point_data;
  for (const auto& f : fields)
    point_data.push_back(
        {"Float64", f.name, f.components, f.values->data(), f.values->size() * sizeof(double)});
  if (body_id)
    point_data.push_back({"Int32", "body", 1, body_id->data(), body_id->size() * sizeof(int)});
  write_vtu(path, points, connectivity, 1, 1 /* VTK_VERTEX */, point_data, {});
}

void write_particles_pvtu(const std::string& path, const std::vector<std::string>& pieces,
                          const std::vector<PointField>& fields, bool body_id) {
  write_atomically(path, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" "
           "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
           "<PUnstructuredGrid GhostLevel=\"0\">\n<PPoints>\n"
           "<PDataArray type=\"Float64\" Name=\"position\" NumberOfComponents=\"3\"/>\n"
           "</PPoints>\n<PPointData>\n";
    for (const auto& f : fields)
      out << fmt::format("<PDataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\"/>\n",
                         f.name, f.components);
    if (body_id) out << "<PDataArray type=\"Int32\" Name=\"body\" NumberOfComponents=\"1\"/>\n";
    out << "</PPointData>\n";
    for (const auto& piece : pieces) out << fmt::format("<Piece Source=\"{}\"/>\n", piece);
    out << "</PUnstructuredGrid>\n</VTKFile>\n";
  });
}

void PvdIndex::add(double time, const std::string& relative_file) {
  frames_.emplace_back(time, relative_file);
  write();
}

void PvdIndex::reset(std::vector<std::pair<double, std::string>> frames) {
  frames_ = std::move(frames);
  write();
}

void PvdIndex::write() const {
  write_atomically(path_, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
    for (const auto& [t, file] : frames_)
      out << fmt::format("<DataSet timestep=\"{:.9g}\" part=\"0\" file=\"{}\"/>\n", t, file);
    out << "</Collection>\n</VTKFile>\n";
  });
}

}  // namespace fissure
