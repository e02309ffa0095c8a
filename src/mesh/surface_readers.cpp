// read_surface: picks the parser from the file extension and validates the result.
#include <fmt/format.h>

#include "core/error.hpp"
#include "mesh/geometry.hpp"
#include "mesh/mesh_util.hpp"
#include "mesh/surface_formats.hpp"

namespace fissure {

SurfaceMesh read_surface(const std::string& path) {
  using namespace mesh_detail;
  const std::string ext = lowercase_extension(path);
  SurfaceMesh (*parse)(std::string_view, const std::string&) = nullptr;
  if (ext == ".obj") parse = parse_obj;
  if (ext == ".off") parse = parse_off;
  if (ext == ".stl") parse = parse_stl;
  if (ext == ".ply") parse = parse_ply;
  if (!parse) {
    throw InputError(path, "",
                     fmt::format("unsupported surface extension '{}' (supported: .obj, .stl, "
                                 ".off, .ply)",
                                 ext));
  }
  SurfaceMesh surface = parse(read_file(path), path);
  validate_surface(surface, path);
  if (ext == ".stl") {
    // STL repeats each triangle's corners: share them.
    weld_vertices(surface);
    validate_surface(surface, path);
  }
  return surface;
}

}  // namespace fissure
