#pragma once
// A loaded scene: the config plus the particles and families sampled from it.
#include <vector>

#include "scene/config.hpp"
#include "scene/particles.hpp"

namespace fissure {

struct Scene {
  Config config;
  Particles particles;
  Families families;
  std::vector<double> horizon_of_body;  // δ in metres, per body
};

// Samples every body into particles (one per tet at its barycentre, paper §5.2, or read from a
// points file) and builds the families. Throws InputError for unusable geometry.
Scene build_scene(const Config& config);

}  // namespace fissure
