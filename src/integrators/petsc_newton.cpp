#include "integrators/petsc_newton.hpp"

#include <fmt/format.h>
#include <petscsnes.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "core/error.hpp"
#include "integrators/newton_line_search.hpp"
#include "integrators/newton_preconditioner.hpp"
#include "integrators/newton_system.hpp"
#include "integrators/petsc_session.hpp"
#include "integrators/refresh_reasons.hpp"
#include "parallel/halo.hpp"

namespace fissure {

namespace fs = std::filesystem;

struct PetscNewton::Solver {
  Solver(Dynamics& dynamics, const PetscNewtonSettings& settings)
      : system(dynamics, settings.tangent), scheme(settings.scheme, settings.rho_infinity) {}
  ~Solver() {
    petsc_release(SNESDestroy(&snes), "SNESDestroy");
    petsc_release(MatDestroy(&matrix), "MatDestroy");
    petsc_release(VecDestroy(&unknowns), "VecDestroy");
    petsc_release(VecDestroy(&residual), "VecDestroy");
    preconditioner.reset();
    petsc_release(PetscOptionsDestroy(&options), "PetscOptionsDestroy");
  }

  NewtonSystem system;
  ImplicitScheme scheme;
  // PETSc's vectors hold this rank's unknowns, the system's arrays all 3N (newton_system.hpp):
  // over several ranks the callbacks copy between them (scratch 3N each); on one rank they are
  // the same arrays.
  MPI_Comm comm = PETSC_COMM_SELF;
  std::vector<double> full_point, full_in, full_out;
  std::unique_ptr<NewtonPreconditioner> preconditioner;
  std::vector<double> acceleration;  // a_n
  bool have_acceleration = false;
  long increments = 0;  // static: load increments taken
  PetscOptions options = nullptr;
  SNES snes = nullptr;
  KSP ksp = nullptr;
  Mat matrix = nullptr;  // A M + K, matrix-free (MATSHELL)
  Vec unknowns = nullptr, residual = nullptr;
  std::exception_ptr error;  // an exception raised inside a PETSc callback
  PotentialLineSearch line_search;
  // Refresh policy (docs/integrators.md, "The linear solves"): the factor is refreshed at the
  // next Newton iteration when `pending` names a reason, when A or the tangent choice changed
  // since it was made, or when the last iterations converged too slowly.
  using Refresh = Refreshes::Reason;
  Refresh pending = Refreshes::first;
  Refreshes refreshes;
  double factor_inertia = -1;
  NewtonSystem::Tangent factor_tangent = NewtonSystem::Tangent::automatic;
  bool factor_failed = false;        // the last refresh met a matrix not positive definite
  int iterations_since_refresh = 0;  // in the current Newton solve
  bool solve_fresh = false;  // the last linear solve's factor was made at that iteration's point
  long contraction_refresh_step = -2;  // the step of the last refresh for a slow contraction
  std::vector<double> norms;           // |r_k| of the current Newton solve
  // |r| that round-off in the positions alone produces (residual_floor): no Newton iteration
  // can go below it, so a solve there has converged and its contraction means nothing.
  double floor = 0;
  double stiffness_bound = 0;  // λ_max of M⁻¹K^bw, from the stable explicit step
  double family_members = 1;   // n, the mean family's size
  bool reuse = true;
  double refresh_contraction = 0.25;
  int refresh_iterations = 6, refresh_krylov = 40;
  long steps = 0, newton_iterations = 0, krylov_iterations = 0;
  long tangent_fallbacks = 0;      // auto: steps redone with the projected tangent
  long step_halvings = 0;          // failed steps redone as two halves
  long fresh_newton_retries = 0;   // stages that failed with a reused factor, redone without
  long precision_raises = 0;       // half factors too inexact for their matrix: single from then on
  bool krylov = false;             // a Krylov method runs on the matrix-free tangent
  double linear_rtol = 1e-3;       // the Krylov method's relative tolerance (-ksp_rtol)
  bool linear_rtol_fixed = false;  // the user set -ksp_rtol: no stop at the Newton target
  long linear_solves_to_target = 0;  // Krylov solves stopped at the Newton target, not -ksp_rtol
  bool options_checked = false;
  // Newton's error test (newton_test: local_error, docs/integrators.md): the estimated error
  // η|Δz_k| of the stage's positions against 1% of the last step's local error estimate, in
  // positions and, divided by γh, in velocities (the stage velocity is (Y_i − Ŷ_i)/(γh)).
  bool error_test = false;
  double local_error_position = 0, local_error_velocity = 0;  // mass-weighted RMS; 0: none yet
  double gamma_h = 0;                                         // γh of the step being taken
  double eta = -1;            // θ/(1 − θ) of the last contraction measured; < 0: none yet
  double last_update = 0;     // |Δz_{k−1}|, mass-weighted RMS
  long error_test_stops = 0;  // Newton solves the error test stopped
  int stops_with_old_contraction = 0;  // ... after one iteration, since η was last measured
  bool evaluate_every_update = false;  // PetscNewtonSettings::evaluate_every_update
  bool step_unevaluated = false;  // the line search took the update without evaluating after it
};

namespace {

using Solver = PetscNewton::Solver;

// PETSc calls these; exceptions must not cross its C frames, so they are parked in the solver.
template <class F>
PetscErrorCode guarded(Solver* s, F&& body) {
  try {
    body();
    return 0;
  } catch (...) {
    s->error = std::current_exception();
    return PETSC_ERR_USER;
  }
}

// The 3N array the system reads for this rank's unknowns `local`: on one rank local itself;
// over several ranks `full` with local at the own range and, for a point (share), the ghosts'
// values from their ranks. Collective with share.
const double* to_full(Solver& s, const double* local, std::vector<double>& full, bool share) {
  if (!s.system.distributed()) return local;
  const std::size_t first = s.system.first_unknown(), end = s.system.end_unknown();
  full.resize(s.system.mass().size());
  std::copy(local, local + (end - first), full.begin() + first);
  if (share) s.system.dynamics().share(full.data());
  return full.data();
}

// Where the system writes a 3N result for `local`, and the copy back to it.
double* full_result(Solver& s, double* local) {
  if (!s.system.distributed()) return local;
  s.full_out.resize(s.system.mass().size());
  return s.full_out.data();
}
void from_full(const Solver& s, const double* full, double* local) {
  if (full == local) return;
  std::copy(full + s.system.first_unknown(), full + s.system.end_unknown(), local);
}

PetscErrorCode form_residual(SNES, Vec x, Vec r, void* context) {
  auto* s = static_cast<Solver*>(context);
  return guarded(s, [&] {
    const PetscScalar* z;
    PetscScalar* out;
    petsc_check(VecGetArrayRead(x, &z), "VecGetArrayRead");
    petsc_check(VecGetArray(r, &out), "VecGetArray");
    double* result = full_result(*s, out);
    s->system.residual(to_full(*s, z, s->full_point, true), result);
    from_full(*s, result, out);
    petsc_check(VecRestoreArray(r, &out), "VecRestoreArray");
    petsc_check(VecRestoreArrayRead(x, &z), "VecRestoreArrayRead");
  });
}

PetscErrorCode form_objective(SNES, Vec x, PetscReal* value, void* context) {
  auto* s = static_cast<Solver*>(context);
  return guarded(s, [&] {
    const PetscScalar* z;
    petsc_check(VecGetArrayRead(x, &z), "VecGetArrayRead");
    *value = s->system.objective(to_full(*s, z, s->full_point, true));
    petsc_check(VecRestoreArrayRead(x, &z), "VecRestoreArrayRead");
  });
}

// The largest λ ≤ 1 for which the update x − λy keeps the potentials' bounds
// (NewtonSystem::max_step); collective.
double bounded_step(Solver& s, Vec x, Vec y) {
  const PetscScalar* point;
  const PetscScalar* direction;
  petsc_check(VecGetArrayRead(x, &point), "VecGetArrayRead");
  petsc_check(VecGetArrayRead(y, &direction), "VecGetArrayRead");
  const std::size_t first = s.system.first_unknown(), end = s.system.end_unknown();
  std::vector<double> update(s.system.mass().size(), 0.0);
  for (std::size_t k = first; k < end; ++k) update[k] = -direction[k - first];
  const double alpha = s.system.max_step(to_full(s, point, s.full_point, true), update.data());
  petsc_check(VecRestoreArrayRead(y, &direction), "VecRestoreArrayRead");
  petsc_check(VecRestoreArrayRead(x, &point), "VecRestoreArrayRead");
  return alpha;
}

// Whether the last Newton iteration reduced |r| by less than refresh_contraction (above the
// round-off floor, where a contraction means nothing), with the factor alone making the Newton
// step. Under a Krylov method the step solves the exact tangent: a slow contraction there is the
// problem's nonlinearity (contact's active set), which neither a new factor nor a more precise
// one mends; a stale factor shows in the Krylov iterations instead.
bool contracted_slowly(const Solver& s) {
  const std::size_t k = s.norms.size();
  return !s.krylov && k >= 2 && s.norms[k - 2] > 10 * s.floor &&
         s.norms[k - 1] > s.refresh_contraction * s.norms[k - 2];
}

// Why the factor must be refreshed before this Newton iteration's linear solve, or none.
Solver::Refresh refresh_reason(Solver& s) {
  if (s.pending != Refreshes::none) return s.pending;
  if (!s.reuse) return Refreshes::every_iteration;
  if (!same_step_coefficient(s.system.inertia(), s.factor_inertia)) return Refreshes::step_size;
  if (s.system.tangent() != s.factor_tangent) return Refreshes::fallback;
  if (!s.preconditioner->follows_the_state()) return Refreshes::none;
  if (contracted_slowly(s)) return Refreshes::convergence;
  if (s.iterations_since_refresh >= s.refresh_iterations) return Refreshes::convergence;
  if (s.krylov && s.norms.size() >= 2) {
    PetscInt its = 0;
    petsc_check(KSPGetIterationNumber(s.ksp, &its), "KSPGetIterationNumber");
    if (its > s.refresh_krylov) return Refreshes::convergence;
  }
  return Refreshes::none;
}

// Inexact Newton that does not over-solve its last linear system: the Krylov method stops at
// 1e-3 of |r_k|, or sooner once its residual is half the one the Newton test stops at (max of
// -snes_atol, -snes_rtol |r_0| and the round-off floor), which that iteration's step then
// reaches up to the remainder the linearization leaves. A -ksp_rtol the user sets holds as given.
void set_linear_tolerance(Solver& s) {
  if (s.linear_rtol_fixed || s.norms.empty()) return;
  PetscReal atol, rtol, stol;
  PetscInt iterations, evaluations;
  petsc_check(SNESGetTolerances(s.snes, &atol, &rtol, &stol, &iterations, &evaluations),
              "SNESGetTolerances");
  const double target = std::max({atol, rtol * s.norms.front(), s.floor});
  const double relative = std::max(s.linear_rtol, 0.5 * target / s.norms.back());
  if (relative > s.linear_rtol) ++s.linear_solves_to_target;
  petsc_check(
      KSPSetTolerances(s.ksp, std::min(relative, 0.5), PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT),
      "KSPSetTolerances");
}

// The Newton matrix is matrix-free; what PETSc calls the Jacobian evaluation only moves its
// linearization point, and refreshes the preconditioner's factor when the policy asks.
PetscErrorCode form_jacobian(SNES, Vec x, Mat, Mat, void* context) {
  auto* s = static_cast<Solver*>(context);
  return guarded(s, [&] {
    const PetscScalar* local;
    petsc_check(VecGetArrayRead(x, &local), "VecGetArrayRead");
    const double* z = to_full(*s, local, s->full_point, true);
    s->system.linearize(z);
    const Solver::Refresh reason = refresh_reason(*s);
    // A slow contraction of an iteration whose factor was made at its own point is not
    // staleness: where that factor is in half precision, its rounding times the matrix's
    // condition is the likely cause (backward Euler at 300 explicit steps: contraction 0.48 in
    // half, 0.009 in single), which a refresh in half would repeat. Nor, likely, is a slow
    // contraction that comes back within a step of the refresh the last one caused (SDIRK4 at
    // 25 ms on the 9,726-particle slow bend: the stages' first iterations contracted by 0.3 in
    // half and 0.03 in single, and half refreshed at 8 stages in a row). Only the contraction
    // test says so: the iteration and Krylov limits do not measure the factor's accuracy.
    const bool slow = (reason == Refreshes::convergence || reason == Refreshes::every_iteration) &&
                      contracted_slowly(*s);
    if (slow && (s->solve_fresh || s->steps - s->contraction_refresh_step <= 1) &&
        s->preconditioner->raise_precision())
      ++s->precision_raises;
    if (slow) s->contraction_refresh_step = s->steps;
    s->solve_fresh = false;
    if (reason != Refreshes::none) {
      s->pending = Refreshes::none;
      s->factor_inertia = s->system.inertia();
      s->factor_tangent = s->system.tangent();
      s->iterations_since_refresh = 0;
      ++s->refreshes.count[reason];
      try {
        s->preconditioner->refresh(z);
      } catch (const RunError&) {
        // Not positive definite: the solve fails like a failed linear solve, and the step is
        // redone (auto tangent: with the projected tangent) or halved.
        s->pending = Refreshes::fallback;
        s->factor_failed = true;
        petsc_check(VecRestoreArrayRead(x, &local), "VecRestoreArrayRead");
        throw;
      }
      s->solve_fresh = true;
    }
    ++s->iterations_since_refresh;
    petsc_check(VecRestoreArrayRead(x, &local), "VecRestoreArrayRead");
    if (s->krylov) set_linear_tolerance(*s);
  });
}

PetscErrorCode apply_newton_matrix(Mat matrix, Vec v, Vec out) {
  void* context;
  PetscCall(MatShellGetContext(matrix, &context));
  auto* s = static_cast<Solver*>(context);
  return guarded(s, [&] {
    const PetscScalar* in;
    PetscScalar* result;
    petsc_check(VecGetArrayRead(v, &in), "VecGetArrayRead");
    petsc_check(VecGetArray(out, &result), "VecGetArray");
    double* full = full_result(*s, result);
    s->system.apply(to_full(*s, in, s->full_in, false), full);  // apply() shares v's ghosts
    from_full(*s, full, result);
    petsc_check(VecRestoreArray(out, &result), "VecRestoreArray");
    petsc_check(VecRestoreArrayRead(v, &in), "VecRestoreArrayRead");
  });
}

PetscErrorCode apply_preconditioner(PC pc, Vec r, Vec x) {
  void* context;
  PetscCall(PCShellGetContext(pc, &context));
  auto* s = static_cast<Solver*>(context);
  return guarded(s, [&] { s->preconditioner->apply(r, x); });
}

PetscErrorCode view_preconditioner(PC pc, PetscViewer viewer) {
  void* context;
  PetscCall(PCShellGetContext(pc, &context));
  auto* s = static_cast<Solver*>(context);
  return guarded(s, [&] { s->preconditioner->view(viewer); });
}

// Fraction of the step's local error estimate the Newton error may reach (the free block of
// test_sdirk_newton_default.cpp: 1% leaves ESDIRK4 a Newton error of 0.02 of its own).
constexpr double kNewtonErrorFraction = 0.01;

// Solves in a row the error test may stop after one iteration with an η measured before; the
// next takes a second iteration, which measures θ again (a twentieth more iterations at most).
constexpr int kStopsWithOldContraction = 20;

// |v| over the unknowns not held, mass-weighted RMS; collective over the ranks.
double mass_weighted_size(const Solver& s, Vec v) {
  const PetscScalar* values;
  petsc_check(VecGetArrayRead(v, &values), "VecGetArrayRead");
  const auto& m = s.system.mass();
  const auto& fixed = s.system.fixed();
  const std::size_t first = s.system.first_unknown(), end = s.system.end_unknown();
  double sum = 0, mass = 0;
  for (std::size_t k = first; k < end; ++k)
    if (!fixed[k]) sum += m[k] * values[k - first] * values[k - first], mass += m[k];
  petsc_check(VecRestoreArrayRead(v, &values), "VecRestoreArrayRead");
  return std::sqrt(s.system.sum_over_ranks(sum) / s.system.sum_over_ranks(mass));
}

// η after iteration `it` whose update has size `size`: θ/(1 − θ) from this update and the one
// before; after the first, η of the last solve that measured one. Negative: none or θ ≥ 1.
double eta_after(const Solver& s, PetscInt it, double size) {
  if (it < 2 || s.last_update <= 0) return s.eta;
  const double theta = size / s.last_update;
  return theta < 1 ? theta / (1 - theta) : -1;
}

// Whether the error test stops after iteration `it` whose update has size `size`.
bool error_test_stops(const Solver& s, PetscInt it, double size) {
  const double eta = eta_after(s, it, size);
  if (eta < 0 || s.local_error_position <= 0) return false;
  if (it == 1 && s.stops_with_old_contraction >= kStopsWithOldContraction) return false;
  const double tolerance =
      kNewtonErrorFraction * std::min(s.local_error_position, s.gamma_h * s.local_error_velocity);
  return eta * size <= tolerance;
}

// Hairer and Wanner's test for simplified Newton (Solving ODEs II, IV.8): after iteration k the
// error is about η|Δz_k| with η = θ/(1 − θ), θ = |Δz_k|/|Δz_{k−1}|; after the first, η of the
// last solve that measured one (their max(η_old, ε)^0.8, which grows η from solve to solve, made
// the glass bar of docs/accuracy.md take 1.8 iterations per stage instead of 1.0). Collective
// over the ranks.
void newton_error_test(Solver& s, SNES snes, PetscInt it, SNESConvergedReason* reason) {
  if (it == 0) {
    s.last_update = 0;
    s.step_unevaluated = false;
    return;
  }
  Vec dz;
  petsc_check(SNESGetSolutionUpdate(snes, &dz), "SNESGetSolutionUpdate");
  const double size = mass_weighted_size(s, dz);
  // a step the line search took unevaluated was accepted by this test already
  const bool unevaluated = std::exchange(s.step_unevaluated, false);
  const bool stops = unevaluated || error_test_stops(s, it, size);
  if (it >= 2 && s.last_update > 0) {
    s.eta = eta_after(s, it, size);
    s.stops_with_old_contraction = 0;
  }
  s.last_update = size;
  if (!unevaluated && (*reason != SNES_CONVERGED_ITERATING || !stops)) return;
  *reason = SNES_CONVERGED_SNORM_RELATIVE;
  ++s.error_test_stops;
  if (it == 1) ++s.stops_with_old_contraction;
}

// An update in a stage that is not the step's last is taken without evaluating E and ∇E after
// it when the error test will stop there (the test reads only the updates' sizes): nothing
// reads them, as the stage derivatives follow from the stage's solution alone
// (ImplicitScheme::finish_stage). The step's last stage is evaluated: the constraint reactions
// are the forces at its solution.
bool accept_unevaluated(Solver& s, Vec direction) {
  if (!s.error_test || s.scheme.last_stage() || s.evaluate_every_update) return false;
  PetscInt done = 0;  // the update being taken is iteration done + 1
  petsc_check(SNESGetIterationNumber(s.snes, &done), "SNESGetIterationNumber");
  s.step_unevaluated = error_test_stops(s, done + 1, mass_weighted_size(s, direction));
  return s.step_unevaluated;
}

// |z − z̄|, the 2-norm of the positions about their mean z̄ (per axis) over all unknowns: the
// scene's extent, which does not change when the scene moves; collective over the ranks.
double extent_norm(const Solver& s, SNES snes) {
  Vec x;
  petsc_check(SNESGetSolution(snes, &x), "SNESGetSolution");
  const PetscScalar* z;
  petsc_check(VecGetArrayRead(x, &z), "VecGetArrayRead");
  const std::size_t first = s.system.first_unknown(), end = s.system.end_unknown();
  double mean[3] = {0, 0, 0};
  for (std::size_t k = first; k < end; ++k) mean[k % 3] += z[k - first];
  const double particles = s.system.sum_over_ranks(double(end - first) / 3);
  for (double& m : mean) m = s.system.sum_over_ranks(m) / std::max(particles, 1.0);
  double sum = 0;
  for (std::size_t k = first; k < end; ++k) {
    const double d = z[k - first] - mean[k % 3];
    sum += d * d;
  }
  petsc_check(VecRestoreArrayRead(x, &z), "VecRestoreArrayRead");
  return std::sqrt(s.system.sum_over_ranks(sum));
}

// PETSc's tests (-snes_rtol, -snes_atol, ... as the user set them), convergence at the
// round-off floor of the residual, and the error test where it is on. PETSc's step test
// (-snes_stol) compares the last update with stol |z|, which grows with the scene's distance from
// the origin (a scene 1 km away stopped Newton after one iteration where it takes two at the
// origin); it is given the positions' extent about their mean instead (extent_norm), so that
// moving a scene changes nothing but round-off.
PetscErrorCode converged(SNES snes, PetscInt it, PetscReal, PetscReal snorm, PetscReal fnorm,
                         SNESConvergedReason* reason, void* context) {
  auto* s = static_cast<Solver*>(context);
  double extent = 0;
  PetscCall(guarded(s, [&] { extent = extent_norm(*s, snes); }));
  PetscCall(SNESConvergedDefault(snes, it, extent, snorm, fnorm, reason, nullptr));
  if (*reason == SNES_CONVERGED_ITERATING && it > 0 && fnorm <= s->floor)
    *reason = SNES_CONVERGED_FNORM_ABS;
  if (s->error_test) PetscCall(guarded(s, [&] { newton_error_test(*s, snes, it, reason); }));
  // A short last update is no convergence where the potentials' bound cut it (a particle held
  // at a collider's surface by the line search while the solution lies beyond): a stall, which
  // the step's fallback (halving) takes up.
  if (*reason == SNES_CONVERGED_SNORM_RELATIVE && s->line_search.last_bounded)
    *reason = SNES_DIVERGED_LINE_SEARCH;
  return 0;
}

// Records |r_k| for the refresh policy.
PetscErrorCode monitor(SNES, PetscInt iteration, PetscReal norm, void* context) {
  auto* s = static_cast<Solver*>(context);
  if (iteration == 0) {
    s->norms.clear();
    s->iterations_since_refresh = 0;
  }
  s->norms.push_back(norm);
  return 0;
}

// The options database of one integrator, from integrator.petsc_options.
PetscOptions read_petsc_options(const PetscNewtonSettings& settings, const std::string& file) {
  PetscOptions options;
  petsc_check(PetscOptionsCreate(&options), "PetscOptionsCreate");
  if (PetscOptionsInsertString(options, settings.petsc_options.c_str()) != 0) {
    petsc_check(PetscOptionsDestroy(&options), "PetscOptionsDestroy");
    throw InputError(file, "integrator.petsc_options",
                     fmt::format("PETSc cannot read '{}'", settings.petsc_options));
  }
  return options;
}

void set_up_petsc(Solver& s, const PetscNewtonSettings& settings, const std::string& file) {
  s.options = read_petsc_options(settings, file);
  using P = PetscNewtonSettings::Preconditioner;
  using K = PetscNewtonSettings::Krylov;
  const Families& families = s.system.dynamics().model().families();
  P kind = settings.preconditioner;
  if (kind == P::automatic)
    kind = s.system.dynamics().model().stiffness()->one_hop_matrices()
               ? choose_preconditioner(families, s.system.distributed())
               : P::tangent;
  if (kind == P::tangent && s.system.tangent() == NewtonSystem::Tangent::majoriser)
    kind = P::majoriser;
  s.preconditioner =
      std::make_unique<NewtonPreconditioner>(s.system, kind, s.options, settings.factor_precision);
  K krylov = settings.krylov;
  // auto: the tangent's factor alone, which is the Newton matrix where it was made; but
  // contact's Hessian changes with its active set (and with ESDIRK4's stage weights (γ +
  // a_i1)/γ), which CG on the exact tangent follows with one factor as its preconditioner
  // (docs/integrators.md, "Contact")
  if (krylov == K::automatic)
    krylov = kind == P::tangent && !s.system.has_contact() ? K::none : K::cg;
  s.krylov = krylov != K::none;
  s.reuse = settings.reuse_factor;
  s.refresh_contraction = settings.refresh_contraction;
  s.refresh_iterations = settings.refresh_iterations;
  s.refresh_krylov = settings.refresh_krylov;

  // over several ranks: this rank's unknowns, on the halo's communicator
  const PetscInt n = static_cast<PetscInt>(s.system.end_unknown() - s.system.first_unknown());
  if (const Halo* halo = s.system.dynamics().halo()) s.comm = halo->comm();
  petsc_check(MatCreateShell(s.comm, n, n, PETSC_DETERMINE, PETSC_DETERMINE, &s, &s.matrix),
              "MatCreateShell");
  petsc_check(MatShellSetOperation(s.matrix, MATOP_MULT,
                                   reinterpret_cast<void (*)(void)>(apply_newton_matrix)),
              "MatShellSetOperation");
  petsc_check(MatSetOption(s.matrix, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
  petsc_check(VecCreateMPI(s.comm, n, PETSC_DETERMINE, &s.unknowns), "VecCreateMPI");
  petsc_check(VecDuplicate(s.unknowns, &s.residual), "VecDuplicate");

  petsc_check(SNESCreate(s.comm, &s.snes), "SNESCreate");
  petsc_check(PetscObjectSetOptions(reinterpret_cast<PetscObject>(s.snes), s.options), "options");
  petsc_check(SNESSetType(s.snes, SNESNEWTONLS), "SNESSetType");
  petsc_check(SNESSetFunction(s.snes, s.residual, form_residual, &s), "SNESSetFunction");
  petsc_check(SNESSetJacobian(s.snes, s.matrix, s.matrix, form_jacobian, &s), "SNESSetJacobian");
  petsc_check(SNESSetObjective(s.snes, form_objective, &s), "SNESSetObjective");
  // Defaults a user may override: the solution error of rtol 1e-6 is far below the scheme's
  // truncation error at the steps these schemes are for; looser ones are not, on a free body
  // (test_sdirk_newton_default.cpp, docs/integrators.md).
  petsc_check(SNESSetTolerances(s.snes, 1e-50, 1e-6, 1e-10, 50, 10000), "SNESSetTolerances");
  SNESLineSearch search;
  petsc_check(SNESGetLineSearch(s.snes, &search), "SNESGetLineSearch");
  petsc_check(PetscObjectSetOptions(reinterpret_cast<PetscObject>(search), s.options), "options");
  petsc_check(SNESLineSearchSetType(search, SNESLINESEARCHSHELL), "SNESLineSearchSetType");
  s.line_search.system = &s.system;
  s.line_search.accept_unevaluated = [&s](Vec direction) {
    bool accept = false;
    return guarded(&s, [&] { accept = accept_unevaluated(s, direction); }) == 0 && accept;
  };
  if (s.system.has_potentials())
    s.line_search.max_step = [&s](Vec x, Vec y) {
      double alpha = 1;
      // an error is parked in s.error and ends the solve at its next callback
      guarded(&s, [&] { alpha = bounded_step(s, x, y); });
      return alpha;
    };
  petsc_check(SNESLineSearchShellSetUserFunc(search, potential_line_search, &s.line_search),
              "SNESLineSearchShellSetUserFunc");
  PC pc;
  petsc_check(SNESGetKSP(s.snes, &s.ksp), "SNESGetKSP");
  petsc_check(PetscObjectSetOptions(reinterpret_cast<PetscObject>(s.ksp), s.options), "options");
  switch (krylov) {
    case K::none:
      petsc_check(KSPSetType(s.ksp, KSPPREONLY), "KSPSetType");
      break;
    case K::gmres:
      petsc_check(KSPSetType(s.ksp, KSPGMRES), "KSPSetType");
      petsc_check(KSPSetPCSide(s.ksp, PC_RIGHT), "KSPSetPCSide");
      break;
    default:
      petsc_check(KSPSetType(s.ksp, KSPCG), "KSPSetType");
      break;
  }
  if (krylov != K::none) {
    // Inexact Newton: each linear solve to 1e-3 of its right-hand side or to the Newton target
    // (set_linear_tolerance), judged on the true residual (no extra preconditioner application
    // per iteration).
    petsc_check(KSPSetNormType(s.ksp, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
    petsc_check(KSPSetTolerances(s.ksp, 1e-3, 1e-50, 1e50, 500), "KSPSetTolerances");
  }
  petsc_check(KSPGetPC(s.ksp, &pc), "KSPGetPC");
  petsc_check(PetscObjectSetOptions(reinterpret_cast<PetscObject>(pc), s.options), "options");
  petsc_check(PCSetType(pc, PCSHELL), "PCSetType");
  petsc_check(PCShellSetContext(pc, &s), "PCShellSetContext");
  petsc_check(PCShellSetApply(pc, apply_preconditioner), "PCShellSetApply");
  petsc_check(PCShellSetView(pc, view_preconditioner), "PCShellSetView");
  petsc_check(PCShellSetName(pc, "fissure"), "PCShellSetName");
  petsc_check(SNESMonitorSet(s.snes, monitor, &s, nullptr), "SNESMonitorSet");
  petsc_check(SNESSetConvergenceTest(s.snes, converged, &s, nullptr), "SNESSetConvergenceTest");
  const double stable = s.system.dynamics().model().stable_time_step();
  s.stiffness_bound = std::isfinite(stable) ? 4 / (stable * stable) : 0;
  s.family_members =
      std::max(1.0, double(families.directed_bonds()) / std::max(1, families.rows()));
  petsc_check(SNESSetFromOptions(s.snes), "SNESSetFromOptions");
  PetscReal rtol, atol, dtol;
  PetscInt iterations;
  petsc_check(KSPGetTolerances(s.ksp, &rtol, &atol, &dtol, &iterations), "KSPGetTolerances");
  s.linear_rtol = rtol;
  PetscBool set = PETSC_FALSE;
  petsc_check(PetscOptionsHasName(s.options, nullptr, "-ksp_rtol", &set), "PetscOptionsHasName");
  s.linear_rtol_fixed = set;
  using T = PetscNewtonSettings::NewtonTest;
  s.error_test = settings.newton_test == T::local_error;
  s.evaluate_every_update = settings.evaluate_every_update;
  if (settings.newton_test == T::automatic &&
      settings.scheme == PetscNewtonSettings::Scheme::esdirk4) {
    // a user who sets the residual's tolerances asks for the residual test. Contact's active set
    // changes from one Newton iterate to the next, which the test's contraction estimate does
    // not model: with colliders it stopped ESDIRK4 short of the solution on the incline of
    // test_implicit_contact.cpp, and the step created energy.
    bool residual_set = false;
    for (const char* name : {"-snes_rtol", "-snes_atol", "-snes_stol"}) {
      petsc_check(PetscOptionsHasName(s.options, nullptr, name, &set), "PetscOptionsHasName");
      residual_set = residual_set || set;
    }
    s.error_test = !residual_set && !s.system.has_contact();
  }
  // settings made in code are not parsed
  if (const std::string refusal = newton_test_refusal(settings); !refusal.empty())
    throw InputError(file, "integrator.newton_test", refusal);
}

// Near the solution the potential's decrease along the Newton step, at most |r|·|Δz|, falls
// below the round-off of E itself; a line search then fails although the step has converged.
bool at_round_off(Solver& s) {
  Vec r, dz;
  PetscReal residual = 0, update = 0;
  petsc_check(SNESGetFunction(s.snes, &r, nullptr, nullptr), "SNESGetFunction");
  petsc_check(SNESGetSolutionUpdate(s.snes, &dz), "SNESGetSolutionUpdate");
  petsc_check(VecNorm(r, NORM_2, &residual), "VecNorm");
  petsc_check(VecNorm(dz, NORM_2, &update), "VecNorm");
  return residual * update <= 1e-12 * s.system.objective_magnitude();
}

// The residual's round-off from the positions' alone, each known to ε|z_k|: the inertia term
// A m_k (z_k − ỹ_k) carries A m_k ε|z_k|; the internal force on k sums its n family members'
// bond forces, each of stiffness about K_kk/n with K_kk ≤ λ_max m_k/2 (λ_max ≥ ‖M⁻¹K‖ the stable
// step's Gershgorin bound, whose row sum counts the diagonal and as much again off it), whose
// round-off errors add up as √n of them: λ_max m_k ε|z_k|/(2√n). Taken at twice that, and summed in
// 2-norm over the free unknowns. On a glass bar 1 km from the origin (test_far_from_origin.cpp)
// the residual stagnates at 0.14 of this floor; the Gershgorin row sum alone (λ_max m_k ε|z_k|)
// is 65 times it there, and stopped Newton after one iteration where it takes two at the origin.
double residual_floor(const Solver& s, const std::vector<double>& z) {
  const double scale = s.system.inertia() + s.stiffness_bound / std::sqrt(s.family_members);
  const auto& m = s.system.mass();
  const auto& fixed = s.system.fixed();
  double sum = 0;
  for (std::size_t k = s.system.first_unknown(); k < s.system.end_unknown(); ++k)
    if (!fixed[k]) sum += (m[k] * z[k]) * (m[k] * z[k]);
  return std::numeric_limits<double>::epsilon() * scale * std::sqrt(s.system.sum_over_ranks(sum));
}

// Options the user gave that PETSc never read are most likely typos.
void warn_unused_options(Solver& s, const std::string& file) {
  int rank = 0;
  petsc_check(MPI_Comm_rank(s.comm, &rank), "MPI_Comm_rank");
  PetscInt count = 0;
  char** names = nullptr;
  char** values = nullptr;
  petsc_check(PetscOptionsLeftGet(s.options, &count, &names, &values), "PetscOptionsLeftGet");
  for (PetscInt k = 0; k < count && rank == 0; ++k)
    fmt::print(stderr, "warning: {}: integrator.petsc_options: PETSc did not use -{}\n", file,
               names[k]);
  petsc_check(PetscOptionsLeftRestore(s.options, &count, &names, &values),
              "PetscOptionsLeftRestore");
}

}  // namespace

PetscNewton::PetscNewton(const PetscNewtonSettings& settings, const std::string& file)
    : settings_(settings), file_(file) {}

PetscNewton::~PetscNewton() = default;

void PetscNewton::check(const Dynamics& dynamics) const {
  if (!dynamics.model().stiffness())
    throw InputError(file_, "integrator.type",
                     fmt::format("material.model '{}' provides no stiffness for petsc_newton; "
                                 "use material.model: lps",
                                 dynamics.model().name()));
  using P = PetscNewtonSettings::Preconditioner;
  if (!dynamics.model().stiffness()->one_hop_matrices()) {
    if (settings_.preconditioner != P::automatic && settings_.preconditioner != P::tangent)
      throw InputError(file_, "integrator.preconditioner",
                       "this model factors its tangent only (surface_correction: fictitious): "
                       "use auto or tangent");
    if (settings_.tangent == PetscNewtonSettings::Tangent::majoriser)
      throw InputError(file_, "integrator.tangent",
                       "this model has no bond-wise majoriser (surface_correction: fictitious): "
                       "use auto, exact or projected");
  }
  // Contact the step does not resolve, where a scheme has no energy bound there
  // (test_contact_blocks.cpp): sdirk4 gained 26% of the energy the 10 cm glass block fell
  // through, at 70 times the explicit step (and slid 20% too far on the incline with friction);
  // under self-contact the SDIRK schemes let stacked blocks sink into each other (esdirk4) or
  // gained energy (sdirk3 1.2%, sdirk4 more).
  using Scheme = PetscNewtonSettings::Scheme;
  bool contact = false, self_contact = false;
  for (const LoadPotential* p : dynamics.potentials()) {
    contact = contact || p->contact();
    self_contact = self_contact || (p->contact() && p->couples());
  }
  const bool sdirk = settings_.scheme == Scheme::sdirk3 || settings_.scheme == Scheme::sdirk4 ||
                     settings_.scheme == Scheme::esdirk4;
  if (contact && settings_.scheme == Scheme::sdirk4)
    throw InputError(file_, "integrator.scheme",
                     "'sdirk4' has no energy bound at a contact its step does not resolve (a "
                     "glass block dropped 3 cm gained 26% of the energy it fell through at 70 "
                     "times the explicit step); with colliders or self-contact use esdirk4, "
                     "sdirk3 or backward_euler (docs/integrators.md, \"Contact\")");
  if (self_contact && sdirk)
    throw InputError(file_, "integrator.scheme",
                     fmt::format("'{}' with self-contact (contact.self) lets bodies resting on "
                                 "each other sink in or gain energy at large steps; use "
                                 "backward_euler, newmark or alpha (docs/integrators.md, "
                                 "\"Contact\")",
                                 scheme_name(settings_.scheme)));
  if (const std::string entry = dynamics.implicit_refusal(); !entry.empty())
    throw InputError(file_, "integrator.type",
                     fmt::format("petsc_newton cannot take the stiff load booked as '{}': it "
                                 "gives no potential (energy, gradient and Hessian) for the "
                                 "step's minimisation (docs/architecture.md, loads); use an "
                                 "explicit integrator",
                                 entry));
  ensure_petsc();
  PetscOptions options = read_petsc_options(settings_, file_);
  petsc_check(PetscOptionsDestroy(&options), "PetscOptionsDestroy");
}

double PetscNewton::step(Dynamics& dynamics, State& state, double dt) {
  if (!solver_) {
    check(dynamics);
    solver_ = std::make_unique<Solver>(dynamics, settings_);
    set_up_petsc(*solver_, settings_, file_);
    if (const std::vector<double>* a = find_array(restored_, "integrator.acceleration")) {
      solver_->acceleration = *a;
      solver_->have_acceleration = true;
    }
    if (const std::vector<double>* n = find_array(restored_, "integrator.increments"))
      solver_->increments = static_cast<long>(n->at(0));
    // a raised factor stays raised over a resume, so that the resumed steps are the same bits
    if (const std::vector<double>* r = find_array(restored_, "integrator.precision_raises")) {
      solver_->precision_raises = static_cast<long>(r->at(0));
      if (solver_->precision_raises > 0) solver_->preconditioner->raise_precision();
    }
    restored_.clear();
  }
  Solver& s = *solver_;
  // static: the load ramp counts increments, so a failed one is not split
  advance(dynamics, state, dt, s.scheme.is_static() ? 0 : settings_.max_step_halvings);
  return dt;
}

bool PetscNewton::distributable() const {
  return NewtonPreconditioner::distributable(settings_.preconditioner, settings_.tangent);
}

void PetscNewton::bonds_changed() {
  if (!solver_) return;
  solver_->preconditioner->bonds_changed();
  solver_->pending = Refreshes::bonds;
  // a_n (Newmark's and an ESDIRK's first stage) from the forces of the bonds left, not from the
  // step's difference formula over the bonds it started with.
  solver_->have_acceleration = false;
  solver_->local_error_position = solver_->local_error_velocity = 0;
}

void PetscNewton::advance(Dynamics& dynamics, State& state, double dt, int halvings) {
  Solver& s = *solver_;
  if (!s.have_acceleration) {
    s.acceleration.resize(state.position.size());
    // without contact's forces, which each stage takes at its end (implicit_scheme.hpp)
    dynamics.acceleration_without_contact(state.time, state.position.data(), state.velocity.data(),
                                          s.acceleration.data());
    s.have_acceleration = true;
  }
  const State start = state;
  const std::vector<double> acceleration = s.acceleration;
  const std::string failure = attempt(dynamics, state, dt);
  if (failure.empty()) return;
  state = start;
  s.acceleration = acceleration;
  // the error test waits for a step of the new size to estimate its local error
  s.local_error_position = s.local_error_velocity = 0;
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
  // static: loads ramp linearly over integrator.steps increments, then stay
  const double load =
      s.scheme.is_static() ? std::min(1.0, double(++s.increments) / settings_.steps) : 1.0;
  std::vector<double> z, contact;  // contact: contact's acceleration at z (NewtonSystem)
  const std::size_t first = s.system.first_unknown(), end = s.system.end_unknown();
  s.gamma_h = s.scheme.gamma() * dt;
  // One Newton solve from z with the given tangent; false if PETSc failed (e.g. the tangent
  // was not positive definite) or Newton did not converge.
  PetscInt iterations = 0;
  SNESConvergedReason reason = SNES_CONVERGED_ITERATING;
  using Tangent = NewtonSystem::Tangent;
  auto solve = [&](Tangent tangent) {
    s.system.use_tangent(tangent);
    PetscScalar* x;
    petsc_check(VecGetArray(s.unknowns, &x), "VecGetArray");
    std::copy(z.begin() + first, z.begin() + end, x);
    petsc_check(VecRestoreArray(s.unknowns, &x), "VecRestoreArray");
    const PetscErrorCode code = SNESSolve(s.snes, nullptr, s.unknowns);
    if (s.error) {
      std::exception_ptr error = std::exchange(s.error, nullptr);
      try {
        std::rethrow_exception(error);
      } catch (const RunError&) {
        // a factor that is not positive definite is a failed solve; anything else is an error
        if (!std::exchange(s.factor_failed, false)) throw;
      }
    }
    PetscInt krylov = 0;
    petsc_check(SNESGetIterationNumber(s.snes, &iterations), "SNESGetIterationNumber");
    petsc_check(SNESGetLinearSolveIterations(s.snes, &krylov), "SNESGetLinearSolveIterations");
    s.newton_iterations += iterations;
    if (s.krylov) s.krylov_iterations += krylov;
    if (code != 0) {
      reason = SNES_DIVERGED_LINEAR_SOLVE;
      return false;
    }
    petsc_check(SNESGetConvergedReason(s.snes, &reason), "SNESGetConvergedReason");
    if (reason == SNES_DIVERGED_LINE_SEARCH && at_round_off(s)) reason = SNES_CONVERGED_ITS;
    return reason > 0;
  };
  for (int stage = 0; stage < s.scheme.stages(); ++stage) {
    s.scheme.predict(state, s.acceleration, dynamics.damping(), dt, stage);
    if (s.scheme.explicit_stage()) continue;
    z = s.system.begin_step(s.scheme, state, s.acceleration, dt, load);
    s.floor = residual_floor(s, z);
    // auto: the exact tangent converges quadratically where A M + K is positive definite; where
    // it is not, or Newton fails with it, the stage is redone with the projected tangent K⁺ ⪰ K.
    auto solve_stage = [&] {
      if (settings_.tangent == Tangent::automatic) {
        if (!solve(Tangent::exact)) {
          ++s.tangent_fallbacks;
          return solve(Tangent::projected);
        }
        return true;
      }
      return solve(settings_.tangent);
    };
    bool solved = solve_stage();
    // A reused factor converges linearly at best: a stage that fails with it is redone with a
    // fresh factorization at every iteration (Newton's own convergence) before the step is
    // halved.
    if (!solved && s.reuse) {
      ++s.fresh_newton_retries;
      s.reuse = false;
      solved = solve_stage();
      s.reuse = true;
      s.pending = Refreshes::fallback;
    }
    if (!solved && settings_.tangent != Tangent::automatic &&
        reason == SNES_DIVERGED_LINEAR_SOLVE) {
      return fmt::format(
          "petsc_newton ({}): the linear solve failed in the step from t = {:.6g} s: the '{}' "
          "tangent is not positive definite there; use integrator.tangent: auto or projected",
          scheme_name(settings_.scheme), state.time, tangent_name(settings_.tangent));
    }
    if (reason < 0 && s.line_search.last_bounded)
      return fmt::format(
          "petsc_newton ({}): Newton stalled in the step from t = {:.6g} s with dt = {:.3g} s: "
          "its last update was cut to keep particles out of a collider (or within self-contact's "
          "skin) while the solution lies beyond, after {} iterations. The contact penalty is too "
          "soft to stop this impact within a particle's radius at this step: raise "
          "contact.stiffness or try a smaller time.dt",
          scheme_name(settings_.scheme), state.time, dt, iterations);
    if (reason < 0)
      return fmt::format(
          "petsc_newton ({}): Newton did not converge in the step from t = {:.6g} s with dt = "
          "{:.3g} s: {} after {} iterations. Try a smaller time.dt, or raise -snes_max_it or "
          "loosen -snes_rtol in integrator.petsc_options",
          scheme_name(settings_.scheme), state.time, dt, SNESConvergedReasons[reason], iterations);
    if (!s.options_checked) {
      warn_unused_options(s, file_);
      s.options_checked = true;
    }
    const PetscScalar* solution;
    petsc_check(VecGetArrayRead(s.unknowns, &solution), "VecGetArrayRead");
    std::copy(solution, solution + (end - first), z.begin() + first);
    petsc_check(VecRestoreArrayRead(s.unknowns, &solution), "VecRestoreArrayRead");
    dynamics.share(z.data());
    s.system.potential_acceleration(z.data(), contact);
    s.scheme.finish_stage(z, contact, dt);
  }
  if (s.error_test) {
    const ImplicitScheme::ErrorSums e =
        s.scheme.local_error(dt, s.system.mass(), s.system.fixed(), first, end);
    const double mass = s.system.sum_over_ranks(e.mass);
    s.local_error_position = mass > 0 ? std::sqrt(s.system.sum_over_ranks(e.position) / mass) : 0;
    s.local_error_velocity = mass > 0 ? std::sqrt(s.system.sum_over_ranks(e.velocity) / mass) : 0;
  }
  s.scheme.correct(z, contact, state, s.acceleration, dt);
  dynamics.share(state.position.data());  // for the post-step and the next step
  dynamics.set_constraint_reactions(s.system.reactions());
  state.time += dt;
  dynamics.constrain_velocity(state.time, state.velocity.data());
  ++s.steps;
  return {};
}

NamedArrays PetscNewton::saved_state() const {
  if (!solver_) return restored_;
  NamedArrays state = {{"integrator.increments", {double(solver_->increments)}},
                       {"integrator.precision_raises", {double(solver_->precision_raises)}}};
  if (solver_->have_acceleration)
    state.emplace_back("integrator.acceleration", solver_->acceleration);
  return state;
}

void PetscNewton::restore_state(const NamedArrays& state) { restored_ = state; }

Statistics PetscNewton::statistics() const {
  if (!solver_) return {};
  const Solver& s = *solver_;
  const NewtonSystem& y = s.system;
  const NewtonPreconditioner& p = *s.preconditioner;
  Statistics stats = {{"newton_iterations", double(s.newton_iterations)},
                      {"linear_solves", double(s.newton_iterations)},  // one per Newton iteration
                      {"krylov_iterations", double(s.krylov_iterations)},
                      {"linear_solves_to_target", double(s.linear_solves_to_target)},
                      {"line_search_cuts", double(s.line_search.cuts)},
                      {"line_search_bounded", double(s.line_search.bounded)},
                      {"assemblies", double(p.assemblies)},
                      {"factorizations", double(p.factorizations)},
                      {"back_solves", double(p.back_solves)},
                      {"tangent_products", double(y.tangent_products)},
                      {"linearizations", double(y.linearizations)},
                      {"tangent_fallbacks", double(s.tangent_fallbacks)},
                      {"step_halvings", double(s.step_halvings)},
                      {"fresh_newton_retries", double(s.fresh_newton_retries)},
                      {"factor_precision_raises", double(s.precision_raises)},
                      {"residual_evaluations", double(y.residual_passes)},
                      {"objective_evaluations", double(y.objective_passes)},
                      {"reused_evaluations", double(y.cache_hits)},
                      {"newton_error_test_stops", double(s.error_test_stops)},
                      {"unevaluated_updates", double(s.line_search.unevaluated)}};
  s.refreshes.append_to(stats);
  return stats;
}

std::string PetscNewton::solver_view() const {
  if (!solver_) return {};
  // PETSc's string viewer abbreviates; its ASCII viewer writes the full report to a file.
  const fs::path path = fs::temp_directory_path() /
                        fmt::format("fissure_kspview_{}.txt", static_cast<const void*>(this));
  PetscViewer viewer;
  petsc_check(PetscViewerASCIIOpen(solver_->comm, path.c_str(), &viewer), "PetscViewerASCIIOpen");
  petsc_check(KSPView(solver_->ksp, viewer), "KSPView");
  petsc_check(PetscViewerDestroy(&viewer), "PetscViewerDestroy");
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  fs::remove(path);
  return text.str();
}

IntegratorKind petsc_newton_kind() {
  return {"petsc_newton", petsc_newton_keys(), read_petsc_newton_settings,
          [](const IntegratorSettings& settings, const std::string& file) {
            return std::make_unique<PetscNewton>(options_of<PetscNewtonSettings>(settings), file);
          }};
}

}  // namespace fissure
