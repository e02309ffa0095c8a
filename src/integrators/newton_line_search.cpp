#include "integrators/newton_line_search.hpp"

#include <algorithm>
#include <cmath>

namespace fissure {

namespace {

// E and ∇E at w (one model pass: the residual request is answered by the kept evaluation).
PetscErrorCode evaluate(SNES snes, Vec w, Vec g, PetscReal* energy, PetscReal* norm) {
  PetscCall(SNESComputeObjective(snes, w, energy));
  PetscCall(SNESComputeFunction(snes, w, g));
  PetscCall(VecNorm(g, NORM_2, norm));
  return 0;
}

}  // namespace

PetscErrorCode potential_line_search(SNESLineSearch search, void* context) {
  auto* c = static_cast<PotentialLineSearch*>(context);
  SNES snes;
  Vec x, f, y, w, g;
  PetscReal xnorm, fnorm, ynorm;
  PetscCall(SNESLineSearchGetSNES(search, &snes));
  PetscCall(SNESLineSearchGetVecs(search, &x, &f, &y, &w, &g));
  PetscCall(SNESLineSearchGetNorms(search, &xnorm, &fnorm, &ynorm));
  const double bound = c->max_step ? c->max_step(x, y) : 1.0;
  c->last_bounded = bound < 1;
  if (bound < 1) ++c->bounded;
  if (bound == 1 && c->accept_unevaluated && c->accept_unevaluated(y)) {
    ++c->unevaluated;
    PetscCall(VecAXPY(x, -1, y));
    PetscCall(VecNorm(x, NORM_2, &xnorm));
    PetscCall(VecNorm(y, NORM_2, &ynorm));
    PetscCall(SNESLineSearchSetLambda(search, 1));
    PetscCall(SNESLineSearchSetNorms(search, xnorm, fnorm, ynorm));
    return 0;
  }
  PetscReal e0;
  PetscCall(SNESComputeObjective(snes, x, &e0));
  // The step is x − λy; its slope along E is −∇Eᵀy (negative for a positive definite factor).
  PetscReal slope;
  PetscCall(VecDot(f, y, &slope));
  slope = -slope;
  const double round_off = 1e-10 * c->system->objective_magnitude();
  PetscReal lambda = bound, energy = 0, norm = 0;
  bool accepted = false;
  for (int trial = 0; trial < 40 && !accepted; ++trial) {
    PetscCall(VecWAXPY(w, -lambda, y, x));
    PetscCall(evaluate(snes, w, g, &energy, &norm));
    const bool finite = std::isfinite(energy) && std::isfinite(norm);
    const bool armijo = finite && slope < 0 && energy <= e0 + 1e-4 * lambda * slope;
    const bool within_round_off = finite && energy <= e0 + round_off && norm < fnorm;
    if (armijo || within_round_off) {
      accepted = true;
      break;
    }
    // Minimiser of the quadratic through E(0), E'(0) and E(λ), kept in [0.1 λ, 0.5 λ].
    double next = 0.5 * lambda;
    if (finite && slope < 0) {
      const double curvature = energy - e0 - slope * lambda;
      if (curvature > 0) next = -slope * lambda * lambda / (2 * curvature);
    }
    lambda = std::clamp(next, 0.1 * lambda, 0.5 * lambda);
  }
  if (!accepted) {
    PetscCall(SNESLineSearchSetReason(search, SNES_LINESEARCH_FAILED_REDUCT));
    return 0;
  }
  if (lambda < 1) ++c->cuts;
  PetscCall(VecCopy(w, x));
  PetscCall(VecCopy(g, f));
  PetscCall(VecNorm(x, NORM_2, &xnorm));
  PetscCall(VecNorm(y, NORM_2, &ynorm));
  PetscCall(SNESLineSearchSetLambda(search, lambda));
  PetscCall(SNESLineSearchSetNorms(search, xnorm, norm, lambda * ynorm));
  return 0;
}

}  // namespace fissure
