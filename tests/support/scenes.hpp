#pragma once
// Small scenes for tests, built through the same path as a user's YAML.
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "scene/config.hpp"
#include "scene/scene.hpp"

namespace fissure::test {

// A tet-sampled box [0, size[0]] × [0, size[1]] × [0, size[2]] at edge length λ = resolution.
struct Block {
  std::array<double, 3> size;
  double resolution;
  double bulk, shear;
  double density = 1000;
  std::string model = "lps";
  double horizon = 1.45;      // δ in units of λ
  std::string material = "";  // appended to the material map, e.g. ", surface_correction: false"
  std::string scene = "";     // appended to the scene after the body, e.g. constraints or gravity
};

inline Scene block_scene(const Block& b) {
  const std::string yaml = fmt::format(
      "time: {{end: 1.0}}\n"
      "bodies:\n"
      "  - geometry: {{box: {{min: [0, 0, 0], max: [{}, {}, {}]}}}}\n"
      "    resolution: {}\n"
      "    horizon: {}\n"
      "    material: {{model: {}, density: {}, bulk_modulus: {}, shear_modulus: {}{}}}\n{}",
      b.size[0], b.size[1], b.size[2], b.resolution, b.horizon, b.model, b.density, b.bulk, b.shear,
      b.material, b.scene);
  return build_scene(parse_config(yaml, "test_block.yaml"));
}

// A tet-sampled cube [0, size]^3 at edge length λ with the given moduli.
inline Scene block_scene(double size, double lambda, double bulk, double shear,
                         const std::string& model = "lps", double horizon = 1.45) {
  return block_scene({.size = {size, size, size},
                      .resolution = lambda,
                      .bulk = bulk,
                      .shear = shear,
                      .model = model,
                      .horizon = horizon});
}

// Indices of particles at least `clearance` from every face of the box [0, size]^3.
inline std::vector<int> interior(const Particles& p, double size, double clearance) {
  std::vector<int> result;
  for (int i = 0; i < p.count(); ++i) {
    bool inside = true;
    for (int k = 0; k < 3; ++k) {
      const double x = p.reference[3 * i + k];
      inside = inside && x >= clearance && x <= size - clearance;
    }
    if (inside) result.push_back(i);
  }
  return result;
}

// y = F x for a 3×3 matrix F (row major).
inline std::vector<double> deform(const Particles& p, const double F[9]) {
  std::vector<double> y(p.reference.size());
  for (int i = 0; i < p.count(); ++i)
    for (int r = 0; r < 3; ++r) {
      double s = 0;
      for (int c = 0; c < 3; ++c) s += F[3 * r + c] * p.reference[3 * i + c];
      y[3 * i + r] = s;
    }
  return y;
}

}  // namespace fissure::test
