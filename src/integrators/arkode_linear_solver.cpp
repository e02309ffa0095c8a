#include "integrators/arkode_linear_solver.hpp"

#include <arkode/arkode_arkstep.h>
#include <fmt/format.h>
#include <nvector/nvector_serial.h>

#include <cmath>

#include "core/error.hpp"
#include "integrators/arkode_methods.hpp"
#include "linear/nearest_bonds.hpp"
#include "linear/shifted_system.hpp"
#include "model/stiffness.hpp"
#include "parallel/collective.hpp"
#include "parallel/halo.hpp"

namespace fissure {

ReducedNewtonSystem::ReducedNewtonSystem(Dynamics& dynamics, void* arkode_memory,
                                         const std::vector<double>& origin, bool reuse,
                                         int krylov_limit, FactorPrecision precision, bool nearest)
    : dynamics_(dynamics),
      first_(3 * std::size_t(dynamics.first_row())),
      count_(3 * std::size_t(dynamics.end_row()) - first_),
      arkode_memory_(arkode_memory),
      origin_(origin),
      reuse_(reuse),
      krylov_limit_(krylov_limit),
      factor_(precision),
      cg_(count_, distributed() ? ConjugateGradient::Sum([this](double v) { return sum(v); })
                                : ConjugateGradient::Sum()) {
  const Families& families = dynamics.model().families();
  if (distributed() && !distributable(nearest))
    throw RunError("arkode: only the nearest preconditioner runs over several ranks");
  const Stiffness& stiffness = *dynamics.model().stiffness();
  if (nearest && !stiffness.one_hop_matrices())
    throw RunError(
        "arkode: this model has no nearest members' stiffness (surface_correction: fictitious), "
        "which Arkode::check refuses for implicit methods");
  if (nearest) {
    nearest_ = nearest_bonds(families, kNearestMembers,
                             [&dynamics](double* reach) { dynamics.share(reach, 1); });
    // over several ranks the rank's rows only, the others empty
    stiffness_ = nearest_bond_pattern(families, nearest_, dynamics.first_row(), dynamics.end_row());
  } else {
    stiffness_ = stiffness.tangent_pattern(families);
  }
  system_ = stiffness_;
  diagonal_ = diagonal_positions(stiffness_);
  const auto& m = dynamics.mass();
  mass_.resize(3 * m.size());
  for (std::size_t i = 0; i < m.size(); ++i)
    for (int d = 0; d < 3; ++d) mass_[3 * i + d] = m[i];
  const std::size_t n = mass_.size();
  for (auto* v : {&predicted_, &assembled_at_, &held_step_, &coupling_}) v->resize(n);
  scratch_.resize(count_);
  rhs_.resize(count_);
  fixed_.assign(n, 0);
  if (!distributed()) return;
  product_in_.resize(n);
  product_out_.resize(n);
  // the diagonal block: the rank's rows, the entries in its own columns, renumbered
  block_.rows = static_cast<int>(count_);
  block_.offsets.assign(count_ + 1, 0);
  for (std::size_t r = 0; r < count_; ++r) {
    const int row = static_cast<int>(first_ + r);
    for (int e = system_.offsets[row]; e < system_.offsets[row + 1]; ++e) {
      const std::size_t c = system_.columns[e];
      if (c < first_ || c >= first_ + count_) continue;
      block_.columns.push_back(static_cast<int>(c - first_));
      block_source_.push_back(e);
    }
    block_.offsets[r + 1] = static_cast<int>(block_.columns.size());
  }
  block_.values.assign(block_.columns.size(), 0.0);
}

double ReducedNewtonSystem::sum(double value) const {
  return distributed() ? sum_over_ranks(dynamics_.halo()->comm(), value) : value;
}

void ReducedNewtonSystem::extract_block() {
  for (std::size_t e = 0; e < block_source_.size(); ++e)
    block_.values[e] = system_.values[block_source_[e]];
}

void ReducedNewtonSystem::begin_stage_if_new() {
  double t, gamma;
  N_Vector predicted, z, fi, sdata;
  void* user_data;
  arkode_check(ARKStepGetNonlinearSystemData(arkode_memory_, &t, &predicted, &z, &fi, &gamma,
                                             &sdata, &user_data),
               "ARKStepGetNonlinearSystemData");
  const double* displacement = N_VGetArrayPointer(predicted);  // the rank's rows
  int same = stage_ > 0 && t == stage_time_;
  for (std::size_t k = 0; k < count_; ++k) {
    scratch_[k] = origin_[first_ + k] + displacement[k];
    same = same && scratch_[k] == predicted_[first_ + k];
  }
  // a new stage's linearization is collective: every rank begins it when one rank's changed
  if (distributed()) same = min_over_ranks(dynamics_.halo()->comm(), same);
  if (same) return;
  std::copy(scratch_.begin(), scratch_.end(), predicted_.begin() + first_);
  dynamics_.share(predicted_.data());
  stage_time_ = t;
  ++stage_;
  stage_solves_ = 0;
  refreshed_in_stage_ = false;
  // Without reuse the held set is the last refresh's, as the factor's (today's behaviour); with
  // it, CG works on the stage's own held set (precondition masks the factor's).
  if (reuse_) hold_at(t);
}

void ReducedNewtonSystem::hold_at(double t) {
  std::vector<int> held;
  std::vector<Vec3> velocity;
  dynamics_.held(t, held, velocity);
  fixed_.assign(mass_.size(), 0);
  for (int i : held)
    for (int d = 0; d < 3; ++d) fixed_[3 * i + d] = 1;
}

void ReducedNewtonSystem::refresh(Refreshes::Reason reason, double gamma) {
  ++refreshes_.count[reason];
  pending_ = Refreshes::none;
  hold_at(stage_time_);
  assembled_at_ = predicted_;
  if (!nearest_.empty()) {
    // Only the matrix-free K changes with the fallback: the nearest matrix is SPD as it is.
    dynamics_.model().stiffness()->assemble_nearest_stiffness(assembled_at_.data(), nearest_,
                                                              stiffness_);
    projected_ = reason == Refreshes::fallback;
  } else {
    dynamics_.model().stiffness()->assemble_tangent(assembled_at_.data(), stiffness_, false);
    projected_ = false;
  }
  factorize(gamma);
  factor_stage_ = stage_;
  if (reason == Refreshes::convergence) refreshed_in_stage_ = true;
  // What the model linearized before (bonds since broken, another tangent) is not reused.
  linearized_stage_ = -1;
}

// S = K + M (1 + γc)/γ², i.e. A = (1 + γc)/γ² in shift_and_fix. K is the exact tangent where S
// is positive definite, else the projected tangent K⁺ (model.hpp), assembled at the same point.
void ReducedNewtonSystem::factorize(double gamma) {
  factor_gamma_ = gamma;
  const double c = dynamics_.damping();
  auto attempt = [&] {
    system_.values = stiffness_.values;
    const double shift = (1 + gamma * c) / (gamma * gamma);
    double scale = held_scale(system_, diagonal_, mass_, shift);
    if (distributed()) scale = max_over_ranks(dynamics_.halo()->comm(), scale);
    shift_and_fix(system_, diagonal_, mass_, shift, fixed_, scale);
    int factored = 0;
    if (!distributed()) {
      factored = factor_.factorize(system_);
    } else {
      // an error of CHOLMOD's on one rank stops every rank, as a failure does
      extract_block();
      agree(dynamics_.halo()->comm(), [&] { factored = factor_.factorize(block_); });
      factored = min_over_ranks(dynamics_.halo()->comm(), factored);
    }
    if (!factored) {
      // over several ranks the whole system's size (system_ holds the rank's rows)
      const int rows = distributed() ? 3 * dynamics_.model().families().total_rows() : system_.rows;
      throw RunError(
          fmt::format("CHOLMOD: the {}×{} system matrix is not positive definite", rows, rows));
    }
    ++factorizations_;
  };
  try {
    attempt();
  } catch (const RunError&) {
    if (projected_ || !nearest_.empty()) throw;
    ++refreshes_.count[Refreshes::fallback];
    dynamics_.model().stiffness()->assemble_tangent(assembled_at_.data(), stiffness_, true);
    projected_ = true;
    attempt();
  }
}

bool ReducedNewtonSystem::same_gamma(double gamma) const {
  return same_step_coefficient(gamma, factor_gamma_);
}

bool ReducedNewtonSystem::fresh(double gamma) const {
  return factor_stage_ == stage_ && same_gamma(gamma);
}

void ReducedNewtonSystem::solve(const double* b, double* x, double tol) {
  begin_stage_if_new();
  ++stage_solves_;
  double gamma = 0;
  arkode_check(ARKStepGetCurrentGamma(arkode_memory_, &gamma), "ARKStepGetCurrentGamma");
  if (pending_ != Refreshes::none) refresh(pending_, gamma);
  double* dy = x;
  if (!nearest_.empty()) return solve_with_nearest(b, gamma, tol, x);
  if (reuse_) {
    if (!fresh(gamma)) {
      linearize_stage();
      reduced_rhs(b, gamma, true);
      if (solve_by_cg(gamma, tol, dy)) return expand(b, gamma, x);
    }
  } else if (stage_solves_ > 5 && !refreshed_in_stage_) {
    // K is stale (e.g. after large rotations) when a stage needs a sixth Newton iteration;
    // without this, fixed-step SDIRK failed on the swinging bar.
    refresh(Refreshes::convergence, gamma);
  } else if (!same_gamma(gamma)) {
    ++refreshes_.count[Refreshes::step_size];
    factorize(gamma);
  }
  // The factor is S at this γ (fresh, or without reuse with the last assembled K): one
  // back-solve.
  reduced_rhs(b, gamma, false);
  factor_.solve(rhs_.data(), dy);
  ++back_solves_;
  expand(b, gamma, x);
}

void ReducedNewtonSystem::reduced_rhs(const double* b, double gamma, bool matrix_free) {
  const double* by = b;
  const double* bv = b + count_;
  const double c = dynamics_.damping();
  bool any_held = false;
  for (std::size_t k = 0; k < count_; ++k) {
    const std::size_t u = first_ + k;
    held_step_[u] = fixed_[u] ? by[k] + gamma * bv[k] : 0.0;
    any_held = any_held || (fixed_[u] && held_step_[u] != 0);
  }
  // the coupling's product is collective, and reads the ghosts' held steps
  if (distributed()) any_held = any_over_ranks(dynamics_.halo()->comm(), any_held);
  if (any_held) dynamics_.share(held_step_.data());
  if (any_held && matrix_free) {
    dynamics_.model().stiffness()->apply_tangent(held_step_.data(), coupling_.data());
    ++tangent_products_;
  } else if (any_held) {
    stiffness_.multiply(held_step_.data(), coupling_.data());
  }
  const double g2 = gamma * gamma;
  for (std::size_t k = 0; k < count_; ++k) {
    const std::size_t u = first_ + k;
    rhs_[k] = fixed_[u] ? 0.0
                        : (mass_[u] * ((1 + gamma * c) * by[k] + gamma * bv[k])) / g2 -
                              (any_held ? coupling_[u] : 0.0);
  }
}

// Δy on held unknowns is prescribed; Δv = (Δy − b_y)/γ from the first row of (I − γJ)Δ = b.
void ReducedNewtonSystem::expand(const double* b, double gamma, double* x) const {
  double* dy = x;
  double* dv = x + count_;
  for (std::size_t k = 0; k < count_; ++k) {
    if (fixed_[first_ + k]) dy[k] = held_step_[first_ + k];
    dv[k] = (dy[k] - b[k]) / gamma;
  }
}

void ReducedNewtonSystem::linearize_stage() {
  if (linearized_stage_ == stage_ && linearized_projected_ == projected_) return;
  dynamics_.model().stiffness()->linearize(predicted_.data(), projected_);
  linearized_stage_ = stage_;
  linearized_projected_ = projected_;
  ++linearizations_;
}

// v and out the rank's unknowns; over several ranks K is applied to v with its ghosts shared.
void ReducedNewtonSystem::apply_system(double gamma, const double* v, double* out) {
  const double* v_all = v;
  double* out_all = out;
  if (distributed()) {
    std::copy(v, v + count_, product_in_.begin() + first_);
    dynamics_.share(product_in_.data());
    v_all = product_in_.data();
    out_all = product_out_.data();
  }
  dynamics_.model().stiffness()->apply_tangent(v_all, out_all);
  ++tangent_products_;
  const double shift = (1 + gamma * dynamics_.damping()) / (gamma * gamma);
  for (std::size_t k = 0; k < count_; ++k) {
    const std::size_t u = first_ + k;
    out[k] = fixed_[u] ? 0.0 : out_all[u] + shift * mass_[u] * v[k];
  }
}

// Z F⁻¹ Z, Z zeroing the stage's held unknowns: SPD on the free ones whichever unknowns the
// factor F held, so CG stays in the free subspace.
void ReducedNewtonSystem::precondition(const double* r, double* z) {
  factor_.solve(r, z);
  ++back_solves_;
  for (std::size_t k = 0; k < count_; ++k)
    if (fixed_[first_ + k]) z[k] = 0;
}

// The stopping test is the one ARKODE asks of its linear solver, ‖b − (I − γJ)x‖₂ ≤ tol (tol
// is ARKODE's linear tolerance eplifac × its Newton tolerance, already converted by ARKODE from
// its weighted RMS norm to this unweighted 2-norm for a solver without scaling vectors, ARKLS
// arkLsSolve), so that the Newton iteration converges as with an exact solve. With Δv from
// expand, the first block row of that residual vanishes and the second is γ M⁻¹ r, r the
// residual of (R); the held rows vanish too. A fixed relative tolerance would ignore ARKODE's
// Newton tolerance, which rtol sets.
// The nearest factor is never S: CG at every solve, once more after the refresh a failed CG
// made (at this stage and γ, with K⁺ where it broke down).
void ReducedNewtonSystem::solve_with_nearest(const double* b, double gamma, double tol, double* x) {
  if (!reuse_ && !same_gamma(gamma)) {
    ++refreshes_.count[Refreshes::step_size];
    factorize(gamma);
  }
  for (int attempt = 0; attempt < 2; ++attempt) {
    linearize_stage();
    reduced_rhs(b, gamma, true);
    if (solve_by_cg(gamma, tol, x)) return expand(b, gamma, x);
  }
  throw RunError(fmt::format(
      "arkode: CG on the stage system did not converge in integrator.refresh_krylov = {} "
      "iterations with a fresh nearest factor; raise refresh_krylov or set "
      "integrator.preconditioner: tangent",
      krylov_limit_));
}

bool ReducedNewtonSystem::solve_by_cg(double gamma, double tol, double* dy) {
  auto done = [&](const double* r) {
    double squares = 0;
    for (std::size_t k = 0; k < count_; ++k) {
      const double e = gamma * r[k] / mass_[first_ + k];
      if (!fixed_[first_ + k]) squares += e * e;
    }
    return std::sqrt(sum(squares)) <= tol;
  };
  const auto outcome = cg_.solve([&](const double* v, double* out) { apply_system(gamma, v, out); },
                                 [&](const double* r, double* z) { precondition(r, z); }, done,
                                 krylov_limit_, rhs_.data(), dy);
  krylov_iterations_ += cg_.iterations();
  using O = ConjugateGradient::Outcome;
  if (outcome == O::converged) return true;
  // Too slow: the factor is too far from S. Broken down: S (with the exact K) is not positive
  // definite, and the refresh falls back to K⁺.
  refresh(outcome == O::iteration_limit ? Refreshes::convergence : Refreshes::fallback, gamma);
  return false;
}

void ReducedNewtonSystem::append_statistics(Statistics& stats) const {
  stats.push_back({"factorizations", double(factorizations_)});
  stats.push_back({"back_solves", double(back_solves_)});
  stats.push_back({"krylov_iterations", double(krylov_iterations_)});
  stats.push_back({"tangent_products", double(tangent_products_)});
  stats.push_back({"linearizations", double(linearizations_)});
  refreshes_.append_to(stats);
}

namespace {

// What the SUNLinearSolver carries: the system, and where an exception thrown in a solve is kept
// for Arkode::step to rethrow with its message (ARKODE itself only sees a failure code).
struct Content {
  ReducedNewtonSystem* system;
  std::exception_ptr* error;
};

Content& content_of(SUNLinearSolver S) { return *static_cast<Content*>(S->content); }

SUNLinearSolver_Type get_type(SUNLinearSolver) { return SUNLINEARSOLVER_MATRIX_EMBEDDED; }
SUNLinearSolver_ID get_id(SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; }

int solve(SUNLinearSolver S, SUNMatrix, N_Vector x, N_Vector b, realtype tol) {
  Content& c = content_of(S);
  try {
    c.system->solve(N_VGetArrayPointer(b), N_VGetArrayPointer(x), tol);
    return 0;
  } catch (...) {
    *c.error = std::current_exception();
    return SUNLS_PACKAGE_FAIL_UNREC;
  }
}

int free_solver(SUNLinearSolver S) {
  delete &content_of(S);
  S->content = nullptr;
  SUNLinSolFreeEmpty(S);
  return 0;
}

}  // namespace

SUNLinearSolver make_reduced_linear_solver(SUNContext context, ReducedNewtonSystem* system,
                                           std::exception_ptr* error) {
  SUNLinearSolver S = SUNLinSolNewEmpty(context);
  if (!S) throw RunError("ARKODE: SUNLinSolNewEmpty failed");
  S->content = new Content{system, error};
  S->ops->gettype = get_type;
  S->ops->getid = get_id;
  // no setup: ARKODE 6.4 never calls a matrix-embedded solver's; solve keeps the factor current
  S->ops->solve = solve;
  S->ops->free = free_solver;
  return S;
}

}  // namespace fissure
