#pragma once
// petsc_newton's line search on the incremental potential E (a PETSc shell line search): the
// full step when it decreases E enough (Armijo, c = 1e-4), which costs one evaluation of E and
// ∇E together and nothing more; else backtracking by safeguarded quadratic fits. Near the
// solution E's decrease falls below the round-off of E itself (extensions of stiff materials are
// tiny differences of lengths), where no test on E can decide: a step that keeps E within that
// round-off and lowers |∇E| is then taken. A step the Newton test has already accepted from its
// size alone (`accept_unevaluated`) is taken without evaluating anything. The trials start from
// the largest step the loads' potentials admit (`max_step`: no particle driven through a
// collider), and a cut step is never taken unevaluated.
#include <petscsnes.h>

#include <functional>

#include "integrators/newton_system.hpp"

namespace fissure {

struct PotentialLineSearch {
  NewtonSystem* system = nullptr;
  long cuts = 0;  // steps shorter than the full step
  // Whether the full step along this direction ends the Newton solve whatever E and ∇E are
  // there; if so it is taken unevaluated (the residual is left at the last point evaluated).
  std::function<bool(Vec direction)> accept_unevaluated;
  long unevaluated = 0;  // steps so taken
  // The largest λ ≤ 1 such that x − λy stays within the potentials' bounds (1 without any).
  std::function<double(Vec x, Vec y)> max_step;
  long bounded = 0;           // steps cut to that bound
  bool last_bounded = false;  // whether the last step was
};

// The SNESLineSearchUserFunc; `context` is a PotentialLineSearch.
PetscErrorCode potential_line_search(SNESLineSearch search, void* context);

}  // namespace fissure
