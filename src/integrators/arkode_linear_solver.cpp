#include "integrators/arkode_linear_solver.hpp"

#include <arkode/arkode_arkstep.h>
#include <nvector/nvector_serial.h>

#include <cmath>

#include "core/error.hpp"
#include "linear/shifted_system.hpp"

namespace fissure {

ReducedNewtonSystem::ReducedNewtonSystem(Dynamics& dynamics, void* arkode_memory,
                                         const std::vector<double>& origin)
    : dynamics_(dynamics), arkode_memory_(arkode_memory), origin_(origin) {
  stiffness_ = two_hop_pattern(dynamics.model().families());
  system_ = stiffness_;
  diagonal_ = diagonal_positions(stiffness_);
  const auto& m = dynamics.mass();
  mass_.resize(3 * m.size());
  for (std::size_t i = 0; i < m.size(); ++i)
    for (int d = 0; d < 3; ++d) mass_[3 * i + d] = m[i];
  rhs_.resize(mass_.size());
  held_step_.resize(mass_.size());
  coupling_.resize(mass_.size());
}

void ReducedNewtonSystem::setup() {
  double t, gamma;
  N_Vector predicted, z, fi, sdata;
  void* user_data;
  ARKStepGetNonlinearSystemData(arkode_memory_, &t, &predicted, &z, &fi, &gamma, &sdata,
                                &user_data);
  const double* displacement = N_VGetArrayPointer(predicted);
  predicted_.resize(mass_.size());
  for (std::size_t k = 0; k < mass_.size(); ++k) predicted_[k] = origin_[k] + displacement[k];
  dynamics_.model().assemble_tangent(predicted_.data(), stiffness_, false);
  projected_ = false;
  std::vector<int> held;
  std::vector<Vec3> velocity;
  dynamics_.held(t, held, velocity);
  fixed_.assign(mass_.size(), 0);
  for (int i : held)
    for (int d = 0; d < 3; ++d) fixed_[3 * i + d] = 1;
  factorize(gamma);
}

// The system over γ²: K + M (1 + γc)/γ², i.e. A = (1 + γc)/γ² in shift_and_fix. K is the exact
// tangent where that is positive definite, else the projected tangent K⁺ (model.hpp).
void ReducedNewtonSystem::factorize(double gamma) {
  gamma_ = gamma;
  const double c = dynamics_.damping();
  auto attempt = [&] {
    system_.values = stiffness_.values;
    shift_and_fix(system_, diagonal_, mass_, (1 + gamma * c) / (gamma * gamma), fixed_);
    factor_.factorize(system_);
  };
  try {
    attempt();
  } catch (const RunError&) {
    if (projected_) throw;
    dynamics_.model().assemble_tangent(predicted_.data(), stiffness_, true);
    projected_ = true;
    attempt();
  }
}

void ReducedNewtonSystem::solve(const double* b, double* x) {
  double t = 0;
  ARKStepGetCurrentTime(arkode_memory_, &t);
  const bool first = fixed_.empty();
  if (first || t != stage_time_) {
    stage_time_ = t;
    stage_solves_ = 0;
    refreshed_in_stage_ = false;
  }
  if (first || (++stage_solves_ > 5 && !refreshed_in_stage_)) {
    refreshed_in_stage_ = !first;
    setup();
  }
  double gamma = gamma_;
  ARKStepGetCurrentGamma(arkode_memory_, &gamma);
  if (std::abs(gamma - gamma_) > 1e-12 * gamma_) factorize(gamma);
  const std::size_t n = mass_.size();
  const double* by = b;
  const double* bv = b + n;
  const double c = dynamics_.damping();
  bool any_held = false;
  for (std::size_t k = 0; k < n; ++k) {
    held_step_[k] = fixed_[k] ? by[k] + gamma * bv[k] : 0.0;
    any_held = any_held || (fixed_[k] && held_step_[k] != 0);
  }
  if (any_held) stiffness_.multiply(held_step_.data(), coupling_.data());
  const double g2 = gamma * gamma;
  for (std::size_t k = 0; k < n; ++k)
    rhs_[k] = fixed_[k] ? 0.0
                        : (mass_[k] * ((1 + gamma * c) * by[k] + gamma * bv[k])) / g2 -
                              (any_held ? coupling_[k] : 0.0);
  double* dy = x;
  double* dv = x + n;
  factor_.solve(rhs_.data(), dy);
  for (std::size_t k = 0; k < n; ++k) {
    if (fixed_[k]) dy[k] = held_step_[k];
    dv[k] = (dy[k] - by[k]) / gamma;
  }
}

namespace {

ReducedNewtonSystem* system_of(SUNLinearSolver S) {
  return static_cast<ReducedNewtonSystem*>(S->content);
}

SUNLinearSolver_Type get_type(SUNLinearSolver) { return SUNLINEARSOLVER_MATRIX_EMBEDDED; }
SUNLinearSolver_ID get_id(SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; }

int setup(SUNLinearSolver S, SUNMatrix) {
  try {
    system_of(S)->setup();
    return 0;
  } catch (...) {
    return SUNLS_PACKAGE_FAIL_UNREC;
  }
}

int solve(SUNLinearSolver S, SUNMatrix, N_Vector x, N_Vector b, realtype) {
  try {
    system_of(S)->solve(N_VGetArrayPointer(b), N_VGetArrayPointer(x));
    return 0;
  } catch (...) {
    return SUNLS_PACKAGE_FAIL_UNREC;
  }
}

int free_solver(SUNLinearSolver S) {
  SUNLinSolFreeEmpty(S);
  return 0;
}

}  // namespace

SUNLinearSolver make_reduced_linear_solver(SUNContext context, ReducedNewtonSystem* system) {
  SUNLinearSolver S = SUNLinSolNewEmpty(context);
  S->content = system;
  S->ops->gettype = get_type;
  S->ops->getid = get_id;
  S->ops->setup = setup;
  S->ops->solve = solve;
  S->ops->free = free_solver;
  return S;
}

}  // namespace fissure
