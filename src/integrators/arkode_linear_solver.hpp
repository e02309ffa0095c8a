#pragma once
// A SUNLinearSolver for ARKODE's implicit stages that reduces the first-order Newton system to
// an SPD one in positions and solves it with CHOLMOD (docs/integrators.md). For u = [y − y0; v]
// (ARKODE integrates the displacement from the run's first state y0) and
// f_i = [v; M⁻¹F_int(y) − c v], the stage system (I − γJ)Δ = b with J = [[0, I], [−M⁻¹K, −cI]]
// becomes
//   (M(1 + γc) + γ²K) Δy = M((1 + γc) b_y + γ b_v),   Δv = (Δy − b_y) / γ,
// with K the exact tangent at ARKODE's predicted stage, or the projected tangent K⁺ ⪰ K where
// the exact one does not give an SPD matrix (model.hpp). Held particles have v̇ = 0: Δy = b_y + γ
// b_v there, moved to the right-hand side.
#include <sundials/sundials_linearsolver.h>

#include <vector>

#include "integrators/dynamics.hpp"
#include "linear/cholmod_factor.hpp"
#include "linear/sparse_symmetric.hpp"

namespace fissure {

class ReducedNewtonSystem {
 public:
  // origin: y0, the positions ARKODE's displacement unknowns are measured from.
  ReducedNewtonSystem(Dynamics& dynamics, void* arkode_memory, const std::vector<double>& origin);
  // Assembles K at ARKODE's predicted stage and factorizes.
  void setup();
  // x = (I − γJ)⁻¹ b, refactorizing first if ARKODE's γ changed since the last factorization.
  // ARKODE 6.4 does not call setup for a matrix-embedded solver, so the matrix is refreshed here
  // too: at the first solve, and when a stage needs a sixth Newton iteration (K is stale, e.g.
  // after large rotations), at that stage's prediction.
  void solve(const double* b, double* x);
  long factorizations() const { return factor_.factorizations(); }

 private:
  void factorize(double gamma);

  Dynamics& dynamics_;
  void* arkode_memory_;
  const std::vector<double>& origin_;
  SparseSymmetric stiffness_;      // K at the last setup
  std::vector<double> predicted_;  // the positions K was assembled at
  bool projected_ = false;         // K is K⁺
  SparseSymmetric system_;         // M(1 + γc) + γ²K with held unknowns taken out, over γ²
  std::vector<int> diagonal_;
  std::vector<double> mass_;  // per unknown
  std::vector<char> fixed_;   // per position unknown: held at the last setup
  CholmodFactor factor_;
  double gamma_ = 0;
  double stage_time_ = 0;  // t of the stage the last solve belonged to
  int stage_solves_ = 0;   // solves (Newton iterations) in that stage
  bool refreshed_in_stage_ = false;
  std::vector<double> rhs_, held_step_, coupling_;
};

// Wraps `system` (not owned) as a matrix-embedded SUNLinearSolver.
SUNLinearSolver make_reduced_linear_solver(SUNContext context, ReducedNewtonSystem* system);

}  // namespace fissure
