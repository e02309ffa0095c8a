#pragma once
// The frames of a run's output folder, from its particles.pvd index, each with the surface file
// written beside it (surface_NNNNNN.obj or .vtu), if any.
#include <string>
#include <vector>

namespace fissure {

struct FrameFiles {
  double time = 0;
  std::string stem;       // "particles_000012": names the picture
  std::string particles;  // path of the particle VTU
  std::string surface;    // path of the surface OBJ or VTU, or ""
};

// Throws InputError when the folder or its index is missing or lists no frame.
std::vector<FrameFiles> list_frames(const std::string& out_dir);

}  // namespace fissure
