#pragma once
// What a particle brings to a contact: its radius r = ½V^(1/3) and its penalty stiffness
// k = contact.stiffness × κ × V^(1/3) (docs/config.md, `contact`).
#include <cmath>
#include <vector>

#include "scene/scene.hpp"

namespace fissure {

struct ContactParticles {
  std::vector<double> radius;
  std::vector<double> stiffness;
};

inline ContactParticles contact_particles(const Scene& scene) {
  const Particles& p = scene.particles;
  ContactParticles c{std::vector<double>(p.count()), std::vector<double>(p.count())};
  for (int i = 0; i < p.count(); ++i) {
    const double size = std::cbrt(p.volume[i]);
    c.radius[i] = 0.5 * size;
    c.stiffness[i] = scene.config.contact.stiffness *
                     scene.config.bodies[p.body[i]].material.bulk_modulus * size;
  }
  return c;
}

}  // namespace fissure
