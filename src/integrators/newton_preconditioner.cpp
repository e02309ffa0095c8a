#include "integrators/newton_preconditioner.hpp"

#include <fmt/format.h>
#include <omp.h>
#include <petscksp.h>
#include <petscmat.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "core/error.hpp"
#include "integrators/petsc_session.hpp"
#include "integrators/threaded_aij.hpp"
#include "linear/blas_threads.hpp"
#include "linear/nearest_bonds.hpp"
#include "linear/shifted_system.hpp"
#include "model/stiffness.hpp"
#include "parallel/collective.hpp"
#include "parallel/halo.hpp"

namespace fissure {

namespace {

// K ← A M + K on the scalar matrix: row i gets A m_i on its diagonal; a held particle's row
// and column are decoupled as shift_and_fix does for the 3N matrices.
void shift_scalar(SparseSymmetric& a, const std::vector<int>& diagonal,
                  const std::vector<double>& mass, double inertia, const std::vector<char>& fixed) {
  std::vector<double> particle_mass(a.rows);
  std::vector<char> particle_fixed(a.rows);
  for (int i = 0; i < a.rows; ++i) particle_mass[i] = mass[3 * i], particle_fixed[i] = fixed[3 * i];
  shift_and_fix(a, diagonal, particle_mass, inertia, particle_fixed);
}

// gamg's matrix keeps more members: a multigrid cycle costs about linearly in its entries where
// a factor's fill grows faster. Measured as above (bench_implicit_step, gamg): CG iterations per
// step 28 / 23 / 19 keeping 20 / 30 / 45 members at 7,948 particles (28.6 / 27.1 / 30.2 µs per
// particle), and at 95,187 particles 20 members took 42 µs per particle, 30 members 38.5.
constexpr int kGamgMembers = 30;

// gamg's default -pc_gamg_threshold (a user's -precond_pc_gamg_threshold overrides it).
constexpr PetscReal kGamgThreshold = 0.02;

// One smoothing sweep per level instead of PETSc's two: more CG iterations (21 against 17 per
// step at 95,187 particles) but cheaper V-cycles, 4.48 against 5.69 s per step there and 0.403
// against 0.543 s at 7,948 (bench_implicit_step, 2026-12-05; docs/accuracy.md). Set on each level's
// smoother after every set-up (GAMG may make the levels anew), unless PETSC_OPTIONS sets
// -precond_mg_levels_ksp_max_it: the levels read only the global options database.
void smooth_once_per_level(PC pc) {
  PetscBool set = PETSC_FALSE;
  petsc_check(PetscOptionsHasName(nullptr, nullptr, "-precond_mg_levels_ksp_max_it", &set),
              "PetscOptionsHasName");
  if (set) return;
  PetscInt levels = 0;
  petsc_check(PCMGGetLevels(pc, &levels), "PCMGGetLevels");
  for (PetscInt level = 1; level < levels; ++level) {
    KSP smoother;
    petsc_check(PCMGGetSmoother(pc, level, &smoother), "PCMGGetSmoother");
    petsc_check(KSPSetTolerances(smoother, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT, 1),
                "KSPSetTolerances");
  }
}

}  // namespace

bool NewtonPreconditioner::distributable(Kind kind, NewtonSystem::Tangent tangent) {
  switch (kind) {
    case Kind::majoriser:
    case Kind::nearest:
    case Kind::gamg:
    case Kind::automatic:
      return true;
    case Kind::tangent:  // the two-hop tangent, unless the tangent is the majoriser
      return tangent == NewtonSystem::Tangent::majoriser;
    case Kind::scalar:  // its N×N matrix is applied per component: not written for ranks yet
      return false;
  }
  return false;
}

const char* preconditioner_name(PetscNewtonSettings::Preconditioner kind) {
  using P = PetscNewtonSettings::Preconditioner;
  switch (kind) {
    case P::tangent:
      return "tangent";
    case P::majoriser:
      return "majoriser";
    case P::nearest:
      return "nearest";
    case P::scalar:
      return "scalar";
    case P::gamg:
      return "gamg";
    case P::automatic:
      break;
  }
  return "auto";
}

PetscNewtonSettings::Preconditioner choose_preconditioner(const Families& families,
                                                          bool distributed) {
  // Measured on the glass cantilever (docs/accuracy.md, bench_implicit_step, backward Euler at
  // 300× the explicit estimate): the two-hop factor is fastest per step while it fits (7,948
  // particles: 0.069 s per later step, 1.77 GB) but grows far faster than the scene. At 26,973
  // particles the one-hop majoriser's factor takes 17.4 s to make and 3.8 GB for 1.36 s per
  // later step, the nearest members' 5.1 s and 1.1 GB for 1.65 s; at 95,187 the nearest takes
  // 7.2 s per step and 5.7 GB where the scalar factor took 34.8 s (59 CG iterations per Newton
  // iteration against 16: the scalar matrix does not see bending). GAMG on the nearest members'
  // matrix costs about linearly: 27 / 27 / 30–35 µs per particle at 7,948 / 17,096 / 95,187
  // particles (nearest's factor: 34 / 30 / 73), 1.9 GB at 95,187.
  const std::size_t particles = families.offsets.size() - 1;
  using P = PetscNewtonSettings::Preconditioner;
  // Over several ranks the two-hop rows reach beyond the halo, and GAMG scales best
  // (bench/run_distributed_bench.sh, 4,215 particles per rank, 1 → 2 ranks: 0.260 → 0.295 s per
  // step, the nearest members' factor 0.386 → 0.664 s, the majoriser's 0.367 → 1.14 s).
  if (distributed) return P::gamg;
  return particles <= 10000 ? P::tangent : P::gamg;
}

NewtonPreconditioner::NewtonPreconditioner(NewtonSystem& system, Kind kind, PetscOptions options,
                                           FactorPrecision precision)
    : system_(system), kind_(kind), options_(options) {
  const Families& families = system.dynamics().model().families();
  const bool distributed = system.distributed();
  if (distributed && !distributable(kind, system.tangent()))
    throw RunError(fmt::format("the {} preconditioner cannot run over several ranks",
                               preconditioner_name(kind)));
  MPI_Comm comm = distributed ? system.dynamics().halo()->comm() : PETSC_COMM_SELF;
  // over several ranks only the rank's rows are kept (the others empty)
  const int first = system.dynamics().first_row(), end = system.dynamics().end_row();
  switch (kind) {
    case Kind::tangent:
      matrix_ = system.tangent() == NewtonSystem::Tangent::majoriser
                    ? bond_pattern(families, first, end)
                    : system.dynamics().model().stiffness()->tangent_pattern(families);
      break;
    case Kind::majoriser:
      matrix_ = bond_pattern(families, first, end);
      break;
    case Kind::nearest:
    case Kind::gamg:
      nearest_ = nearest_bonds(families, kind == Kind::gamg ? kGamgMembers : kNearestMembers,
                               [&system](double* reach) { system.dynamics().share(reach, 1); });
      matrix_ = nearest_bond_pattern(families, nearest_, first, end);
      break;
    case Kind::scalar:
      matrix_ = scalar_bond_pattern(families);
      scalar_stiffness_ = matrix_;
      break;
    case Kind::automatic:
      throw RunError("NewtonPreconditioner: choose a kind first");
  }
  diagonal_ = diagonal_positions(matrix_);
  if (kind == Kind::scalar) component_in_.resize(matrix_.rows), component_out_.resize(matrix_.rows);
  petsc_check(PCCreate(comm, &pc_), "PCCreate");
  petsc_check(PetscObjectSetOptions(reinterpret_cast<PetscObject>(pc_), options_), "options");
  petsc_check(PCSetOptionsPrefix(pc_, "precond_"), "PCSetOptionsPrefix");
  if (kind == Kind::gamg) {
    petsc_check(PCSetType(pc_, PCGAMG), "PCSetType");
    // Drop the weakest couplings from the aggregation graph: 26 against 46 µs per particle with
    // PETSc's default (none dropped) at 7,948 particles (bench_implicit_step, docs/integrators.md).
    const PetscReal threshold[] = {kGamgThreshold};
    petsc_check(PCGAMGSetThreshold(pc_, const_cast<PetscReal*>(threshold), 1),
                "PCGAMGSetThreshold");
  } else {
    // over several ranks MUMPS's parallel Cholesky factors the same matrix as CHOLMOD on one
    petsc_check(PCSetType(pc_, PCCHOLESKY), "PCSetType");
    petsc_check(PCFactorSetMatSolverType(pc_, distributed ? MATSOLVERMUMPS : MATSOLVERCHOLMOD),
                "PCFactorSetMatSolverType");
  }
  petsc_check(PCSetFromOptions(pc_), "PCSetFromOptions");
  PCType type;
  petsc_check(PCGetType(pc_, &type), "PCGetType");
  MatSolverType solver = nullptr;
  if (std::strcmp(type, PCCHOLESKY) == 0)
    petsc_check(PCFactorGetMatSolverType(pc_, &solver), "PCFactorGetMatSolverType");
  if (!distributed && solver && std::strcmp(solver, MATSOLVERCHOLMOD) == 0) {
    // PETSc's own CHOLMOD Cholesky, as by default: made and solved here instead.
    cholesky_ = std::make_unique<SupernodalCholesky>(precision);
    return;
  }
  create_petsc_matrix(matrix_, kind == Kind::scalar ? 1 : 3);
  petsc_check(PCSetOperators(pc_, petsc_matrix_, petsc_matrix_), "PCSetOperators");
  if (kind == Kind::scalar) {
    petsc_check(
        VecCreateSeqWithArray(PETSC_COMM_SELF, 1, matrix_.rows, component_in_.data(), &component_),
        "VecCreateSeqWithArray");
    petsc_check(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, matrix_.rows, component_out_.data(),
                                      &component_solution_),
                "VecCreateSeqWithArray");
  }
}

NewtonPreconditioner::~NewtonPreconditioner() {
  petsc_release(VecDestroy(&component_), "VecDestroy");
  petsc_release(VecDestroy(&component_solution_), "VecDestroy");
  petsc_release(PCDestroy(&pc_), "PCDestroy");
  petsc_release(MatDestroy(&petsc_matrix_), "MatDestroy");
}

void NewtonPreconditioner::create_petsc_matrix(const SparseSymmetric& a, int block_size) {
  if (system_.distributed()) {
    create_distributed_matrix(a);
    return;
  }
  petsc_check(MatCreate(PETSC_COMM_SELF, &petsc_matrix_), "MatCreate");
  petsc_check(MatSetSizes(petsc_matrix_, a.rows, a.rows, a.rows, a.rows), "MatSetSizes");
  petsc_check(MatSetType(petsc_matrix_, MATSEQAIJ), "MatSetType");
  petsc_check(MatSetBlockSize(petsc_matrix_, block_size), "MatSetBlockSize");
  petsc_check(MatSeqAIJSetPreallocationCSR(petsc_matrix_, a.offsets.data(), a.columns.data(),
                                           a.values.data()),
              "MatSeqAIJSetPreallocationCSR");
  petsc_check(MatSetOption(petsc_matrix_, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
  petsc_check(MatSetOption(petsc_matrix_, MAT_SYMMETRY_ETERNAL, PETSC_TRUE), "MatSetOption");
  petsc_check(MatSetOption(petsc_matrix_, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE),
              "MatSetOption");
  // assembled by the preallocation; copy_values() changes the values in place only
  if (block_size == 3) threaded_product_ = multiply_over_threads(petsc_matrix_);
}

PetscInt NewtonPreconditioner::global_column(int c) const {
  const Families& families = system_.dynamics().model().families();
  return 3 * PetscInt(families.global_row(c / 3)) + c % 3;
}

// This rank's rows of `a` (3N×3N over the rows of the families, block size 3) in a MATMPIAIJ
// whose rows are distributed as the unknowns, its columns in the whole scene's numbering. The
// families number their rows in the order of the particles' ids, so each row's columns stay
// sorted.
void NewtonPreconditioner::create_distributed_matrix(const SparseSymmetric& a) {
  const int first = static_cast<int>(system_.first_unknown());
  const int rows = static_cast<int>(system_.end_unknown()) - first;
  std::vector<PetscInt> offsets(rows + 1), columns(a.offsets[first + rows] - a.offsets[first]);
  for (int r = 0; r <= rows; ++r) offsets[r] = a.offsets[first + r] - a.offsets[first];
  for (std::size_t k = 0; k < columns.size(); ++k)
    columns[k] = global_column(a.columns[a.offsets[first] + k]);
  petsc_check(MatCreate(system_.dynamics().halo()->comm(), &petsc_matrix_), "MatCreate");
  petsc_check(MatSetSizes(petsc_matrix_, rows, rows, PETSC_DETERMINE, PETSC_DETERMINE),
              "MatSetSizes");
  petsc_check(MatSetType(petsc_matrix_, MATMPIAIJ), "MatSetType");
  petsc_check(MatSetBlockSize(petsc_matrix_, 3), "MatSetBlockSize");
  petsc_check(MatMPIAIJSetPreallocationCSR(petsc_matrix_, offsets.data(), columns.data(),
                                           a.values.data() + a.offsets[first]),
              "MatMPIAIJSetPreallocationCSR");
  petsc_check(MatSetOption(petsc_matrix_, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
  petsc_check(MatSetOption(petsc_matrix_, MAT_SYMMETRY_ETERNAL, PETSC_TRUE), "MatSetOption");
  // A M + the one-hop majoriser or nearest stiffness (PSD), held rows on the diagonal: MUMPS
  // factors it as SPD (LLᵀ), and reports a matrix that is not
  if (kind_ != Kind::gamg)
    petsc_check(MatSetOption(petsc_matrix_, MAT_SPD, PETSC_TRUE), "MatSetOption");
  petsc_check(MatSetOption(petsc_matrix_, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE),
              "MatSetOption");
}

// The own rows of matrix_ into the PETSc matrix, in place.
void NewtonPreconditioner::copy_values() {
  if (!system_.distributed()) {
    PetscScalar* values;
    petsc_check(MatSeqAIJGetArray(petsc_matrix_, &values), "MatSeqAIJGetArray");
    std::memcpy(values, matrix_.values.data(), matrix_.values.size() * sizeof(double));
    petsc_check(MatSeqAIJRestoreArray(petsc_matrix_, &values), "MatSeqAIJRestoreArray");
    return;
  }
  const int first = static_cast<int>(system_.first_unknown());
  const PetscInt first_global = 3 * PetscInt(system_.dynamics().halo()->first_global());
  std::vector<PetscInt> columns;
  for (int r = first; r < static_cast<int>(system_.end_unknown()); ++r) {
    const int begin = matrix_.offsets[r], end = matrix_.offsets[r + 1];
    columns.resize(end - begin);
    for (int k = begin; k < end; ++k) columns[k - begin] = global_column(matrix_.columns[k]);
    const PetscInt row = first_global + (r - first);
    petsc_check(MatSetValues(petsc_matrix_, 1, &row, end - begin, columns.data(),
                             matrix_.values.data() + begin, INSERT_VALUES),
                "MatSetValues");
  }
  petsc_check(MatAssemblyBegin(petsc_matrix_, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  petsc_check(MatAssemblyEnd(petsc_matrix_, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
}

// + the loads' Hessian blocks ∇²B⁺ at z (NewtonSystem::add_potential_blocks) on each particle's
// own block; on the scalar matrix, the block's largest diagonal entry on the particle's row.
void NewtonPreconditioner::add_potential_blocks(const double* z) {
  if (!system_.add_potential_blocks(z, blocks_)) return;
  const int first = static_cast<int>(system_.first_unknown() / 3),
            end = static_cast<int>(system_.end_unknown() / 3);
  for (int i = first; i < end; ++i) {
    const double* b = &blocks_[9 * std::size_t(i)];
    if (std::all_of(b, b + 9, [](double v) { return v == 0; })) continue;
    if (kind_ == Kind::scalar) {
      matrix_.values[diagonal_[i]] += std::max({b[0], b[4], b[8]});
      continue;
    }
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) {
        const int at = matrix_.find(3 * i + a, 3 * i + c);
        if (at < 0) throw std::logic_error("a particle's own block is missing from the pattern");
        matrix_.values[at] += b[3 * a + c];
      }
  }
}

// shift_and_fix with the held rows' scale of the whole matrix: the largest diagonal over the
// ranks, as one rank takes it.
void NewtonPreconditioner::shift_and_hold(double inertia) {
  double scale = held_scale(matrix_, diagonal_, system_.mass(), inertia);
  if (system_.distributed()) scale = max_over_ranks(system_.dynamics().halo()->comm(), scale);
  shift_and_fix(matrix_, diagonal_, system_.mass(), inertia, system_.fixed(), scale);
}

void NewtonPreconditioner::refresh(const double* z) {
  Stiffness& stiffness = *system_.dynamics().model().stiffness();  // check() made sure
  const double inertia = system_.inertia();
  switch (kind_) {
    case Kind::tangent:
      if (system_.tangent() == NewtonSystem::Tangent::majoriser)
        stiffness.assemble_majoriser(z, matrix_);
      else
        stiffness.assemble_tangent(z, matrix_,
                                   system_.tangent() == NewtonSystem::Tangent::projected);
      add_potential_blocks(z);
      shift_and_hold(inertia);
      break;
    case Kind::majoriser:
      stiffness.assemble_majoriser(z, matrix_);
      add_potential_blocks(z);
      shift_and_hold(inertia);
      break;
    case Kind::nearest:
    case Kind::gamg:
      stiffness.assemble_nearest_stiffness(z, nearest_, matrix_);
      add_potential_blocks(z);
      shift_and_hold(inertia);
      break;
    case Kind::scalar:
      if (!scalar_assembled_) {
        stiffness.assemble_scalar_stiffness(scalar_stiffness_);
        scalar_assembled_ = true;
      }
      matrix_.values = scalar_stiffness_.values;
      add_potential_blocks(z);
      shift_scalar(matrix_, diagonal_, system_.mass(), inertia, system_.fixed());
      break;
    case Kind::automatic:
      break;
  }
  ++assemblies;
  if (cholesky_) {
    if (!cholesky_->factorize(matrix_)) throw not_positive_definite();
    ++factorizations;
    return;
  }
  copy_values();
  PCType type;
  petsc_check(PCGetType(pc_, &type), "PCGetType");
  if (std::strcmp(type, PCGAMG) == 0 && kind_ != Kind::scalar) {
    MPI_Comm comm;
    // The rigid-body modes at z: what the stiffness (nearly) does not resist (also when a
    // user's -precond_pc_type gamg picks multigrid for another kind's matrix).
    Vec coordinates;
    MatNullSpace modes;
    const PetscInt first = system_.first_unknown(), n = system_.end_unknown() - first;
    petsc_check(PetscObjectGetComm(reinterpret_cast<PetscObject>(petsc_matrix_), &comm),
                "PetscObjectGetComm");
    petsc_check(VecCreateMPIWithArray(comm, 3, n, PETSC_DETERMINE, z + first, &coordinates),
                "VecCreateMPIWithArray");
    petsc_check(MatNullSpaceCreateRigidBody(coordinates, &modes), "MatNullSpaceCreateRigidBody");
    petsc_check(MatSetNearNullSpace(petsc_matrix_, modes), "MatSetNearNullSpace");
    petsc_check(MatNullSpaceDestroy(&modes), "MatNullSpaceDestroy");
    petsc_check(VecDestroy(&coordinates), "VecDestroy");
  }
  // CHOLMOD reports a matrix that is not positive definite as a failed factorization. BLAS
  // threads help the factorization's dense blocks, not the solves (blas_threads.hpp).
  set_blas_threads(omp_get_max_threads());
  const PetscErrorCode code = PCSetUp(pc_);
  set_blas_threads(1);
  PCFailedReason reason = PC_NOERROR;
  if (code == 0) petsc_check(PCGetFailedReason(pc_, &reason), "PCGetFailedReason");
  bool failed = code != 0 || reason != PC_NOERROR;
  // every rank takes the same way (MUMPS reports a global status; other solvers may not)
  if (system_.distributed()) failed = any_over_ranks(system_.dynamics().halo()->comm(), failed);
  if (failed) {
    // CHOLMOD leaves a failed supernodal factor that it cannot refactorize ("cannot operate on
    // supernodal L"): without a reset every later refresh, the projected tangent's included,
    // would fail too. The next refresh analyses the pattern afresh.
    petsc_check(PCReset(pc_), "PCReset");
    petsc_check(PCSetOperators(pc_, petsc_matrix_, petsc_matrix_), "PCSetOperators");
    throw not_positive_definite();
  }
  if (std::strcmp(type, PCGAMG) == 0) smooth_once_per_level(pc_);
  ++factorizations;
}

RunError NewtonPreconditioner::not_positive_definite() const {
  // over several ranks the whole system's size (matrix_ holds the rank's rows)
  const int rows =
      system_.distributed() ? 3 * system_.dynamics().model().families().total_rows() : matrix_.rows;
  return RunError(fmt::format("the {} preconditioner's {}×{} matrix is not positive definite",
                              preconditioner_name(kind_), rows, rows));
}

void NewtonPreconditioner::apply(Vec r, Vec x) {
  ++back_solves;
  if (!cholesky_ && kind_ != Kind::scalar) {
    petsc_check(PCApply(pc_, r, x), "PCApply");
    return;
  }
  const PetscScalar* in;
  PetscScalar* out;
  petsc_check(VecGetArrayRead(r, &in), "VecGetArrayRead");
  petsc_check(VecGetArray(x, &out), "VecGetArray");
  if (kind_ != Kind::scalar) {
    cholesky_->solve(in, out);
  } else {
    // The scalar factor solves each component (component_ and component_solution_ hold the
    // arrays of component_in_ and component_out_ for PETSc's PC).
    const int n = matrix_.rows;
    for (int d = 0; d < 3; ++d) {
      for (int i = 0; i < n; ++i) component_in_[i] = in[3 * i + d];
      if (cholesky_) {
        cholesky_->solve(component_in_.data(), component_out_.data());
      } else {
        // component_in_ was written behind PETSc's back: a write access marks the vector changed.
        PetscScalar* written;
        petsc_check(VecGetArrayWrite(component_, &written), "VecGetArrayWrite");
        petsc_check(VecRestoreArrayWrite(component_, &written), "VecRestoreArrayWrite");
        petsc_check(PCApply(pc_, component_, component_solution_), "PCApply");
      }
      for (int i = 0; i < n; ++i) out[3 * i + d] = component_out_[i];
    }
  }
  petsc_check(VecRestoreArray(x, &out), "VecRestoreArray");
  petsc_check(VecRestoreArrayRead(r, &in), "VecRestoreArrayRead");
}

void NewtonPreconditioner::view(PetscViewer viewer) const {
  petsc_check(PetscViewerASCIIPrintf(viewer, "Fissure preconditioner: %s (refreshed %ld times)\n",
                                     preconditioner_name(kind_), factorizations),
              "PetscViewerASCIIPrintf");
  if (cholesky_) {
    petsc_check(PetscViewerASCIIPrintf(
                    viewer,
                    "  CHOLMOD supernodal factor kept in %s precision: %ld entries; solved on %d "
                    "threads as %d subtrees side by side and %d supernodes above them\n",
                    factor_precision_name(cholesky_->precision()), cholesky_->factor_entries(),
                    cholesky_->threads(), cholesky_->subtrees(), cholesky_->top_supernodes()),
                "PetscViewerASCIIPrintf");
  } else if (factorizations > 0) {
    if (threaded_product_)
      petsc_check(PetscViewerASCIIPrintf(viewer, "  its matrix multiplied over the threads\n"),
                  "PetscViewerASCIIPrintf");
    petsc_check(PCView(pc_, viewer), "PCView");
  }
}

}  // namespace fissure
