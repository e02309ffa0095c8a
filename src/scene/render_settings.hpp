#pragma once
// How `fissure render` draws a run: the optional `render:` block of a scene file
// (docs/config.md), overridable from the command line.
#include <array>
#include <string>
#include <vector>

namespace fissure {

struct RenderSettings {
  std::string field = "damage";  // damage, velocity, displacement or dilatation
  bool camera_given = false;     // false: derived from the run's bounds
  std::array<double, 3> camera_position{};
  std::array<double, 3> look_at{};
  double view_angle = 35;  // horizontal field of view, degrees
  int width = 800, height = 600;
  bool range_given = false;  // false: the field's range over all frames
  double range_min = 0, range_max = 1;
  double particle_radius = 0;     // sphere radius [m]; 0: from the particle spacing
  int every = 1;                  // render every n-th frame
  std::string animation = "gif";  // gif, mp4 or none
  double fps = 10;                // animation frames per second
  std::string show = "auto";      // auto (surface if written, else particles), particles, surface
};

// The settings for `fissure render`: the `render:` block of `config_path` when one is given
// (with `overrides` applied to the whole scene file), else the defaults with `overrides`, which
// may then only set render.* keys. Throws InputError.
RenderSettings load_render_settings(const std::string& config_path,
                                    const std::vector<std::string>& overrides);

}  // namespace fissure
