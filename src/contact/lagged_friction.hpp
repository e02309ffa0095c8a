#pragma once
// Friction inside an implicit step (docs/integrators.md, "Contact"): each contact that presses at
// the step's start keeps its normal n and its Coulomb limit μλ (λ = k p, the normal force then)
// through the step, which makes friction a smooth dissipative potential of the positions
// (IPC's lagged friction, Li et al. 2020, §5). The scheme makes the stage's velocity of its
// positions, v = (z − ŷ)/s (backward Euler: ŷ = y_n, s = h; Newmark: ŷ = y_n + h v_n/2, s = h/2;
// an SDIRK stage: ŷ = Ŷ_i, s = γh; ImplicitScheme::stage_velocity). With u = (I − n nᵀ)(z − ŷ − s
// w) = s times the particle's tangential velocity relative to the collider (moving at w), and x =
// |u|/s its slip speed,
//   D(z) = μλ s f0(x),  f0(x) = x²/(2ε_v) for x ≤ ε_v, x − ε_v/2 beyond,
//   ∇D = μλ min(x/ε_v, 1) u/|u|,
// the regularised Coulomb force of the explicit law (contact/collider_shape.hpp) at the stage's
// mean slip speed, and its Hessian μλ/(ε_v s) (I − n nᵀ) while sticking, μλ/|u| (I − n nᵀ − ûûᵀ)
// while sliding: positive semidefinite in both.
#include <cmath>

#include "contact/collider_shape.hpp"

namespace fissure {

// The slip u of contact c at z, the collider's velocity times the stage's span being `shift`.
inline void slip(const LaggedContact& c, const double* z, const Point& shift, double* u) {
  const int i = c.particle;
  double d[3], along = 0;
  for (int k = 0; k < 3; ++k) {
    d[k] = z[3 * i + k] - c.start[k] - shift[k];
    along += d[k] * c.normal[k];
  }
  for (int k = 0; k < 3; ++k) u[k] = d[k] - along * c.normal[k];
}

// D of contact c at slip u over a stage of length s; adds ∇D to gradient[0..2] and, where blocks
// is not null, its Hessian to blocks[0..8].
inline double lagged_friction(const LaggedContact& c, const double* u, double s, double* gradient,
                              double* blocks) {
  const double length = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  const double speed = length / s, eps = kStickSpeed;
  const bool sticking = speed <= eps;
  const double energy =
      c.limit * s * (sticking ? speed * speed / (2 * eps) : speed - 0.5 * eps);  // μλ s f0(x)
  // ∇D = μλ f1(x) û: μλ u/(ε_v s) while sticking, μλ û while sliding
  const double scale = sticking ? c.limit / (eps * s) : c.limit / length;
  for (int k = 0; k < 3; ++k) gradient[k] += scale * u[k];
  if (blocks)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        const double projector = (a == b ? 1.0 : 0.0) - c.normal[a] * c.normal[b];
        blocks[3 * a + b] +=
            scale * (sticking ? projector : projector - u[a] * u[b] / (length * length));
      }
  return energy;
}

}  // namespace fissure
