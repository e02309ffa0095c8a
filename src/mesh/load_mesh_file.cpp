// load_mesh_file: TetGen files are read as they are, surfaces are tetrahedralized.
#include <fmt/format.h>

#include <filesystem>

#include "core/error.hpp"
#include "mesh/geometry.hpp"
#include "mesh/mesh_util.hpp"

namespace fissure {

TetMesh load_mesh_file(const std::string& path, double edge_length) {
  const std::string ext = mesh_detail::lowercase_extension(path);
  // A TetGen pair may be named by its base name, which can itself contain a dot.
  if (ext == ".node" || ext == ".ele" || std::filesystem::exists(path + ".node"))
    return read_tetgen(path);
  if (ext == ".obj" || ext == ".stl" || ext == ".off" || ext == ".ply") {
    return tetrahedralize_surface(read_surface(path), edge_length, path);
  }
  throw InputError(path, "",
                   fmt::format("unsupported mesh file extension '{}' (supported: .obj, .stl, .off, "
                               ".ply, .node, .ele)",
                               ext));
}

}  // namespace fissure
