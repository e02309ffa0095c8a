// Wavefront .obj: `v x y z` and `f i j k ...` (with optional /vt/vn, negative = relative).
#include <fmt/format.h>

#include "mesh/mesh_util.hpp"
#include "mesh/surface_formats.hpp"

namespace fissure::mesh_detail {

SurfaceMesh parse_obj(std::string_view text, const std::string& path) {
  SurfaceMesh s;
  std::vector<int> polygon;
  for (const Line& line : tokenized_lines(text, true)) {
    const std::string_view key = line.tokens[0];
    if (key == "v") {
      append_vertex(line, path, s.vertices);
    } else if (key == "f") {
      const long long defined = static_cast<long long>(s.vertices.size() / 3);
      polygon.clear();
      for (size_t k = 1; k < line.tokens.size(); ++k) {
        const std::string_view token = line.tokens[k].substr(0, line.tokens[k].find('/'));
        long long index;
        if (!parse_int(token, index) || index == 0) {
          fail_at_line(path, line.number, fmt::format("invalid vertex index '{}'", token));
        }
        const long long zero_based = index < 0 ? defined + index : index - 1;
        if (zero_based < 0 || zero_based >= defined) {
          fail_at_line(path, line.number,
                       fmt::format("vertex index {} out of range ({} vertices defined so far)",
                                   index, defined));
        }
        polygon.push_back(static_cast<int>(zero_based));
      }
      if (polygon.size() < 3) fail_at_line(path, line.number, "face needs at least 3 vertices");
      for (size_t k = 1; k + 1 < polygon.size(); ++k) {
        s.triangles.insert(s.triangles.end(), {polygon[0], polygon[k], polygon[k + 1]});
      }
    }
  }
  return s;
}

}  // namespace fissure::mesh_detail
