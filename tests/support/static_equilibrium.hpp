#pragma once
// The quasi-static equilibrium reached from a state under the scene's loads and constraints:
// one petsc_newton `static` step (loads applied at once, held regions moved by their velocity ×
// 1 s), Newton solved to a relative residual of 1e-10.
#include "integrators/integrator.hpp"
#include "support/state.hpp"

namespace fissure::test {

inline State static_equilibrium(Dynamics& dynamics, State start) {
  IntegratorSettings settings;
  settings.type = "petsc_newton";
  settings.scheme = "static";
  settings.petsc_options = "-snes_rtol 1e-10";
  auto integrator = make_integrator(settings, "test");
  integrator->step(dynamics, start, 1.0);
  return start;
}

}  // namespace fissure::test
