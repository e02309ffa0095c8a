#pragma once
// For bench_fictitious_particles: a clamp face x = x_c represented by mirror images of the
// particles behind it instead of a held block (issue 15). Behind a held face the displacement is
// zero, so an image there moves as the quadratic displacement that vanishes on the face,
//   u(p) = (p_x − x_c) (a + B (p − x_k)),
// fitted around the particle k nearest to it: the continuation of the body's field through the
// face, which the families near the face then sample as they would inside.
#include "model/fictitious_particles.hpp"
#include "scene/particles.hpp"

namespace fissure::bench {

// Replaces the stencils of the images with x < clamp_x by the clamped fit over the particles of
// their body within fit_radius of their nearest particle (weights ω V as fit_stencils). Throws
// std::invalid_argument where fewer than 4 particles make the fit singular.
void clamp_stencils(const Particles& particles, double horizon, double fit_radius, double clamp_x,
                    FictitiousParticles& images);

}  // namespace fissure::bench
