#pragma once
// What docs/config.md (contact.self) gives each particle, computed here by brute force from the
// scene's volumes, families and reference positions rather than by the code under test: its
// radius r = ½V^(1/3), capped at half the distance of every pair without a bond that starts
// closer than r_i + r_j, and its penalty stiffness k = contact.stiffness × κ × V^(1/3)
// (contact.stiffness 1 by default), with κ per body given.
#include <algorithm>
#include <cmath>
#include <vector>

#include "scene/scene.hpp"

namespace fissure::test {

struct ContactSizes {
  std::vector<double> radius, stiffness;
};

inline ContactSizes documented_sizes(const Scene& scene, const std::vector<double>& bulk_modulus) {
  ContactSizes c;
  const int n = scene.particles.count();
  for (int i = 0; i < n; ++i) {
    const double size = std::cbrt(scene.particles.volume[i]);
    c.radius.push_back(0.5 * size);
    c.stiffness.push_back(bulk_modulus[scene.particles.body[i]] * size);
  }
  const Families& fam = scene.families;
  const auto& y = scene.particles.reference;
  std::vector<double> capped = c.radius;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      if (j == i) continue;
      double d2 = 0;
      for (int k = 0; k < 3; ++k) d2 += std::pow(y[3 * i + k] - y[3 * j + k], 2);
      const bool bonded = std::count(fam.neighbors.begin() + fam.offsets[i],
                                     fam.neighbors.begin() + fam.offsets[i + 1], j) > 0;
      if (std::sqrt(d2) < c.radius[i] + c.radius[j] && !bonded)
        capped[i] = std::min(capped[i], 0.5 * std::sqrt(d2));
    }
  c.radius = capped;
  return c;
}

}  // namespace fissure::test
