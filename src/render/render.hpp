#pragma once
// `fissure render RUN_DIR`: a run's frames to PNG pictures (POV-Ray) and an animation
// (ImageMagick's convert for GIF, ffmpeg for MP4), written to RUN_DIR/render/ or the folder
// --out names.
#include <string>

#include "scene/render_settings.hpp"

namespace fissure {

struct RenderSummary {
  int frames = 0;         // pictures written
  std::string folder;     // where they are
  std::string animation;  // path of the animation, or "" with animation: none
  double seconds = 0;
};

// Renders the frames of the run in `run_dir` into `folder` ("": run_dir/render). Throws
// InputError for a missing folder or frames, RunError when a program is missing or fails (the
// message names the Debian package to install).
RenderSummary render_run(const std::string& run_dir, const RenderSettings& settings,
                         const std::string& folder, bool progress);

}  // namespace fissure
