#pragma once
// The penalty φ(p) = ½ k p₊² of a particle at depth p taken as the secant over a step from the
// depth p0 at its start (a discrete gradient, Gonzalez 1996): the force k̄ = (φ(p) − φ(p0))/(p −
// p0), so that the force times the change of depth is exactly the change of φ, and a step that
// moves the position by the mean of its velocities (Newmark's trapezoidal rule) neither gains nor
// loses energy at a contact it does not resolve (docs/integrators.md, "Contact"). In p it is the
// derivative of G(p) = ∫ from p0 to p of the secant slope: convex (a convex φ's secant slope
// grows with p), twice continuously differentiable, and G(p0) = 0.
#include <cmath>

namespace fissure {

struct SecantPenalty {
  double energy;     // G(p)
  double slope;      // G'(p) = (φ(p) − φ(p0))/(p − p0), φ'(p0) at p = p0
  double curvature;  // G''(p) ≥ 0
};

inline SecantPenalty secant_penalty(double k, double p0, double p) {
  if (p0 > 0) {
    if (p >= 0)  // both in contact: the mean of the two forces
      return {0.25 * k * (p - p0) * (p + 3 * p0), 0.5 * k * (p + p0), 0.5 * k};
    // left the contact: φ(p) = 0, slope ½ k p0²/(p0 − p), integrated from G(0) = −¾ k p0²
    const double gap = p0 - p;
    return {-0.75 * k * p0 * p0 - 0.5 * k * p0 * p0 * std::log1p(-p / p0), 0.5 * k * p0 * p0 / gap,
            0.5 * k * p0 * p0 / (gap * gap)};
  }
  if (p <= 0) return {0, 0, 0};
  // entered the contact from the gap a = −p0 ≥ 0: slope ½ k p²/(p + a), and G = ½ k a² (ln(1 +
  // x) − x + x²/2) with x = p/a, by its series where x is small (the terms cancel)
  const double a = -p0, sum = p + a;
  const double slope = 0.5 * k * p * p / sum, curvature = 0.5 * k * p * (p + 2 * a) / (sum * sum);
  if (p <= 1e-3 * a) {
    const double x = p / a;
    return {0.5 * k * a * a * x * x * x * (1.0 / 3 - x * (0.25 - x * (0.2 - x / 6))), slope,
            curvature};
  }
  if (a == 0) return {0.25 * k * p * p, slope, curvature};
  return {0.5 * k * (0.5 * p * p - a * p + a * a * std::log1p(p / a)), slope, curvature};
}

}  // namespace fissure
