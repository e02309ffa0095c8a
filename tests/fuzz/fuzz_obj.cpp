// libFuzzer target: .obj bytes through mesh_detail::parse_obj and read_surface's checks.
#include "surface_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return fissure::fuzz::run_surface_parser(fissure::mesh_detail::parse_obj, data, size,
                                           "fuzz/mesh.obj");
}
