#pragma once
// Parsers for the surface file formats; `path` is only used in error messages.
#include <string>
#include <string_view>

#include "mesh/tet_mesh.hpp"

namespace fissure::mesh_detail {

SurfaceMesh parse_obj(std::string_view text, const std::string& path);
SurfaceMesh parse_off(std::string_view text, const std::string& path);
SurfaceMesh parse_stl(std::string_view data, const std::string& path);
SurfaceMesh parse_ply(std::string_view data, const std::string& path);

}  // namespace fissure::mesh_detail
