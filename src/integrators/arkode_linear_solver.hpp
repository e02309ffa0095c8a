#pragma once
// A SUNLinearSolver for ARKODE's implicit stages that reduces the first-order Newton system to
// an SPD one in positions and solves it with a CHOLMOD factor, reused across γ changes and
// stages as the preconditioner of CG (docs/integrators.md). For u = [y − y0; v] (ARKODE
// integrates the displacement from the run's first state y0) and f_i = [v; M⁻¹F_int(y) − c v],
// the stage system (I − γJ)Δ = b with J = [[0, I], [−M⁻¹K, −cI]] becomes
//   S Δy = M((1 + γc) b_y + γ b_v)/γ²,   S = M(1 + γc)/γ² + K,   Δv = (Δy − b_y) / γ,    (R)
// with K the exact tangent at ARKODE's predicted stage, or the projected tangent K⁺ ⪰ K where
// the exact one does not give an SPD matrix (model.hpp). Held particles have v̇ = 0: Δy = b_y + γ
// b_v there, moved to the right-hand side.
//
// With reuse (integrator.reuse_factor: true; arkode's default is false, docs/integrators.md) the
// factor of S at one γ and one state preconditions CG on (R) at the current γ, K applied
// matrix-free at the current stage's prediction; it is refreshed (assembled and factorized at the
// current stage and γ, after which one back-solve is exact) when CG needs more than
// integrator.refresh_krylov iterations or breaks down, when bonds broke, and when the factorization
// is not SPD (then with K⁺). Without reuse, S is refactorized whenever γ changes, with the K of the
// last assembly.
//
// With `nearest` (integrator.preconditioner, for large scenes) the factor is of S with the
// nearest members' one-hop matrix (Stiffness::assemble_nearest_stiffness) in place of K: never S
// itself, so every solve is CG on (R), refreshed as above (and, without reuse, at every γ
// change); where CG breaks down (S with the exact K not SPD) the matrix-free K becomes K⁺.
//
// Over several MPI ranks (Dynamics::distribute; docs/mpi.md) ARKODE's vectors hold the rank's
// own rows, [Δy; Δv] of them; the system's own arrays stay 3N over the rank's rows with the
// ghosts' positions shared, CG's dot products are summed over the ranks, and the factor is of
// the rank's diagonal block of S (block Jacobi): `nearest` only, the two-hop tangent's rows
// reaching beyond the halo.
#include <sundials/sundials_linearsolver.h>

#include <exception>
#include <vector>

#include "integrators/dynamics.hpp"
#include "integrators/integrator.hpp"
#include "integrators/refresh_reasons.hpp"
#include "linear/conjugate_gradient.hpp"
#include "linear/sparse_symmetric.hpp"
#include "linear/supernodal_cholesky.hpp"

namespace fissure {

class ReducedNewtonSystem {
 public:
  // origin: y0, the positions ARKODE's displacement unknowns are measured from. reuse and
  // krylov_limit: integrator.reuse_factor and integrator.refresh_krylov.
  // nearest: factorize the nearest members' matrix instead of the two-hop tangent.
  ReducedNewtonSystem(Dynamics& dynamics, void* arkode_memory, const std::vector<double>& origin,
                      bool reuse, int krylov_limit, FactorPrecision precision, bool nearest);
  // Whether a ReducedNewtonSystem runs over several ranks with this factor.
  static bool distributable(bool nearest) { return nearest; }
  // x = (I − γJ)⁻¹ b, with ‖b − (I − γJ)x‖₂ ≤ tol where CG is used (solve_by_cg); b and x the
  // rank's own rows ([Δy; Δv], 6 × its rows; all rows on one rank). ARKODE 6.4
  // does not call setup for a matrix-embedded solver, so the matrix is refreshed here: at the
  // first solve, after bonds broke and as the reuse policy says.
  void solve(const double* b, double* x, double tol);
  // Bonds broke: the factor is refreshed at the next solve.
  void bonds_changed() { pending_ = Refreshes::bonds; }
  // factorizations, back_solves, krylov_iterations, tangent_products, linearizations and the
  // refreshes per reason (petsc_newton's names).
  void append_statistics(Statistics& stats) const;

 private:
  // Stage bookkeeping: a solve with another t or prediction than the last begins a stage.
  void begin_stage_if_new();
  // fixed_: the unknowns constraints hold at t.
  void hold_at(double t);
  // Assembles K at the stage's prediction and factorizes S at gamma (K⁺ if S is not SPD).
  void refresh(Refreshes::Reason reason, double gamma);
  // Factorizes S at gamma with the assembled K; where that is not SPD, assembles K⁺ at the
  // same point and factorizes again (a refresh for `fallback`).
  void factorize(double gamma);
  bool same_gamma(double gamma) const;  // as the factor's (same_step_coefficient)
  // The factor is S itself: made in this stage, at this γ.
  bool fresh(double gamma) const;
  // rhs_ and held_step_ of (R) for b; the held particles' coupling −K Δy_held uses the
  // assembled K, or the matrix-free one when `matrix_free`.
  void reduced_rhs(const double* b, double gamma, bool matrix_free);
  // x = [Δy; Δv] from Δy (x's first half) by (R).
  void expand(const double* b, double gamma, double* x) const;
  // CG on (R) preconditioned by the factor; false when it needed more than the limit or broke
  // down (dy is then to be overwritten).
  bool solve_by_cg(double gamma, double tol, double* dy);
  // x = (I − γJ)⁻¹ b by CG with the nearest factor.
  void solve_with_nearest(const double* b, double gamma, double tol, double* x);
  // out = S v on free unknowns (v zero on held ones), 0 on held ones; K matrix-free.
  void apply_system(double gamma, const double* v, double* out);
  // z = the factor's solve of r, zero on held unknowns.
  void precondition(const double* r, double* z);
  // Over several ranks: the rank's diagonal block of system_, from the entries block_source_
  // names; the factor is made of it. Σ over the ranks (one rank: the value).
  void extract_block();
  double sum(double value) const;
  bool distributed() const { return dynamics_.halo() != nullptr; }
  // The model's matrix-free tangent at the stage's prediction, with the factor's tangent
  // choice (exact or K⁺).
  void linearize_stage();

  Dynamics& dynamics_;
  std::size_t first_ = 0, count_ = 0;  // the rank's unknowns: [first_, first_ + count_) of 3N
  void* arkode_memory_;
  const std::vector<double>& origin_;
  bool reuse_;
  int krylov_limit_;
  std::vector<char> nearest_;         // per directed bond: kept (`nearest` only; else empty)
  SparseSymmetric stiffness_;         // K at the last assembly
  std::vector<double> assembled_at_;  // ... at these positions
  SparseSymmetric system_;            // S with held unknowns taken out
  SparseSymmetric block_;             // over several ranks: its diagonal block, rows renumbered
  std::vector<int> block_source_;     // ... each entry's index in system_
  std::vector<int> diagonal_;
  std::vector<double> mass_;  // per unknown
  SupernodalCholesky factor_;
  long factorizations_ = 0;
  ConjugateGradient cg_;
  // The stage: ARKODE's t and predicted positions, which unknowns are held, its solves.
  double stage_time_ = 0;
  std::vector<double> predicted_;
  std::vector<char> fixed_;
  long stage_ = 0;  // stages begun
  int stage_solves_ = 0;
  bool refreshed_in_stage_ = false;
  // The factor: its γ, the stage it was made in, whether its K is K⁺.
  double factor_gamma_ = 0;
  long factor_stage_ = -1;
  bool projected_ = false;
  long linearized_stage_ = -1;  // the stage the model's matrix-free tangent belongs to
  bool linearized_projected_ = false;
  Refreshes::Reason pending_ = Refreshes::first;
  Refreshes refreshes_;
  long back_solves_ = 0, krylov_iterations_ = 0, tangent_products_ = 0, linearizations_ = 0;
  // rhs_ and scratch_ the rank's unknowns; held_step_, coupling_ and the product's in and out 3N
  std::vector<double> scratch_, rhs_, held_step_, coupling_, product_in_, product_out_;
};

// Wraps `system` (not owned) as a matrix-embedded SUNLinearSolver. An exception a solve throws
// is stored in *error (ARKODE gets SUNLS_PACKAGE_FAIL_UNREC) for the caller to rethrow.
SUNLinearSolver make_reduced_linear_solver(SUNContext context, ReducedNewtonSystem* system,
                                           std::exception_ptr* error);

}  // namespace fissure
