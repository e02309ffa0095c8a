#pragma once
// The preconditioner of petsc_newton's linear solves: a matrix close to the Newton matrix
// A M + K (+ the loads' Hessian blocks, NewtonSystem), assembled and factorized (or set up, for
// multigrid) at one point and then reused for as many Newton iterations and steps as the refresh
// policy allows (petsc_newton.cpp).
//   tangent:   the tangent itself, two-hop 3N×3N, CHOLMOD (an exact Newton matrix when fresh);
//   majoriser: the bond-wise majoriser K^bw ⪰ K, one-hop 3N×3N, CHOLMOD;
//   nearest:   the majoriser's bonds to each family's nearest members only, rescaled to the
//              family's stiffness (Stiffness::assemble_nearest_stiffness), 3N×3N, CHOLMOD;
//   scalar:    A M + L ⊗ I₃ with L the one-hop scalar stiffness (Model::assemble_scalar_stiffness),
//              N×N, CHOLMOD, applied to the three components;
//   gamg:      PETSc's algebraic multigrid (GAMG) on the nearest matrix, rigid-body modes as
//              near null space, threshold 0.02.
// The inner PETSc PC reads the options prefixed `precond_` (e.g. -precond_pc_gamg_threshold);
// GAMG's level smoothers (-precond_mg_levels_*) read only PETSC_OPTIONS: PETSc 3.18 creates them
// on the global options database.
// While it stays PETSc's CHOLMOD Cholesky (the default), the factor is made and solved by
// SupernodalCholesky instead, in the precision `factor_precision` asks for.
#include <petscpc.h>

#include <memory>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "integrators/newton_system.hpp"
#include "linear/supernodal_cholesky.hpp"

namespace fissure {

class NewtonPreconditioner {
 public:
  using Kind = PetscNewtonSettings::Preconditioner;
  NewtonPreconditioner(NewtonSystem& system, Kind kind, PetscOptions options,
                       FactorPrecision precision);
  ~NewtonPreconditioner();
  NewtonPreconditioner(const NewtonPreconditioner&) = delete;
  NewtonPreconditioner& operator=(const NewtonPreconditioner&) = delete;

  // Assembles the matrix at z with the system's current A, held unknowns and tangent choice,
  // and factorizes it. Throws RunError when it is not positive definite.
  void refresh(const double* z);
  // x = P⁻¹ r.
  void apply(Vec r, Vec x);
  // Half to single precision for the factors from the next refresh on (SupernodalCholesky::
  // raise_precision); false when the factor is not kept in half precision.
  bool raise_precision() { return cholesky_ && cholesky_->raise_precision(); }
  // Bonds broke: the scalar stiffness is assembled again at the next refresh.
  void bonds_changed() { scalar_assembled_ = false; }
  void view(PetscViewer viewer) const;
  Kind kind() const { return kind_; }
  // The factor SupernodalCholesky keeps, or nullptr when PETSc's PC makes it.
  const SupernodalCholesky* cholesky() const { return cholesky_.get(); }
  // Whether the factor depends on the point it is made at: the scalar one depends on A and the
  // bonds only, so a refresh for slow convergence would rebuild the same factor.
  bool follows_the_state() const { return kind_ != Kind::scalar; }
  long assemblies = 0, factorizations = 0, back_solves = 0;
  // Whether a preconditioner of this kind runs over several ranks: there its matrix's own rows
  // form a MATMPIAIJ, factored by MUMPS's Cholesky (or set up by PETSc's GAMG).
  static bool distributable(Kind kind, NewtonSystem::Tangent tangent);

 private:
  void create_petsc_matrix(const SparseSymmetric& a, int block_size);
  void create_distributed_matrix(const SparseSymmetric& a);
  void copy_values();
  // Column c of matrix_ in the whole scene's numbering (over several ranks), in the same order.
  PetscInt global_column(int c) const;
  void add_potential_blocks(const double* z);
  void shift_and_hold(double inertia);
  RunError not_positive_definite() const;

  NewtonSystem& system_;
  Kind kind_;
  PetscOptions options_;
  SparseSymmetric matrix_;            // what is factorized, in CHOLMOD's and SEQAIJ's layout
  std::vector<int> diagonal_;         // index of entry (r, r) in matrix_
  std::vector<double> blocks_;        // the loads' Hessian blocks at the last refresh
  std::vector<char> nearest_;         // nearest: the kept bonds
  SparseSymmetric scalar_stiffness_;  // scalar: L
  bool scalar_assembled_ = false;
  bool threaded_product_ = false;  // PETSc's matrix multiplies over the threads (threaded_aij)
  Mat petsc_matrix_ = nullptr;
  PC pc_ = nullptr;
  std::unique_ptr<SupernodalCholesky> cholesky_;
  std::vector<double> component_in_, component_out_;  // scalar: one component, N
  // scalar without cholesky_: the same arrays as PETSc vectors
  Vec component_ = nullptr, component_solution_ = nullptr;
};

// The preconditioner `auto` picks for a scene of these families (docs/integrators.md), on one
// rank or over several.
PetscNewtonSettings::Preconditioner choose_preconditioner(const Families& families,
                                                          bool distributed = false);
const char* preconditioner_name(PetscNewtonSettings::Preconditioner kind);

}  // namespace fissure
