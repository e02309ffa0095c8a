#pragma once
// Semi-implicit (symplectic) Euler, the paper's integrator: v ← v + Δt a(y, v); y ← y + Δt v.
#include "integrators/integrator.hpp"

namespace fissure {

class SymplecticEuler final : public Integrator {
 public:
  void step(Dynamics& dynamics, State& state, double dt) override;

 private:
  std::vector<double> acceleration_;
};

}  // namespace fissure
