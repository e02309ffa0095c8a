#pragma once
// Shared body of the surface-format fuzz targets: parse, then the checks and welding that
// read_surface applies. An InputError is the expected rejection of bad input; any other
// exception, crash, sanitizer report or hang is a finding.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "core/error.hpp"
#include "mesh/mesh_util.hpp"
#include "mesh/surface_formats.hpp"

namespace fissure::fuzz {

using SurfaceParser = SurfaceMesh (*)(std::string_view, const std::string&);

inline int run_surface_parser(SurfaceParser parse, const uint8_t* data, size_t size,
                              const std::string& path) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    SurfaceMesh surface = parse(bytes, path);
    mesh_detail::validate_surface(surface, path);
    mesh_detail::weld_vertices(surface);
    mesh_detail::validate_surface(surface, path);
  } catch (const InputError&) {
  }
  return 0;
}

}  // namespace fissure::fuzz
