#pragma once
// Pre-cracks: which bonds cross a crack surface (the thin sheet of Figure 17 starts cracked).
#include "scene/config.hpp"

namespace fissure {

// True if the segment from a to b crosses `crack`: it changes side of the plane (at a point
// inside the plane's region, when bounded), or it meets the box.
bool crosses(const Crack& crack, const double* a, const double* b);

}  // namespace fissure
