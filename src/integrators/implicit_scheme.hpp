#pragma once
// An implicit step as the minimisation of an incremental potential (docs/integrators.md):
//   E(z) = (A/2)(z − ỹ)ᵀ M (z − ỹ) + Π(z) − fᵀz,   ∇E = A M (z − ỹ) − F_int(z) − f,
// whose Hessian A M + K is what Newton factorizes. Each scheme fixes A and ỹ from the state at
// the start of the step, and turns the minimiser z back into positions and velocities.
#include <vector>

#include "integrators/integrator.hpp"

namespace fissure {

class ImplicitScheme {
 public:
  // scheme: backward_euler, newmark, alpha (with ρ∞), static.
  ImplicitScheme(const std::string& scheme, double rho_infinity);

  // Sets inertia() and target() for a step of size h from y_n, v_n and the acceleration a_n,
  // with mass-proportional damping c.
  void predict(const State& state, const std::vector<double>& acceleration, double c, double h);
  // The coefficient A of M in the potential (0 for static).
  double inertia() const { return inertia_; }
  // ỹ.
  const std::vector<double>& target() const { return target_; }
  // Newton's starting guess, z at constant velocity: ỹ would add h²a_n, which after a sudden
  // release (a_n large, h large) lands far outside the basin of a good Newton start.
  std::vector<double> guess(const State& state, double h) const;
  // z of a particle that moves at velocity u through the step (held by a constraint).
  double held_value(double y, double u, double h) const { return y + (1 - alpha_f_) * h * u; }
  // From the minimiser z: y_{n+1}, v_{n+1} into `state` and a_{n+1} into `acceleration`.
  void correct(const std::vector<double>& z, State& state, std::vector<double>& acceleration,
               double h) const;
  bool is_static() const { return kind_ == Kind::static_equilibrium; }

 private:
  enum class Kind { backward_euler, newmark_alpha, static_equilibrium } kind_;
  // Generalized-α (Chung & Hulbert 1993); Newmark's average acceleration is α_m = α_f = 0.
  double alpha_m_ = 0, alpha_f_ = 0, beta_ = 0.25, gamma_ = 0.5;
  double inertia_ = 0;
  std::vector<double> target_;
};

}  // namespace fissure
