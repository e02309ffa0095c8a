#pragma once
// `fissure info`: what a scene costs before running it.
#include "scene/config.hpp"

namespace fissure {

void print_info(const Config& config);

}  // namespace fissure
