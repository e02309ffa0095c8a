#pragma once
// Semi-implicit (symplectic) Euler, the paper's integrator: v ← v + Δt a(y, v); y ← y + Δt v.
#include "integrators/registry.hpp"

namespace fissure {

class SymplecticEuler final : public Integrator {
 public:
  double step(Dynamics& dynamics, State& state, double dt) override;
  bool explicit_step() const override { return true; }
  bool distributable() const override { return true; }

 private:
  std::vector<double> acceleration_;
};

// type: symplectic_euler, no options of its own.
IntegratorKind symplectic_euler_kind();

}  // namespace fissure
