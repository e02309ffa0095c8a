// STL, binary (80-byte header, uint32 count, 50-byte records) or ASCII (solid/facet/vertex).
#include <fmt/format.h>

#include <bit>
#include <cstdint>
#include <cstring>

#include "core/error.hpp"
#include "mesh/mesh_util.hpp"
#include "mesh/surface_formats.hpp"

namespace fissure::mesh_detail {

namespace {

static_assert(std::endian::native == std::endian::little, "binary readers assume little endian");

constexpr size_t kHeaderBytes = 84;
constexpr size_t kRecordBytes = 50;

uint32_t binary_count(std::string_view data) {
  uint32_t count;
  std::memcpy(&count, data.data() + 80, sizeof count);
  return count;
}

SurfaceMesh parse_binary(std::string_view data) {
  const uint32_t count = binary_count(data);
  SurfaceMesh s;
  s.vertices.reserve(9 * size_t{count});
  s.triangles.reserve(3 * size_t{count});
  for (size_t t = 0; t < count; ++t) {
    // Skip the 12-byte normal; the 2-byte attribute follows the corners.
    const char* record = data.data() + kHeaderBytes + t * kRecordBytes + 12;
    for (int k = 0; k < 9; ++k) {
      float x;
      std::memcpy(&x, record + 4 * k, sizeof x);
      s.vertices.push_back(x);
    }
    for (int k = 0; k < 3; ++k) s.triangles.push_back(static_cast<int>(3 * t + k));
  }
  return s;
}

SurfaceMesh parse_ascii(std::string_view text, const std::string& path) {
  SurfaceMesh s;
  int corners = 0;
  for (const Line& line : tokenized_lines(text, false)) {
    const std::string_view key = line.tokens[0];
    if (key == "vertex") {
      append_vertex(line, path, s.vertices);
      ++corners;
    } else if (key == "endfacet") {
      if (corners != 3) {
        fail_at_line(path, line.number, fmt::format("facet has {} vertices, expected 3", corners));
      }
      const int first = static_cast<int>(s.vertices.size() / 3) - 3;
      s.triangles.insert(s.triangles.end(), {first, first + 1, first + 2});
      corners = 0;
    } else if (key != "solid" && key != "facet" && key != "outer" && key != "endloop" &&
               key != "endsolid") {
      fail_at_line(path, line.number, fmt::format("unexpected keyword '{}'", key));
    }
  }
  return s;
}

}  // namespace

SurfaceMesh parse_stl(std::string_view data, const std::string& path) {
  // A binary file whose size matches its triangle count is binary even if it starts with "solid".
  if (data.size() >= kHeaderBytes &&
      data.size() == kHeaderBytes + kRecordBytes * uint64_t{binary_count(data)}) {
    return parse_binary(data);
  }
  // Text never holds NUL bytes; binary counts and coordinates almost always do.
  const size_t start = data.find_first_not_of(" \t\r\n");
  if (start != std::string_view::npos && data.substr(start).starts_with("solid") &&
      data.find('\0') == std::string_view::npos) {
    return parse_ascii(data, path);
  }
  if (data.size() < kHeaderBytes) {
    throw InputError(
        path, "",
        fmt::format("too short for a binary STL ({} bytes) and not ASCII STL", data.size()));
  }
  const uint32_t count = binary_count(data);
  throw InputError(path, "",
                   fmt::format("binary STL header claims {} triangles, which need {} bytes, but "
                               "the file has {} bytes",
                               count, kHeaderBytes + kRecordBytes * uint64_t{count}, data.size()));
}

}  // namespace fissure::mesh_detail
