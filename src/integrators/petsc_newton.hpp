#pragma once
// Implicit integration with PETSc (type: petsc_newton): each step (each stage of an SDIRK
// scheme) minimises the incremental potential of the chosen scheme (implicit_scheme.hpp) with
// SNES Newton and a backtracking line search on that potential. The Newton matrix A M + K is
// applied matrix-free; the linear solves are the preconditioner's factor alone (modified Newton)
// or a Krylov method preconditioned by it, and the factor is reused across iterations, stages
// and steps until the refresh policy renews it (newton_preconditioner.hpp, docs/integrators.md).
#include <memory>
#include <string>

#include "integrators/petsc_newton_settings.hpp"
#include "integrators/registry.hpp"

namespace fissure {

class PetscNewton final : public Integrator {
 public:
  PetscNewton(const PetscNewtonSettings& settings, const std::string& file);
  ~PetscNewton() override;
  void check(const Dynamics& dynamics) const override;
  double step(Dynamics& dynamics, State& state, double dt) override;
  void bonds_changed() override;
  // Over several ranks with every preconditioner but the two-hop tangent and the scalar one
  // (docs/mpi.md).
  bool distributable() const override;
  std::string undistributable_option() const override { return "integrator.preconditioner"; }
  Statistics statistics() const override;
  NamedArrays saved_state() const override;
  void restore_state(const NamedArrays& state) override;
  // What PETSc reports of its linear solver (KSPView), e.g. to check the factorization package.
  std::string solver_view() const;

  struct Solver;  // the PETSc objects

 private:
  // Advances by dt; where Newton fails, redoes the step as two halves, up to `halvings` deep.
  // Throws RunError with the state as it was before the step when that fails too.
  void advance(Dynamics& dynamics, State& state, double dt, int halvings);
  // One step of dt from a known a_n: empty on success, else why it failed (the state is then
  // partly updated).
  std::string attempt(Dynamics& dynamics, State& state, double dt);

  PetscNewtonSettings settings_;
  std::string file_;
  std::unique_ptr<Solver> solver_;
  NamedArrays restored_;  // a checkpoint's state, applied when the solver is set up
};

// type: petsc_newton, its options in petsc_newton_settings.hpp.
IntegratorKind petsc_newton_kind();

}  // namespace fissure
