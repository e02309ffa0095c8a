#pragma once
// Fictitious particles for bench_fictitious_particles (issue 15): mirror images of a box body's
// particles across its free faces, each moved as the quadratic (or linear) displacement field
// fitted to the family of the real particle nearest to it.
#include <array>
#include <vector>

#include "scene/particles.hpp"

namespace fissure::bench {

struct BoxFaces {
  std::array<double, 3> min, max;
  // Faces that get mirror images, as (axis, 0 for min or 1 for max).
  std::vector<std::array<int, 2>> free;
};

// Mirror images of the particles within δ of a free face, across it, and across each pair and
// triple of those faces on different axes (edges and corners), kept where they lie within δ of
// the box. Each keeps its source's volume.
struct Mirrors {
  std::vector<double> position;  // 3 per image
  std::vector<double> volume;
  int count() const { return static_cast<int>(volume.size()); }
};
Mirrors mirror_images(const Particles& particles, const BoxFaces& box, double horizon);

// Instead of mirror images: the points of a cubic lattice of the particles' mean spacing
// (V̄^⅓, each of volume V̄) outside the box, beyond its free faces only, within δ of the box and
// no closer than half the spacing to a particle: what a body of any shape could use.
Mirrors lattice_images(const Particles& particles, const BoxFaces& box, double horizon);

// u_g = Σ_k stencil weight · u_k over real particles: the fit of
// u_j − u_k = H ξ + ½ G:ξξ (order 2) or H ξ (order 1) to the real particles within
// `fit_radius` of k, the real particle nearest to g, weighted by δ/|ξ| V_j, evaluated at g.
// The weights of a stencil sum to 1, and reproduce every field of the fit's order exactly.
struct Extrapolation {
  std::vector<int> offsets;   // per image + 1
  std::vector<int> particle;  // real particle k
  std::vector<double> weight;
  double largest_l1 = 0, mean_l1 = 0;  // Σ|weight| of a stencil: how much it amplifies
  double smallest_conditioning = 1;    // smallest eigenvalue ratio of the fits' moment matrices
};
Extrapolation extrapolation(const Particles& particles, const Mirrors& mirrors, double horizon,
                            double fit_radius, int order);

}  // namespace fissure::bench
