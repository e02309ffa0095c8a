#pragma once
// A contact potential evaluated at z for the finite-difference tests (tests/contact): anything
// with potential(z, gradient, blocks) as Colliders and SelfContact have (energy returned, the
// gradient and 9 Hessian entries per particle added).
#include <vector>

namespace fissure::test {

struct Evaluation {
  double energy;
  std::vector<double> gradient, blocks;
};

template <class Potential>
Evaluation evaluate(Potential& potential, const std::vector<double>& z) {
  Evaluation e{0, std::vector<double>(z.size(), 0.0), std::vector<double>(3 * z.size(), 0.0)};
  e.energy = potential.potential(z.data(), e.gradient.data(), e.blocks.data());
  return e;
}

}  // namespace fissure::test
