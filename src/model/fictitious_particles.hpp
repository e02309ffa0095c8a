#pragma once
// Fictitious particles (docs/model.md, deviation 8): mirror images of a body's
// particles across its boundary, which complete the families near its surface so that a
// particle there samples a strain gradient as one inside does. An image stores no energy of its
// own; it moves as the quadratic displacement fitted around the particle nearest to it: a fixed
// affine combination of particles' positions (its stencil) that reproduces every quadratic
// displacement field, so a rigid motion moves it rigidly.
#include <array>
#include <vector>

#include "scene/particles.hpp"

namespace fissure {

// A boundary triangle: its corners, xyz each.
using Triangle = std::array<double, 9>;

struct FictitiousParticles {
  std::vector<double> position;  // x_g, xyz interleaved
  std::vector<double> volume;    // V_g: its source's
  std::vector<int> body;
  // u_g = Σ_s weight[s] u_particle[s] over s in [offsets[g], offsets[g + 1]), displacements;
  // the weights of a free face's image sum to 1, so that y_g = Σ_s weight[s] y_particle[s] too
  std::vector<int> offsets{0};
  std::vector<int> particle;
  std::vector<double> weight;
  int count() const { return static_cast<int>(volume.size()); }
};

// Faces of the boundary near one particle whose planes are parallel within this angle and lie
// within half a particle spacing of each other are one face (a curved surface's triangles);
// otherwise the particle sits at an edge or a corner, or in a thin plate, and its images are
// reflected across both faces in turn. 20°: a sphere's triangles within δ of a particle differ
// by about δ/R, a box's faces by 90° (or 0° and a plate's thickness for opposite ones).
constexpr double kSameFaceCosine = 0.9396926207859084;  // cos 20°

// Adds mirror images of the particles of `body`: each particle within δ of `boundary` is
// reflected across the plane of each distinct face within δ of it, and across every pair and
// triple of them in turn (edges, corners). An image is kept where it lies within δ of a particle
// of the body, and no closer than half the body's mean particle spacing (the cube root of its
// mean volume) to any particle of any body or to an image kept before: an image that lands inside
// a body (a concave corner) or on another image is dropped. Stencils are left to fit_stencils.
void add_mirror_images(const Particles& particles, int body, const std::vector<Triangle>& boundary,
                       double horizon, FictitiousParticles& images);

// The stencil of every image: the displacement u_j − u_k = H ξ + ½ G:ξξ fitted in least squares,
// weighted by δ/|ξ| V_j, to the particles of its body within fit_radius of k, the particle of its
// body nearest to it, and evaluated at the image. Throws std::invalid_argument naming the
// particle where fewer than 9 particles make the fit singular.
void fit_stencils(const Particles& particles, const std::vector<double>& horizon_of_body,
                  double fit_radius, FictitiousParticles& images);

// A clamp face: the plane through `point` with unit `normal` pointing out of the body, behind
// which the displacement is held at zero.
struct ClampPlane {
  std::array<double, 3> point, normal;
};

// Replaces the stencils of the images behind `plane` (normal·(x_g − point) > 0) by the quadratic
// displacement that vanishes on the plane, u(p) = (normal·(p − point)) (a + B (p − x_k)), fitted
// as fit_stencils does around the particle k of its body nearest to it: a clamp's field continued
// through its face, where a held block of particles would make the clamp soft (docs/model.md,
// deviation 8). Such a stencil reproduces every quadratic displacement vanishing on the plane; its
// weights do not sum to 1 (a translation is not free). Throws std::invalid_argument naming the
// particle where fewer than 4 particles make the fit singular.
void clamp_stencils(const Particles& particles, const std::vector<double>& horizon_of_body,
                    double fit_radius, const ClampPlane& plane, FictitiousParticles& images);

// The particles followed by the images (at rest, without mass): the points whose families the
// images complete.
Particles with_images(const Particles& particles, const FictitiousParticles& images);

// The largest and the mean Σ_s |weight[s]| of the stencils: how much an image amplifies a
// displacement of its particles (1 for an interpolation).
std::array<double, 2> stencil_amplification(const FictitiousParticles& images);

}  // namespace fissure
