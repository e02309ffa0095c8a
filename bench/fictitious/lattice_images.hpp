#pragma once
// For bench_fictitious_particles: fictitious particles on a cubic lattice instead of mirror
// images (model/fictitious_particles.hpp), to compare.
#include <array>
#include <vector>

#include "model/fictitious_particles.hpp"
#include "scene/particles.hpp"

namespace fissure::bench {

// An axis-aligned box and the faces of it that are free, as (axis, 0 for min or 1 for max).
struct BoxFaces {
  std::array<double, 3> min, max;
  std::vector<std::array<int, 2>> free;
};

// The two triangles of each free face.
std::vector<Triangle> free_face_triangles(const BoxFaces& box);

// The points of a cubic lattice of the particles' mean spacing (V̄^⅓, each of volume V̄) outside
// the box beyond its free faces only, within δ of the box and no closer than half the spacing
// to a particle, as fictitious particles of body 0 (without stencils).
FictitiousParticles lattice_images(const Particles& particles, const BoxFaces& box, double horizon);

}  // namespace fissure::bench
