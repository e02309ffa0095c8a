#pragma once
// The quasi-static equilibrium reached from a state under the scene's loads and constraints:
// one petsc_newton `static` step (loads applied at once, held regions moved by their velocity ×
// 1 s), Newton solved to a relative residual of 1e-10.
#include "integrators/petsc_newton_settings.hpp"
#include "integrators/registry.hpp"
#include "support/state.hpp"

namespace fissure::test {

inline State static_equilibrium(Dynamics& dynamics, State start) {
  PetscNewtonSettings settings;
  settings.scheme = PetscNewtonSettings::Scheme::static_equilibrium;
  settings.petsc_options = "-snes_rtol 1e-10";
  auto integrator = make_integrator(integrator_settings("petsc_newton", settings), "test");
  integrator->step(dynamics, start, 1.0);
  return start;
}

}  // namespace fissure::test
