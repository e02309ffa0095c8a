#include "io/vtu_reader.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/error.hpp"

namespace fissure {

namespace {

// The value of attribute `name` in the XML tag `tag`, or "".
std::string attribute(const std::string& tag, const std::string& name) {
  const std::string key = " " + name + "=\"";
  const auto start = tag.find(key);
  if (start == std::string::npos) return "";
  const auto begin = start + key.size();
  const auto end = tag.find('"', begin);
  return end == std::string::npos ? "" : tag.substr(begin, end - begin);
}

template <typename T>
void convert(const char* data, std::uint64_t bytes, std::vector<double>& out) {
  const std::size_t n = bytes / sizeof(T);
  out.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    T v;
    std::memcpy(&v, data + i * sizeof(T), sizeof(T));
    out[i] = static_cast<double>(v);
  }
}

class Reader {
 public:
  Reader(std::string path, std::string content)
      : path_(std::move(path)), content_(std::move(content)) {}

  VtuGrid read() {
    const auto appended = content_.find("<AppendedData");
    if (appended == std::string::npos) fail("no <AppendedData> section (only appended raw VTU)");
    const std::string appended_tag =
        content_.substr(appended, content_.find('>', appended) - appended);
    if (attribute(appended_tag, "encoding") != "raw") fail("appended data is not encoding=\"raw\"");
    data_ = content_.find('_', appended + appended_tag.size());
    if (data_ == std::string::npos) fail("no '_' marker before the appended data");
    ++data_;
    const std::string header = content_.substr(0, appended);
    if (header.find("compressor=") != std::string::npos) fail("compressed VTU is not supported");
    if (header.find("byte_order=\"BigEndian\"") != std::string::npos)
      fail("big-endian VTU is not supported");
    wide_headers_ = header.find("header_type=\"UInt64\"") != std::string::npos;
    VtuGrid grid;
    std::string section;
    for (std::size_t pos = header.find('<'); pos != std::string::npos;
         pos = header.find('<', pos + 1)) {
      const std::string tag = header.substr(pos, header.find('>', pos) - pos + 1);
      for (const char* s : {"Points", "Cells", "PointData", "CellData"})
        if (tag.rfind(std::string("<") + s, 0) == 0 &&
            (tag[std::strlen(s) + 1] == '>' || tag[std::strlen(s) + 1] == ' '))
          section = s;
      if (tag.rfind("<DataArray", 0) != 0) continue;
      VtuArray array;
      const std::string components = attribute(tag, "NumberOfComponents");
      array.components = components.empty() ? 1 : std::stoi(components);
      array.values = block(tag);
      const std::string name = attribute(tag, "Name");
      if (section == "Points") {
        if (array.components != 3) fail("points need 3 components");
        grid.points = std::move(array.values);
      } else if (section == "Cells") {
        std::vector<long>* target = name == "connectivity" ? &grid.connectivity
                                    : name == "offsets"    ? &grid.offsets
                                                           : nullptr;
        if (target) target->assign(array.values.begin(), array.values.end());
      } else if (section == "PointData") {
        grid.point_data[name] = std::move(array);
      }
    }
    for (const auto& [name, array] : grid.point_data)
      if (array.values.size() != static_cast<std::size_t>(array.components * grid.point_count()))
        fail(fmt::format("point array '{}' has {} values for {} points", name, array.values.size(),
                         grid.point_count()));
    return grid;
  }

 private:
  [[noreturn]] void fail(const std::string& reason) const { throw InputError(path_, "", reason); }

  std::vector<double> block(const std::string& tag) {
    if (attribute(tag, "format") != "appended") fail("every DataArray must be format=\"appended\"");
    const std::size_t at = data_ + std::stoull(attribute(tag, "offset"));
    const std::size_t header_bytes = wide_headers_ ? 8 : 4;
    if (at + header_bytes > content_.size()) fail("truncated appended data");
    std::uint64_t bytes = 0;
    std::memcpy(&bytes, content_.data() + at, header_bytes);
    if (at + header_bytes + bytes > content_.size()) fail("truncated appended data");
    const char* p = content_.data() + at + header_bytes;
    const std::string type = attribute(tag, "type");
    std::vector<double> out;
    if (type == "Float64")
      convert<double>(p, bytes, out);
    else if (type == "Float32")
      convert<float>(p, bytes, out);
    else if (type == "Int64")
      convert<std::int64_t>(p, bytes, out);
    else if (type == "Int32")
      convert<std::int32_t>(p, bytes, out);
    else if (type == "UInt8")
      convert<std::uint8_t>(p, bytes, out);
    else
      fail(fmt::format("unsupported DataArray type '{}'", type));
    return out;
  }

  std::string path_, content_;
  std::size_t data_ = 0;
  bool wide_headers_ = false;
};

}  // namespace

namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot open the frame");
  std::stringstream content;
  content << in.rdbuf();
  return content.str();
}

// Appends `piece` to `grid`: its points after the grid's, its cells renumbered to them.
void append(VtuGrid& grid, const VtuGrid& piece, const std::string& path) {
  const long shift = grid.point_count();
  const long cell_shift = grid.connectivity.size();
  grid.points.insert(grid.points.end(), piece.points.begin(), piece.points.end());
  for (const long c : piece.connectivity) grid.connectivity.push_back(c + shift);
  for (const long o : piece.offsets) grid.offsets.push_back(o + cell_shift);
  for (const auto& [name, array] : piece.point_data) {
    VtuArray& into = grid.point_data[name];
    if (shift > 0 && (into.values.size() != std::size_t(shift) * into.components ||
                      into.components != array.components))
      throw InputError(path, "", fmt::format("its pieces disagree on the point data '{}'", name));
    into.components = array.components;
    into.values.insert(into.values.end(), array.values.begin(), array.values.end());
  }
}

// A .pvtu: its pieces (Piece Source, relative to it) read and joined in order.
VtuGrid read_pieces(const std::string& path, const std::string& content) {
  VtuGrid grid;
  const auto slash = path.find_last_of('/');
  const std::string folder = slash == std::string::npos ? "" : path.substr(0, slash + 1);
  int pieces = 0;
  for (auto at = content.find("<Piece"); at != std::string::npos;
       at = content.find("<Piece", at + 1)) {
    const std::string source = attribute(content.substr(at, content.find('>', at) - at), "Source");
    if (source.empty()) throw InputError(path, "", "a Piece without a Source");
    const std::string piece = folder + source;
    append(grid, Reader(piece, slurp(piece)).read(), path);
    ++pieces;
  }
  if (pieces == 0) throw InputError(path, "", "lists no piece");
  return grid;
}

}  // namespace

VtuGrid read_vtu(const std::string& path) {
  const std::string content = slurp(path);
  if (path.size() > 5 && path.compare(path.size() - 5, 5, ".pvtu") == 0)
    return read_pieces(path, content);
  return Reader(path, content).read();
}

}  // namespace fissure
