#include "integrators/arkode.hpp"

#include <arkode/arkode_arkstep.h>
#include <fmt/format.h>
#include <nvector/nvector_mpiplusx.h>
#include <nvector/nvector_serial.h>

#include <algorithm>
#include <cstdio>
#include <exception>

#include "core/error.hpp"
#include "integrators/arkode_linear_solver.hpp"
#include "parallel/halo.hpp"

namespace fissure {

struct Arkode::Solver {
  explicit Solver(Dynamics& d) : dynamics(d) {
    if (SUNContext_Create(nullptr, &context) != 0)
      throw RunError("SUNDIALS: SUNContext_Create failed");
  }
  ~Solver() {
    ARKStepFree(&memory);
    if (linear_solver && SUNLinSolFree(linear_solver) != 0)
      std::fprintf(stderr, "warning: SUNDIALS: SUNLinSolFree failed\n");
    N_VDestroy(u);
    N_VDestroy(local);
    if (SUNContext_Free(&context) != 0)
      std::fprintf(stderr, "warning: SUNDIALS: SUNContext_Free failed\n");
  }
  Dynamics& dynamics;
  SUNContext context = nullptr;
  void* memory = nullptr;
  N_Vector u = nullptr;  // [y − origin; v] of rows [first, first + count/3)
  // Over several ranks: u is an MPI+X vector over the ranks' `local` parts, each [y − origin; v]
  // of its own rows; velocity and acceleration are 3N over the rank's rows (own and ghosts).
  N_Vector local = nullptr;
  std::size_t first = 0, count = 0;  // in coordinates: 3 × the first row, 3 × the rows
  bool distributed = false;
  std::vector<double> velocity, acceleration;
  // The positions at the first step: ARKODE integrates the displacement from them, so rtol
  // weighs the motion rather than the distance from the coordinate origin.
  std::vector<double> origin;
  std::vector<double> position;  // origin + u's first half, for the right-hand sides
  SUNLinearSolver linear_solver = nullptr;
  std::unique_ptr<ReducedNewtonSystem> reduced;
  std::exception_ptr error;  // an exception raised inside an ARKODE callback
  double fixed_step = 0;
  Statistics carried;  // the counters of the runs before the last re-initialisation
  ARKRhsFn explicit_rhs = nullptr, implicit_rhs = nullptr;
};

namespace {

using Solver = Arkode::Solver;
using Acceleration = void (Dynamics::*)(double, const double*, const double*, double*);

// u̇ = [v (if with_velocity, else 0); a(t, y, v)] for one part of the right-hand side, over the
// rows u holds (all on one rank).
template <Acceleration part, bool with_velocity>
int rhs(realtype t, N_Vector u, N_Vector u_dot, void* user_data) {
  auto* s = static_cast<Solver*>(user_data);
  try {
    const std::size_t n = s->count, first = s->first;
    const double* displacement = N_VGetArrayPointer(u);
    const double* v = displacement + n;
    double* out = N_VGetArrayPointer(u_dot);
    for (std::size_t k = 0; k < n; ++k)
      s->position[first + k] = s->origin[first + k] + displacement[k];
    if constexpr (with_velocity)
      std::copy(v, v + n, out);
    else
      std::fill(out, out + n, 0.0);
    if (!s->distributed) {
      (s->dynamics.*part)(t, s->position.data(), v, out + n);
      return 0;
    }
    // the dynamics reads and writes all the rank's rows, the ghosts' positions from the halo
    std::copy(v, v + n, s->velocity.begin() + first);
    s->dynamics.share(s->position.data());
    (s->dynamics.*part)(t, s->position.data(), s->velocity.data(), s->acceleration.data());
    std::copy(s->acceleration.begin() + first, s->acceleration.begin() + first + n, out + n);
    return 0;
  } catch (...) {
    s->error = std::current_exception();
    return -1;
  }
}

}  // namespace

Arkode::Arkode(const ArkodeSettings& settings, const std::string& file)
    : settings_(settings), file_(file), method_(*settings.method) {}

Arkode::~Arkode() = default;

void Arkode::check(const Dynamics& dynamics) const {
  if (method_.kind != ArkodeMethod::Kind::explicit_rk && !dynamics.model().stiffness())
    throw InputError(file_, "integrator.method",
                     fmt::format("'{}' is implicit, and material.model '{}' provides no "
                                 "stiffness; use material.model: lps or an explicit method",
                                 method_.name, dynamics.model().name()));
  // Without one-hop matrices ARKODE's linear solver is untested, and slow or stalled where it was
  // tried (docs/integrators.md): each CG iteration rebuilds every row's Hessian; with
  // reuse_factor: true the first step's factor (ARKODE's first step is near 1e-13 s) is kept
  // while the step grows by orders of magnitude, and a free vibrating 250-particle block did not
  // get past 2 µs in minutes; refactorized at each γ change, a held one took 0.13 s per step.
  if (method_.kind != ArkodeMethod::Kind::explicit_rk &&
      !dynamics.model().stiffness()->one_hop_matrices())
    throw InputError(file_, "integrator.method",
                     fmt::format("'{}' is implicit, and ARKODE's linear solver needs the nearest "
                                 "members' matrices, which surface_correction: fictitious has "
                                 "not; use integrator.type: petsc_newton or an explicit method",
                                 method_.name));
}

double Arkode::step(Dynamics& dynamics, State& state, double dt) {
  const std::size_t n = state.position.size();
  if (!solver_) {
    check(dynamics);
    solver_ = std::make_unique<Solver>(dynamics);
    Solver& s = *solver_;
    s.first = 3 * std::size_t(dynamics.first_row());
    s.count = 3 * std::size_t(dynamics.end_row()) - s.first;
    s.distributed = dynamics.halo() != nullptr;
    if (s.distributed) {
      s.local = N_VNew_Serial(static_cast<sunindextype>(2 * s.count), s.context);
      if (!s.local) throw RunError("SUNDIALS: N_VNew_Serial failed");
      s.u = N_VMake_MPIPlusX(dynamics.halo()->comm(), s.local, s.context);
      if (!s.u) throw RunError("SUNDIALS: N_VMake_MPIPlusX failed");
      s.velocity = state.velocity;
      s.acceleration.resize(n);
    } else {
      s.u = N_VNew_Serial(static_cast<sunindextype>(2 * n), s.context);
      if (!s.u) throw RunError("SUNDIALS: N_VNew_Serial failed");
    }
    s.origin = state.position;
    s.position = state.position;
    using K = ArkodeMethod::Kind;
    switch (method_.kind) {
      case K::explicit_rk:
        s.explicit_rhs = rhs<&Dynamics::acceleration, true>;
        break;
      case K::implicit_rk:
        s.implicit_rhs = rhs<&Dynamics::acceleration, true>;
        break;
      case K::imex:
        s.explicit_rhs = rhs<&Dynamics::explicit_acceleration, false>;
        s.implicit_rhs = rhs<&Dynamics::implicit_acceleration, true>;
        break;
    }
  }
  Solver& s = *solver_;
  if (!s.memory || reinitialise_) {
    double* u = N_VGetArrayPointer(s.u);
    const std::size_t first = s.first, rows = s.count;
    for (std::size_t k = 0; k < rows; ++k) u[k] = state.position[first + k] - s.origin[first + k];
    std::copy(state.velocity.begin() + first, state.velocity.begin() + first + rows, u + rows);
    if (!s.memory) {
      s.memory = ARKStepCreate(s.explicit_rhs, s.implicit_rhs, state.time, s.u, s.context);
      if (!s.memory) throw RunError("ARKODE: ARKStepCreate failed");
      arkode_check(ARKStepSetUserData(s.memory, &s), "ARKStepSetUserData");
      arkode_check(ARKStepSetTableNum(s.memory, method_.implicit_table, method_.explicit_table),
                   "ARKStepSetTableNum");
      arkode_check(ARKStepSStolerances(s.memory, settings_.rtol, settings_.atol),
                   "ARKStepSStolerances");
      arkode_check(ARKStepSetMaxNumSteps(s.memory, -1), "ARKStepSetMaxNumSteps");
      if (s.implicit_rhs) {
        using P = ArkodeSettings::Preconditioner;
        P kind = settings_.preconditioner;
        if (kind == P::automatic)
          kind = choose_arkode_preconditioner(s.origin.size() / 3, s.distributed);
        s.reduced = std::make_unique<ReducedNewtonSystem>(
            dynamics, s.memory, s.origin, settings_.reuse_factor, settings_.refresh_krylov,
            settings_.factor_precision, kind == P::nearest);
        s.linear_solver = make_reduced_linear_solver(s.context, s.reduced.get(), &s.error);
        arkode_check(ARKStepSetLinearSolver(s.memory, s.linear_solver, nullptr),
                     "ARKStepSetLinearSolver");
        // A projected or stale tangent makes Newton converge linearly: allow more than the
        // default 3 iterations.
        arkode_check(ARKStepSetMaxNonlinIters(s.memory, 10), "ARKStepSetMaxNonlinIters");
      }
    } else {
      // Re-initialising resets ARKODE's counters and its step size: keep both.
      s.carried = arkode_counters();
      realtype last_step = 0;
      arkode_check(ARKStepGetLastStep(s.memory, &last_step), "ARKStepGetLastStep");
      arkode_check(ARKStepReInit(s.memory, s.explicit_rhs, s.implicit_rhs, state.time, s.u),
                   "ARKStepReInit");
      if (!settings_.fixed_step && last_step > 0)
        arkode_check(ARKStepSetInitStep(s.memory, last_step), "ARKStepSetInitStep");
    }
    s.fixed_step = 0;
    reinitialise_ = false;
  }
  if (settings_.fixed_step && dt != s.fixed_step) {
    arkode_check(ARKStepSetFixedStep(s.memory, dt), "ARKStepSetFixedStep");
    s.fixed_step = dt;
  }
  const double stop = state.time + dt;
  arkode_check(ARKStepSetStopTime(s.memory, stop), "ARKStepSetStopTime");
  realtype reached = state.time;
  const int flag = ARKStepEvolve(s.memory, stop, s.u, &reached, ARK_ONE_STEP);
  if (s.error) std::rethrow_exception(std::exchange(s.error, nullptr));
  if (flag < 0)
    throw RunError(fmt::format(
        "arkode ({}): the step from t = {:.6g} s failed: {}. Try a looser rtol/atol, a smaller "
        "time.dt or another method{}",
        method_.name, state.time, ARKStepGetReturnFlagName(flag),
        dynamics.colliders() && method_.kind != ArkodeMethod::Kind::explicit_rk
            ? "; arkode takes colliders explicitly, so its implicit methods need a step that "
              "resolves the contacts: for large steps with contact use petsc_newton "
              "(docs/integrators.md, \"Contact\")"
            : ""));
  const double* u = N_VGetArrayPointer(s.u);
  const std::size_t first = s.first, rows = s.count;
  for (std::size_t k = 0; k < rows; ++k) state.position[first + k] = s.origin[first + k] + u[k];
  std::copy(u + rows, u + 2 * rows, state.velocity.begin() + first);
  dynamics.share(state.position.data());  // the post-step reads the ghosts' new positions
  const double taken = reached - state.time;
  state.time = reached;
  return taken;
}

void Arkode::set_tolerances(double rtol, double atol) {
  settings_.rtol = rtol;
  settings_.atol = atol;
  if (solver_ && solver_->memory)
    arkode_check(ARKStepSStolerances(solver_->memory, rtol, atol), "ARKStepSStolerances");
}

void Arkode::bonds_changed() {
  reinitialise_ = true;
  if (solver_ && solver_->reduced) solver_->reduced->bonds_changed();
}

// ARKODE's own counters, which a re-initialisation resets (Solver::carried keeps the earlier
// runs').
Statistics Arkode::arkode_counters() const {
  void* m = solver_->memory;
  long steps = 0, attempts = 0, error_failures = 0, explicit_rhs = 0, implicit_rhs = 0;
  long newton = 0, convergence_failures = 0, setups = 0;
  arkode_check(ARKStepGetNumSteps(m, &steps), "ARKStepGetNumSteps");
  arkode_check(ARKStepGetNumStepAttempts(m, &attempts), "ARKStepGetNumStepAttempts");
  arkode_check(ARKStepGetNumErrTestFails(m, &error_failures), "ARKStepGetNumErrTestFails");
  arkode_check(ARKStepGetNumRhsEvals(m, &explicit_rhs, &implicit_rhs), "ARKStepGetNumRhsEvals");
  Statistics stats = {{"steps", double(steps)},
                      {"step_attempts", double(attempts)},
                      {"error_test_failures", double(error_failures)},
                      {"explicit_rhs_evaluations", double(explicit_rhs)},
                      {"implicit_rhs_evaluations", double(implicit_rhs)}};
  if (solver_->reduced) {
    arkode_check(ARKStepGetNumNonlinSolvIters(m, &newton), "ARKStepGetNumNonlinSolvIters");
    arkode_check(ARKStepGetNumNonlinSolvConvFails(m, &convergence_failures),
                 "ARKStepGetNumNonlinSolvConvFails");
    arkode_check(ARKStepGetNumLinSolvSetups(m, &setups), "ARKStepGetNumLinSolvSetups");
    stats.emplace_back("newton_iterations", double(newton));
    stats.emplace_back("newton_convergence_failures", double(convergence_failures));
    stats.emplace_back("linear_setups", double(setups));
  }
  for (std::size_t k = 0; k < solver_->carried.size(); ++k)
    stats[k].second += solver_->carried[k].second;
  return stats;
}

Statistics Arkode::statistics() const {
  if (!solver_ || !solver_->memory) return {};
  Statistics stats = arkode_counters();
  // The linear solver's counters: it lives across re-initialisations.
  if (solver_->reduced) solver_->reduced->append_statistics(stats);
  return stats;
}

IntegratorKind arkode_kind() {
  return {"arkode", arkode_keys(), read_arkode_settings,
          [](const IntegratorSettings& settings, const std::string& file) {
            return std::make_unique<Arkode>(options_of<ArkodeSettings>(settings), file);
          }};
}

}  // namespace fissure
