// libFuzzer target: a TetGen .node/.ele pair through mesh_detail::parse_tetgen. The input holds
// the .node text, the separator line, then the .ele text (no separator: the .ele text is empty).
// An InputError is the expected rejection; any other exception, crash, sanitizer report, hang or
// a returned mesh with an out-of-range index or a non-positive tet is a finding.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "core/error.hpp"
#include "mesh/mesh_util.hpp"
#include "mesh/tetgen_format.hpp"

namespace {

constexpr std::string_view kSeparator = "\n=== ele ===\n";

void check_mesh(const fissure::TetMesh& mesh) {
  for (int index : mesh.tets)
    if (index < 0 || index >= mesh.vertex_count()) __builtin_trap();
  for (size_t t = 0; t < mesh.tets.size(); t += 4)
    if (!(fissure::mesh_detail::tet_signed_volume(mesh.vertices.data(), &mesh.tets[t]) > 0.0))
      __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const size_t split = bytes.find(kSeparator);
  const std::string_view node = bytes.substr(0, split);
  const std::string_view ele = split == std::string_view::npos
                                   ? std::string_view()
                                   : bytes.substr(split + kSeparator.size());
  try {
    check_mesh(fissure::mesh_detail::parse_tetgen(node, ele, "fuzz/mesh.node", "fuzz/mesh.ele"));
  } catch (const fissure::InputError&) {
  }
  return 0;
}
