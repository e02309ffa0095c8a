#pragma once
// Velocity Verlet (kick–drift–kick), second order and symplectic for conservative forces.
#include "integrators/registry.hpp"

namespace fissure {

class VelocityVerlet final : public Integrator {
 public:
  double step(Dynamics& dynamics, State& state, double dt) override;
  bool explicit_step() const override { return true; }
  bool distributable() const override { return true; }
  void bonds_changed() override { have_acceleration_ = false; }
  NamedArrays saved_state() const override;
  void restore_state(const NamedArrays& state) override;

 private:
  std::vector<double> acceleration_;
  bool have_acceleration_ = false;
};

// type: velocity_verlet, no options of its own.
IntegratorKind velocity_verlet_kind();

}  // namespace fissure
