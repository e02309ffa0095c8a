// libFuzzer target: .ply bytes through mesh_detail::parse_ply and read_surface's checks.
#include "surface_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return fissure::fuzz::run_surface_parser(fissure::mesh_detail::parse_ply, data, size,
                                           "fuzz/mesh.ply");
}
