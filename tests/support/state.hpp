#pragma once
// The state a scene starts from when nothing has moved yet.
#include <vector>

#include "integrators/integrator.hpp"

namespace fissure::test {

// The particles' reference positions at rest, at time 0.
inline State at_rest(const Particles& p) {
  return {p.reference, std::vector<double>(p.reference.size(), 0.0), 0.0};
}

}  // namespace fissure::test
