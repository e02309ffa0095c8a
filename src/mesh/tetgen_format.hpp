#pragma once
// Parser for a TetGen .node/.ele pair held in memory; the paths are only used in error messages.
#include <string>
#include <string_view>

#include "mesh/tet_mesh.hpp"

namespace fissure::mesh_detail {

// Vertices and 4-node (or 10-node, corners kept) tets, positively oriented. Throws InputError
// naming the file, line and reason for malformed, degenerate or mixed-orientation input.
TetMesh parse_tetgen(std::string_view node_text, std::string_view ele_text,
                     const std::string& node_path, const std::string& ele_path);

}  // namespace fissure::mesh_detail
