// Object File Format .off: header, counts, one vertex per line, then `k i0 ... ik-1` faces.
#include <fmt/format.h>

#include "core/error.hpp"
#include "mesh/mesh_util.hpp"
#include "mesh/surface_formats.hpp"

namespace fissure::mesh_detail {

namespace {

// OFF and its variants with per-vertex extras after xyz (COFF, NOFF, STOFF, ...).
bool is_off_keyword(std::string_view token) {
  if (!token.ends_with("OFF")) return false;
  token.remove_suffix(3);
  return token.find_first_not_of("STCN") == std::string_view::npos;
}

long long count_at(const Line& line, size_t k, const std::string& path, const char* what) {
  long long value;
  if (k >= line.tokens.size() || !parse_int(line.tokens[k], value) || value < 0) {
    fail_at_line(path, line.number, fmt::format("missing or invalid {} count", what));
  }
  return value;
}

}  // namespace

SurfaceMesh parse_off(std::string_view text, const std::string& path) {
  const std::vector<Line> lines = tokenized_lines(text, true);
  if (lines.empty() || !is_off_keyword(lines[0].tokens[0])) {
    throw InputError(path, "", "missing OFF header");
  }
  // Counts follow the keyword on the same line or on the next.
  const bool counts_below = lines[0].tokens.size() == 1;
  if (counts_below && lines.size() < 2) {
    throw InputError(path, "", "missing vertex and face counts");
  }
  const Line& counts = lines[counts_below ? 1 : 0];
  const size_t first = counts_below ? 0 : 1;
  size_t next = counts_below ? 2 : 1;
  const long long vertex_count = count_at(counts, first, path, "vertex");
  const long long face_count = count_at(counts, first + 1, path, "face");
  const long long available = static_cast<long long>(lines.size() - next);
  if (vertex_count > available || face_count > available - vertex_count) {
    throw InputError(path, "",
                     fmt::format("header claims {} vertices and {} faces but the file has only {} "
                                 "more lines",
                                 vertex_count, face_count, available));
  }

  SurfaceMesh s;
  s.vertices.reserve(3 * vertex_count);
  for (long long i = 0; i < vertex_count; ++i) {
    const Line& line = lines[next++];
    if (line.tokens.size() < 3) fail_at_line(path, line.number, "vertex needs x y z");
    for (int k = 0; k < 3; ++k) {
      double x;
      if (!parse_double(line.tokens[k], x)) {
        fail_at_line(path, line.number, fmt::format("invalid number '{}'", line.tokens[k]));
      }
      s.vertices.push_back(x);
    }
  }
  for (long long f = 0; f < face_count; ++f) {
    const Line& line = lines[next++];
    const long long corners = count_at(line, 0, path, "face vertex");
    if (corners < 3) fail_at_line(path, line.number, "face needs at least 3 vertices");
    if (static_cast<long long>(line.tokens.size()) < 1 + corners) {
      fail_at_line(path, line.number, fmt::format("face lists fewer than {} vertices", corners));
    }
    std::vector<int> polygon(corners);
    for (long long k = 0; k < corners; ++k) {
      long long index;
      if (!parse_int(line.tokens[1 + k], index) || index < 0 || index >= vertex_count) {
        fail_at_line(path, line.number,
                     fmt::format("vertex index '{}' out of range (0 to {})", line.tokens[1 + k],
                                 vertex_count - 1));
      }
      polygon[k] = static_cast<int>(index);
    }
    for (long long k = 1; k + 1 < corners; ++k) {
      s.triangles.insert(s.triangles.end(), {polygon[0], polygon[k], polygon[k + 1]});
    }
  }
  return s;
}

}  // namespace fissure::mesh_detail
