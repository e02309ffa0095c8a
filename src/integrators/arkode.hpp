#pragma once
// SUNDIALS ARKODE (type: arkode) on the first-order form u = [y; v]: explicit, implicit or
// implicit–explicit additive Runge–Kutta through ARKStep, adaptive under rtol/atol or at a fixed
// step. Each call takes one internal step (ARK_ONE_STEP), so the run loop's post-step runs after
// every accepted internal step; a bond-set change re-initialises ARKODE at the current state.
// Over several ranks (explicit methods) u holds the rank's own rows.
#include <memory>
#include <string>

#include "integrators/arkode_methods.hpp"
#include "integrators/arkode_settings.hpp"
#include "integrators/registry.hpp"

namespace fissure {

class Arkode final : public Integrator {
 public:
  Arkode(const ArkodeSettings& settings, const std::string& file);
  ~Arkode() override;
  void check(const Dynamics& dynamics) const override;
  double step(Dynamics& dynamics, State& state, double dt) override;
  void bonds_changed() override;
  bool explicit_step() const override {
    return settings_.fixed_step && method_.kind == ArkodeMethod::Kind::explicit_rk;
  }
  bool adaptive() const override { return !settings_.fixed_step; }
  // Over several ranks: u holds this rank's rows in an MPI+X vector, so its norms (adaptive
  // steps) are global (docs/mpi.md); implicit and IMEX methods with the nearest
  // preconditioner (auto's choice there), block Jacobi over the ranks.
  bool distributable() const override {
    return method_.kind == ArkodeMethod::Kind::explicit_rk ||
           settings_.preconditioner != ArkodeSettings::Preconditioner::tangent;
  }
  std::string undistributable_option() const override { return "integrator.preconditioner"; }
  Statistics statistics() const override;
  // New tolerances for the following steps (adaptive runs), e.g. to tighten them mid-run.
  void set_tolerances(double rtol, double atol);

  struct Solver;  // the SUNDIALS objects

 private:
  Statistics arkode_counters() const;

  ArkodeSettings settings_;
  std::string file_;
  const ArkodeMethod& method_;
  std::unique_ptr<Solver> solver_;
  bool reinitialise_ = false;
};

// type: arkode, its options in arkode_settings.hpp.
IntegratorKind arkode_kind();

}  // namespace fissure
