#pragma once
// `fissure render OUT_DIR`: a run's frames to PNG pictures (POV-Ray) and an animation
// (ImageMagick's convert for GIF, ffmpeg for MP4), written to OUT_DIR/render/.
#include <string>

#include "render/render_settings.hpp"

namespace fissure {

struct RenderSummary {
  int frames = 0;         // pictures written
  std::string folder;     // where they are
  std::string animation;  // path of the animation, or "" with animation: none
  double seconds = 0;
};

// Throws InputError for a missing folder or frames, RunError when a program is missing or fails
// (the message names the Debian package to install).
RenderSummary render_run(const std::string& out_dir, const RenderSettings& settings, bool progress);

}  // namespace fissure
