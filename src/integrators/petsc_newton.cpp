#include "integrators/petsc_newton.hpp"

#include <fmt/format.h>
#include <petscsnes.h>

#include <algorithm>
#include <exception>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "integrators/newton_system.hpp"
#include "integrators/petsc_session.hpp"

namespace fissure {

namespace fs = std::filesystem;

struct PetscNewton::Solver {
  Solver(Dynamics& dynamics, const IntegratorSettings& settings)
      : system(dynamics, settings.tangent), scheme(settings.scheme, settings.rho_infinity) {}
  ~Solver() {
    SNESDestroy(&snes);
    MatDestroy(&matrix);
    VecDestroy(&unknowns);
    VecDestroy(&residual);
    PetscOptionsDestroy(&options);
  }

  NewtonSystem system;
  ImplicitScheme scheme;
  std::vector<double> acceleration;  // a_n
  bool have_acceleration = false;
  long increments = 0;  // static: load increments taken
  PetscOptions options = nullptr;
  SNES snes = nullptr;
  Mat matrix = nullptr;
  Vec unknowns = nullptr, residual = nullptr;
  std::exception_ptr error;  // an exception raised inside a PETSc callback
  long steps = 0, newton_iterations = 0, linear_solves = 0, line_search_cuts = 0;
  long factorizations = 0, function_evaluations = 0, objective_evaluations = 0;
  long tangent_fallbacks = 0;  // auto: steps redone with the projected tangent
  long step_halvings = 0;      // failed steps redone as two halves
  bool options_checked = false;
};

namespace {

using Solver = PetscNewton::Solver;

// PETSc calls these; exceptions must not cross its C frames, so they are parked in the solver.
PetscErrorCode form_residual(SNES, Vec x, Vec r, void* context) {
  auto* s = static_cast<Solver*>(context);
  try {
    const PetscScalar* z;
    PetscScalar* out;
    VecGetArrayRead(x, &z);
    VecGetArray(r, &out);
    s->system.residual(z, out);
    VecRestoreArray(r, &out);
    VecRestoreArrayRead(x, &z);
    ++s->function_evaluations;
    return 0;
  } catch (...) {
    s->error = std::current_exception();
    return PETSC_ERR_USER;
  }
}

PetscErrorCode form_hessian(SNES, Vec x, Mat, Mat matrix, void* context) {
  auto* s = static_cast<Solver*>(context);
  try {
    const PetscScalar* z;
    VecGetArrayRead(x, &z);
    s->system.hessian(z);
    VecRestoreArrayRead(x, &z);
    // Same pattern, same order (sorted columns): the values are copied over as they are.
    PetscScalar* values;
    MatSeqAIJGetArray(matrix, &values);
    const auto& v = s->system.matrix().values;
    std::memcpy(values, v.data(), v.size() * sizeof(double));
    MatSeqAIJRestoreArray(matrix, &values);
    ++s->factorizations;
    return 0;
  } catch (...) {
    s->error = std::current_exception();
    return PETSC_ERR_USER;
  }
}

PetscErrorCode form_objective(SNES, Vec x, PetscReal* value, void* context) {
  auto* s = static_cast<Solver*>(context);
  try {
    const PetscScalar* z;
    VecGetArrayRead(x, &z);
    *value = s->system.objective(z);
    VecRestoreArrayRead(x, &z);
    ++s->objective_evaluations;
    return 0;
  } catch (...) {
    s->error = std::current_exception();
    return PETSC_ERR_USER;
  }
}

// Counts Newton iterations whose line search had to shorten the step.
PetscErrorCode count_cuts(SNES snes, PetscInt iteration, PetscReal, void* context) {
  if (iteration == 0) return 0;
  SNESLineSearch search;
  PetscReal lambda = 1;
  SNESGetLineSearch(snes, &search);
  SNESLineSearchGetLambda(search, &lambda);
  if (lambda < 1) ++static_cast<Solver*>(context)->line_search_cuts;
  return 0;
}

void set_up_petsc(Solver& s, const IntegratorSettings& settings, const std::string& file) {
  petsc_check(PetscOptionsCreate(&s.options), "options");
  if (PetscOptionsInsertString(s.options, settings.petsc_options.c_str()) != 0)
    throw InputError(file, "integrator.petsc_options",
                     fmt::format("PETSc cannot read '{}'", settings.petsc_options));
  const SparseSymmetric& a = s.system.matrix();
  petsc_check(MatCreate(PETSC_COMM_SELF, &s.matrix), "MatCreate");
  petsc_check(MatSetSizes(s.matrix, a.rows, a.rows, a.rows, a.rows), "MatSetSizes");
  petsc_check(MatSetType(s.matrix, MATSEQAIJ), "MatSetType");
  petsc_check(
      MatSeqAIJSetPreallocationCSR(s.matrix, a.offsets.data(), a.columns.data(), a.values.data()),
      "MatSeqAIJSetPreallocationCSR");
  petsc_check(MatSetOption(s.matrix, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
  petsc_check(MatSetOption(s.matrix, MAT_SYMMETRY_ETERNAL, PETSC_TRUE), "MatSetOption");
  petsc_check(MatSetOption(s.matrix, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE), "MatSetOption");
  petsc_check(VecCreateSeq(PETSC_COMM_SELF, a.rows, &s.unknowns), "VecCreateSeq");
  petsc_check(VecDuplicate(s.unknowns, &s.residual), "VecDuplicate");

  petsc_check(SNESCreate(PETSC_COMM_SELF, &s.snes), "SNESCreate");
  petsc_check(PetscObjectSetOptions(reinterpret_cast<PetscObject>(s.snes), s.options), "options");
  petsc_check(SNESSetType(s.snes, SNESNEWTONLS), "SNESSetType");
  petsc_check(SNESSetFunction(s.snes, s.residual, form_residual, &s), "SNESSetFunction");
  petsc_check(SNESSetJacobian(s.snes, s.matrix, s.matrix, form_hessian, &s), "SNESSetJacobian");
  petsc_check(SNESSetObjective(s.snes, form_objective, &s), "SNESSetObjective");
  // Defaults a user may override: the solution error of rtol 1e-6 is far below the scheme's
  // truncation error at the steps these schemes are for (docs/integrators.md).
  petsc_check(SNESSetTolerances(s.snes, 1e-50, 1e-6, 1e-10, 50, 10000), "SNESSetTolerances");
  SNESLineSearch search;
  petsc_check(SNESGetLineSearch(s.snes, &search), "SNESGetLineSearch");
  petsc_check(PetscObjectSetOptions(reinterpret_cast<PetscObject>(search), s.options), "options");
  petsc_check(SNESLineSearchSetType(search, SNESLINESEARCHBT), "SNESLineSearchSetType");
  KSP ksp;
  PC pc;
  petsc_check(SNESGetKSP(s.snes, &ksp), "SNESGetKSP");
  petsc_check(PetscObjectSetOptions(reinterpret_cast<PetscObject>(ksp), s.options), "options");
  petsc_check(KSPSetType(ksp, KSPPREONLY), "KSPSetType");
  petsc_check(KSPGetPC(ksp, &pc), "KSPGetPC");
  petsc_check(PetscObjectSetOptions(reinterpret_cast<PetscObject>(pc), s.options), "options");
  petsc_check(PCSetType(pc, PCCHOLESKY), "PCSetType");
  petsc_check(PCFactorSetMatSolverType(pc, MATSOLVERCHOLMOD), "PCFactorSetMatSolverType");
  petsc_check(SNESMonitorSet(s.snes, count_cuts, &s, nullptr), "SNESMonitorSet");
  petsc_check(SNESSetFromOptions(s.snes), "SNESSetFromOptions");
}

// Near the solution the potential's decrease along the Newton step, at most |r|·|Δz|, falls
// below the round-off of E itself; a line search then fails although the step has converged.
bool at_round_off(Solver& s) {
  Vec r, dz;
  PetscReal residual = 0, update = 0;
  SNESGetFunction(s.snes, &r, nullptr, nullptr);
  SNESGetSolutionUpdate(s.snes, &dz);
  VecNorm(r, NORM_2, &residual);
  VecNorm(dz, NORM_2, &update);
  return residual * update <= 1e-12 * s.system.objective_magnitude();
}

// Options the user gave that PETSc never read are most likely typos.
void warn_unused_options(Solver& s, const std::string& file) {
  PetscInt count = 0;
  char** names = nullptr;
  char** values = nullptr;
  if (PetscOptionsLeftGet(s.options, &count, &names, &values) != 0) return;
  for (PetscInt k = 0; k < count; ++k)
    fmt::print(stderr, "warning: {}: integrator.petsc_options: PETSc did not use -{}\n", file,
               names[k]);
  PetscOptionsLeftRestore(s.options, &count, &names, &values);
}

}  // namespace

PetscNewton::PetscNewton(const IntegratorSettings& settings, const std::string& file)
    : settings_(settings), file_(file) {}

PetscNewton::~PetscNewton() = default;

double PetscNewton::step(Dynamics& dynamics, State& state, double dt) {
  if (!solver_) {
    if (!dynamics.model().has_stiffness())
      throw InputError(file_, "integrator.type",
                       fmt::format("material.model '{}' provides no stiffness for petsc_newton; "
                                   "use material.model: lps",
                                   dynamics.model().name()));
    ensure_petsc();
    solver_ = std::make_unique<Solver>(dynamics, settings_);
    set_up_petsc(*solver_, settings_, file_);
    if (const std::vector<double>* a = find_array(restored_, "integrator.acceleration")) {
      solver_->acceleration = *a;
      solver_->have_acceleration = true;
    }
    if (const std::vector<double>* n = find_array(restored_, "integrator.increments"))
      solver_->increments = static_cast<long>(n->at(0));
    restored_.clear();
  }
  Solver& s = *solver_;
  // static: the load ramp counts increments, so a failed one is not split
  advance(dynamics, state, dt, s.scheme.is_static() ? 0 : settings_.max_step_halvings);
  return dt;
}

void PetscNewton::advance(Dynamics& dynamics, State& state, double dt, int halvings) {
  Solver& s = *solver_;
  const State start = state;
  const std::vector<double> acceleration = s.acceleration;
  const std::string failure = attempt(dynamics, state, dt);
  if (failure.empty()) return;
  state = start;
  s.acceleration = acceleration;
  if (halvings == 0)
    throw RunError(settings_.max_step_halvings > 0 && !s.scheme.is_static()
                       ? fmt::format("{} (the step was already halved {} times: "
                                     "integrator.max_step_halvings)",
                                     failure, settings_.max_step_halvings)
                       : failure);
  // Fallback: redo the step as two halves, each halved again where it fails.
  ++s.step_halvings;
  advance(dynamics, state, 0.5 * dt, halvings - 1);
  advance(dynamics, state, 0.5 * dt, halvings - 1);
}

std::string PetscNewton::attempt(Dynamics& dynamics, State& state, double dt) {
  Solver& s = *solver_;
  if (!s.have_acceleration) {
    s.acceleration.resize(state.position.size());
    dynamics.acceleration(state.time, state.position.data(), state.velocity.data(),
                          s.acceleration.data());
    s.have_acceleration = true;
  }
  // static: loads ramp linearly over integrator.steps increments, then stay
  const double load =
      s.scheme.is_static() ? std::min(1.0, double(++s.increments) / settings_.steps) : 1.0;
  s.scheme.predict(state, s.acceleration, dynamics.damping(), dt);
  std::vector<double> z = s.system.begin_step(s.scheme, state, dt, load);
  // One Newton solve from z with the given tangent; false if PETSc failed (e.g. the tangent
  // was not positive definite) or Newton did not converge.
  PetscInt iterations = 0;
  SNESConvergedReason reason = SNES_CONVERGED_ITERATING;
  auto solve = [&](const std::string& tangent) {
    s.system.use_tangent(tangent);
    PetscScalar* x;
    VecGetArray(s.unknowns, &x);
    std::copy(z.begin(), z.end(), x);
    VecRestoreArray(s.unknowns, &x);
    const PetscErrorCode code = SNESSolve(s.snes, nullptr, s.unknowns);
    if (s.error) std::rethrow_exception(std::exchange(s.error, nullptr));
    PetscInt linear = 0;
    SNESGetIterationNumber(s.snes, &iterations);
    SNESGetLinearSolveIterations(s.snes, &linear);
    s.newton_iterations += iterations;
    s.linear_solves += linear;
    if (code != 0) {
      reason = SNES_DIVERGED_LINEAR_SOLVE;
      return false;
    }
    SNESGetConvergedReason(s.snes, &reason);
    if (reason == SNES_DIVERGED_LINE_SEARCH && at_round_off(s)) reason = SNES_CONVERGED_ITS;
    return reason > 0;
  };
  // auto: the exact tangent converges quadratically where A M + K is positive definite; where it
  // is not, or Newton fails with it, the step is redone with the projected tangent K⁺ ⪰ K.
  if (settings_.tangent == "auto") {
    if (!solve("exact")) {
      ++s.tangent_fallbacks;
      solve("projected");
    }
  } else if (!solve(settings_.tangent) && reason == SNES_DIVERGED_LINEAR_SOLVE) {
    return fmt::format(
        "petsc_newton ({}): the linear solve failed in the step from t = {:.6g} s: the '{}' "
        "tangent is not positive definite there; use integrator.tangent: auto or projected",
        settings_.scheme, state.time, settings_.tangent);
  }
  if (reason < 0)
    return fmt::format(
        "petsc_newton ({}): Newton did not converge in the step from t = {:.6g} s with dt = "
        "{:.3g} s: {} after {} iterations. Try a smaller time.dt, or raise -snes_max_it or "
        "loosen -snes_rtol in integrator.petsc_options",
        settings_.scheme, state.time, dt, SNESConvergedReasons[reason], iterations);
  if (!s.options_checked) {
    warn_unused_options(s, file_);
    s.options_checked = true;
  }
  const PetscScalar* solution;
  VecGetArrayRead(s.unknowns, &solution);
  std::copy(solution, solution + z.size(), z.begin());
  VecRestoreArrayRead(s.unknowns, &solution);
  s.scheme.correct(z, state, s.acceleration, dt);
  dynamics.set_constraint_reactions(s.system.reactions());
  state.time += dt;
  dynamics.constrain_velocity(state.time, state.velocity.data());
  ++s.steps;
  return {};
}

NamedArrays PetscNewton::saved_state() const {
  if (!solver_) return restored_;
  NamedArrays state = {{"integrator.increments", {double(solver_->increments)}}};
  if (solver_->have_acceleration)
    state.emplace_back("integrator.acceleration", solver_->acceleration);
  return state;
}

void PetscNewton::restore_state(const NamedArrays& state) { restored_ = state; }

Statistics PetscNewton::statistics() const {
  if (!solver_) return {};
  const Solver& s = *solver_;
  return {{"newton_iterations", double(s.newton_iterations)},
          {"linear_solves", double(s.linear_solves)},
          {"line_search_cuts", double(s.line_search_cuts)},
          {"factorizations", double(s.factorizations)},
          {"tangent_fallbacks", double(s.tangent_fallbacks)},
          {"step_halvings", double(s.step_halvings)},
          {"residual_evaluations", double(s.function_evaluations)},
          {"objective_evaluations", double(s.objective_evaluations)}};
}

std::string PetscNewton::solver_view() const {
  if (!solver_) return {};
  // PETSc's string viewer abbreviates; its ASCII viewer writes the full report to a file.
  const fs::path path = fs::temp_directory_path() /
                        fmt::format("fissure_kspview_{}.txt", static_cast<const void*>(this));
  KSP ksp;
  PetscViewer viewer;
  SNESGetKSP(solver_->snes, &ksp);
  PetscViewerASCIIOpen(PETSC_COMM_SELF, path.c_str(), &viewer);
  KSPView(ksp, viewer);
  PetscViewerDestroy(&viewer);
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  fs::remove(path);
  return text.str();
}

}  // namespace fissure
