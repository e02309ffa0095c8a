#pragma once
// Why an implicit integrator's reused factor was made again (a "refresh"), counted per reason
// under the same statistics names by petsc_newton and arkode (docs/integrators.md): the first
// factorization is no refresh, so factorizations = 1 + the sum of the counts.
#include <array>

#include "integrators/integrator.hpp"

namespace fissure {

struct Refreshes {
  enum Reason { none, first, step_size, bonds, convergence, fallback, every_iteration, reasons };
  std::array<long, reasons> count{};  // per reason
  // refreshes_step_size, _bonds_broken, _convergence, _fallback, _every_iteration
  void append_to(Statistics& stats) const {
    stats.push_back({"refreshes_step_size", double(count[step_size])});
    stats.push_back({"refreshes_bonds_broken", double(count[bonds])});
    stats.push_back({"refreshes_convergence", double(count[convergence])});
    stats.push_back({"refreshes_fallback", double(count[fallback])});
    stats.push_back({"refreshes_every_iteration", double(count[every_iteration])});
  }
};

}  // namespace fissure
