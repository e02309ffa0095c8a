// TetGen .node/.ele pair: vertices and 4-node (or 10-node, corners kept) tets.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/error.hpp"
#include "mesh/geometry.hpp"
#include "mesh/mesh_util.hpp"
#include "mesh/tetgen_format.hpp"

namespace fissure {

namespace {

using mesh_detail::fail_at_line;
using mesh_detail::Line;

// Tets whose |volume| is below this fraction of (longest edge)^3 count as degenerate.
constexpr double kDegenerateRatio = 1e-12;

long long header_value(const Line& line, size_t k, long long fallback, const std::string& path,
                       const char* what) {
  if (k >= line.tokens.size()) return fallback;
  long long value;
  if (!mesh_detail::parse_int(line.tokens[k], value) || value < 0) {
    fail_at_line(path, line.number, fmt::format("invalid {} '{}'", what, line.tokens[k]));
  }
  return value;
}

// Header and body lines of `text`; throws if the header's count exceeds the lines present.
std::vector<Line> counted_lines(std::string_view text, const std::string& path, long long& count,
                                const char* what) {
  std::vector<Line> lines = mesh_detail::tokenized_lines(text, true);
  if (lines.empty()) throw InputError(path, "", "empty file");
  count = header_value(lines[0], 0, 0, path, "count");
  if (count == 0) throw InputError(path, "", fmt::format("no {}", what));
  if (count > static_cast<long long>(lines.size()) - 1) {
    throw InputError(path, "",
                     fmt::format("header claims {} {} but the file has only {} more lines", count,
                                 what, lines.size() - 1));
  }
  return lines;
}

// Returns the numbering base (0 or 1) of the node indices.
int read_nodes(std::string_view text, const std::string& path, std::vector<double>& vertices) {
  long long count;
  const std::vector<Line> lines = counted_lines(text, path, count, "nodes");
  if (header_value(lines[0], 1, 3, path, "dimension") != 3) {
    fail_at_line(path, lines[0].number, "dimension must be 3");
  }
  int base = 0;
  vertices.reserve(3 * count);
  for (long long i = 0; i < count; ++i) {
    const Line& line = lines[i + 1];
    long long index;
    if (line.tokens.size() < 4 || !mesh_detail::parse_int(line.tokens[0], index)) {
      fail_at_line(path, line.number, "node line needs an index and x y z");
    }
    if (i == 0) {
      if (index != 0 && index != 1)
        fail_at_line(path, line.number, "first node index must be 0 or 1");
      base = static_cast<int>(index);
    }
    if (index != base + i) {
      fail_at_line(path, line.number,
                   fmt::format("expected node index {}, found {}", base + i, index));
    }
    for (int k = 1; k <= 3; ++k) {
      double x;
      if (!mesh_detail::parse_double(line.tokens[k], x) || !std::isfinite(x)) {
        fail_at_line(path, line.number,
                     fmt::format("invalid or non-finite coordinate '{}'", line.tokens[k]));
      }
      vertices.push_back(x);
    }
  }
  return base;
}

// Fills `tets` (0-based) and the file's element numbers, for error messages.
void read_elements(std::string_view text, const std::string& path, int base, long long vertex_count,
                   std::vector<int>& tets, std::vector<long long>& numbers) {
  long long count;
  const std::vector<Line> lines = counted_lines(text, path, count, "tets");
  const long long corners = header_value(lines[0], 1, 4, path, "nodes per tet");
  if (corners != 4 && corners != 10)
    fail_at_line(path, lines[0].number, "nodes per tet must be 4 or 10");
  tets.reserve(4 * count);
  numbers.reserve(count);
  for (long long i = 0; i < count; ++i) {
    const Line& line = lines[i + 1];
    long long number;
    if (static_cast<long long>(line.tokens.size()) < 1 + corners ||
        !mesh_detail::parse_int(line.tokens[0], number)) {
      fail_at_line(path, line.number, fmt::format("tet line needs an index and {} nodes", corners));
    }
    numbers.push_back(number);
    for (int k = 1; k <= 4; ++k) {
      long long index;
      if (!mesh_detail::parse_int(line.tokens[k], index) || index < base ||
          index >= base + vertex_count) {
        fail_at_line(path, line.number,
                     fmt::format("node index '{}' out of range ({} to {})", line.tokens[k], base,
                                 base + vertex_count - 1));
      }
      tets.push_back(static_cast<int>(index - base));
    }
  }
}

double longest_edge(const std::vector<double>& v, const int* tet) {
  double longest = 0.0;
  for (int a = 0; a < 4; ++a) {
    for (int b = a + 1; b < 4; ++b) {
      const double* p = &v[3 * tet[a]];
      const double* q = &v[3 * tet[b]];
      longest = std::max(longest, std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]));
    }
  }
  return longest;
}

// Rejects degenerate tets; flips all tets if all are inverted, rejects a mix.
void orient(TetMesh& mesh, const std::vector<long long>& numbers, const std::string& path) {
  long long inverted = 0, first_inverted = -1;
  for (int t = 0; t < mesh.tet_count(); ++t) {
    const int* tet = &mesh.tets[4 * static_cast<size_t>(t)];
    const double volume = mesh_detail::tet_signed_volume(mesh.vertices.data(), tet);
    const double scale = std::pow(longest_edge(mesh.vertices, tet), 3);
    if (!(std::abs(volume) > kDegenerateRatio * scale)) {
      throw InputError(path, "", fmt::format("tet {} is degenerate (zero volume)", numbers[t]));
    }
    if (volume < 0.0 && inverted++ == 0) first_inverted = numbers[t];
  }
  if (inverted == mesh.tet_count()) {
    for (size_t t = 0; t < mesh.tets.size(); t += 4) std::swap(mesh.tets[t + 2], mesh.tets[t + 3]);
  } else if (inverted > 0) {
    throw InputError(path, "",
                     fmt::format("tet {} is inverted (negative volume) while {} of {} tets are "
                                 "positive",
                                 first_inverted, mesh.tet_count() - inverted, mesh.tet_count()));
  }
}

// Nodes first: a malformed .node is reported even when the .ele is missing. `ele_text()` gives
// the .ele contents (a string or string_view).
template <class EleText>
TetMesh parse_pair(std::string_view node_text, EleText&& ele_text, const std::string& node_path,
                   const std::string& ele_path) {
  TetMesh mesh;
  const int base = read_nodes(node_text, node_path, mesh.vertices);
  const auto ele = ele_text();
  std::vector<long long> numbers;
  read_elements(ele, ele_path, base, mesh.vertex_count(), mesh.tets, numbers);
  orient(mesh, numbers, ele_path);
  return mesh;
}

}  // namespace

TetMesh mesh_detail::parse_tetgen(std::string_view node_text, std::string_view ele_text,
                                  const std::string& node_path, const std::string& ele_path) {
  return parse_pair(
      node_text, [&] { return ele_text; }, node_path, ele_path);
}

TetMesh read_tetgen(const std::string& path) {
  const std::string ext = mesh_detail::lowercase_extension(path);
  const std::string base_name =
      ext == ".node" || ext == ".ele" ? path.substr(0, path.size() - ext.size()) : path;
  const std::string node_path = base_name + ".node";
  const std::string ele_path = base_name + ".ele";
  return parse_pair(
      mesh_detail::read_file(node_path), [&] { return mesh_detail::read_file(ele_path); },
      node_path, ele_path);
}

}  // namespace fissure
