#pragma once
// Velocity Verlet (kick–drift–kick), second order and symplectic for conservative forces.
#include "integrators/integrator.hpp"

namespace fissure {

class VelocityVerlet final : public Integrator {
 public:
  void step(Dynamics& dynamics, State& state, double dt) override;
  void bonds_changed() override { have_acceleration_ = false; }

 private:
  std::vector<double> acceleration_;
  bool have_acceleration_ = false;
};

}  // namespace fissure
