#pragma once
// The two-hop tangent of an elastic block at rest plus a mass shift, as an SDIRK stage at a few
// hundred times the explicit step makes it: what the tangent preconditioner factors.
#include <vector>

#include "linear/shifted_system.hpp"
#include "linear/sparse_symmetric.hpp"
#include "model/model.hpp"
#include "model/stiffness.hpp"
#include "support/scenes.hpp"

namespace fissure::test {

inline SparseSymmetric stage_matrix(const Block& block) {
  const Scene scene = block_scene(block);
  auto model = make_model(scene);
  SparseSymmetric a = two_hop_pattern(scene.families);
  model->stiffness()->assemble_tangent(scene.particles.reference.data(), a, false);
  const double h = 300 * model->stable_time_step();
  std::vector<double> mass;
  for (double m : scene.particles.mass) mass.insert(mass.end(), 3, m);
  const std::vector<char> fixed(mass.size(), 0);
  shift_and_fix(a, diagonal_positions(a), mass, 16 / (h * h), fixed);
  return a;
}

}  // namespace fissure::test
