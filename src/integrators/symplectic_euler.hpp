#pragma once
// Semi-implicit (symplectic) Euler, the paper's integrator: v ← v + Δt a(y, v); y ← y + Δt v.
#include "integrators/integrator.hpp"

namespace fissure {

class SymplecticEuler final : public Integrator {
 public:
  double step(Dynamics& dynamics, State& state, double dt) override;
  bool explicit_step() const override { return true; }

 private:
  std::vector<double> acceleration_;
};

}  // namespace fissure
