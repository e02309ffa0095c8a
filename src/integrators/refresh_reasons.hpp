#pragma once
// Why an implicit integrator's reused factor was made again (a "refresh"), counted per reason
// under the same statistics names by petsc_newton and arkode (docs/integrators.md): the first
// factorization is no refresh, so factorizations = 1 + the sum of the counts.
#include <array>
#include <cmath>

#include "integrators/integrator.hpp"

namespace fissure {

// Whether a factor made for a step-size coefficient (petsc_newton's A, arkode's γ) still fits
// `current`: a step shortened only by the round-off of end − t moves it in its last digits, and
// a factor off by 1e-6 of itself is an exact-enough Newton matrix (a refresh of the two-hop
// factor at 1e4 particles costs about 100 back-solves).
inline bool same_step_coefficient(double current, double factored) {
  return std::abs(current - factored) <= 1e-6 * factored;
}

struct Refreshes {
  enum Reason { none, first, step_size, bonds, convergence, fallback, every_iteration, reasons };
  std::array<long, reasons> count{};  // per reason
  // refreshes_step_size, _bonds_broken, _convergence, _fallback, _every_iteration
  void append_to(Statistics& stats) const {
    stats.emplace_back("refreshes_step_size", double(count[step_size]));
    stats.emplace_back("refreshes_bonds_broken", double(count[bonds]));
    stats.emplace_back("refreshes_convergence", double(count[convergence]));
    stats.emplace_back("refreshes_fallback", double(count[fallback]));
    stats.emplace_back("refreshes_every_iteration", double(count[every_iteration]));
  }
};

}  // namespace fissure
