#pragma once
// An implicit step as the minimisation of an incremental potential (docs/integrators.md):
//   E(z) = (A/2)(z − ỹ)ᵀ M (z − ỹ) + Π(z) − fᵀz,   ∇E = A M (z − ỹ) − F_int(z) − f,
// whose Hessian A M + K is what Newton solves with. Each scheme fixes A and ỹ from the state at
// the start of the step, and turns the minimiser z back into positions and velocities. A
// singly diagonally implicit Runge–Kutta scheme (SDIRK) takes one such minimisation per stage,
// all with the same A, so one factor serves every stage and step.
//
// Contact's potential B (LoadPotential::contact) is taken at the stage's end point only: a_n and
// an ESDIRK's explicit first stage carry the other forces, never B's, so a contact that opens
// within a step is not pushed on by its force from the step's start (docs/integrators.md,
// "Contact"). Each stage weighs B by potential_weight(), and finish_stage() and correct() take
// B's acceleration at the minimiser, −M⁻¹∇B, to keep it out of what is carried.
#include <vector>

#include "integrators/integrator.hpp"
#include "integrators/petsc_newton_settings.hpp"
#include "integrators/sdirk_tableau.hpp"

namespace fissure {

class ImplicitScheme {
 public:
  using Scheme = PetscNewtonSettings::Scheme;
  // rho_infinity: ρ∞ of alpha.
  ImplicitScheme(Scheme scheme, double rho_infinity);

  // Minimisations per step: the SDIRK stages, else 1.
  int stages() const { return tableau_ ? tableau_->stages : 1; }
  // Sets inertia() and target() for stage `stage` of a step of size h from y_n, v_n and the
  // acceleration a_n, with mass-proportional damping c. Stages are taken in order, each after
  // the previous one's finish_stage().
  void predict(const State& state, const std::vector<double>& acceleration, double c, double h,
               int stage = 0);
  // The coefficient A of M in the potential (0 for static).
  double inertia() const { return inertia_; }
  // ỹ.
  const std::vector<double>& target() const { return target_; }
  // Newton's starting guess, z at constant velocity: ỹ would add h²a_n, which after a sudden
  // release (a_n large, h large) lands far outside the basin of a good Newton start. An SDIRK
  // stage after another (an ESDIRK's first implicit stage after its explicit one) starts from ỹ
  // plus the previous stage's acceleration held: its error is O(h³), where the previous stage's
  // minimiser's is O(h).
  std::vector<double> guess(const State& state, double h) const;
  // z of a particle held by a constraint, for the stage last predicted: y + chord Δ(time h),
  // Δ(τ) its prescribed displacement over τ from the step's start. The stage's positions lie at
  // time c_i h (an SDIRK stage; 1 for backward Euler and Newmark); generalized-α's z =
  // y_{n+1−α_f} is the chord's point (1 − α_f) of the way to y_{n+1}.
  double held_time() const { return kind_ == Kind::newmark_alpha ? 1.0 : held_fraction_; }
  double held_chord() const { return kind_ == Kind::newmark_alpha ? held_fraction_ : 1.0; }
  // Where in the step the stage's positions are taken, over h (1 for backward Euler, 1 − α_f
  // for Newmark and generalized-α, c_i for an SDIRK stage; 0 for static, which has no time).
  double stage_fraction() const { return is_static() ? 0.0 : held_fraction_; }
  // The velocity the scheme makes of the stage's positions z, affine: (z − anchor)/span, for the
  // stage last predicted from `state` (span 0 for static).
  void stage_velocity(const State& state, const std::vector<double>& acceleration, double h,
                      std::vector<double>& anchor, double& span) const;
  // Where the stage takes B: at y_n + s (z − y_n), s = potential_scale() (1, but 1/(1 − α_f)
  // for generalized-α, which takes B at y_{n+1} rather than at its z = y_{n+1−α_f}).
  double potential_scale() const { return kind_ == Kind::newmark_alpha ? 1 / (1 - alpha_f_) : 1; }
  // The weight w of B in the potential of the stage last predicted, w B(y_n + s (z − y_n)): 1,
  // but (1 − α_m)(1 − α_f)/γ for Newmark and generalized-α (2 for Newmark) and (γ + a_i1)/γ for
  // an ESDIRK's implicit stages, which take B's share of the explicit first stage at their own
  // end point.
  double potential_weight() const { return potential_weight_; }
  // Whether contact's penalty is taken as its secant from the step's start (Newmark, whose
  // trapezoidal position update then keeps the energy through a contact it does not resolve:
  // contact/secant_penalty.hpp) rather than at the stage's end point.
  bool contact_secant() const {
    return kind_ == Kind::newmark_alpha && alpha_m_ == 0 && alpha_f_ == 0;
  }
  // Records the minimiser z of the stage last predicted (SDIRK; nothing for the others).
  // `contact`: −M⁻¹∇B where the stage takes B, 3N, or empty when the scene has no
  // potentials.
  void finish_stage(const std::vector<double>& z, const std::vector<double>& contact, double h);
  // From the minimiser z of the last stage: y_{n+1}, v_{n+1} into `state` and a_{n+1} into
  // `acceleration`, without B's share (`contact` as for finish_stage).
  void correct(const std::vector<double>& z, const std::vector<double>& contact, State& state,
               std::vector<double>& acceleration, double h) const;
  // True while a stage after an SDIRK step's first implicit one is being solved.
  bool later_stage() const {
    return kind_ == Kind::sdirk && stage_ > (tableau_->explicit_stage(0) ? 1 : 0);
  }
  // True while the step's last stage (its only one, for the schemes that are not SDIRK) is.
  bool last_stage() const { return stage_ == stages() - 1; }
  // True if the stage last predicted is explicit (an ESDIRK's first): predict() recorded it,
  // and it has no minimisation and no finish_stage().
  bool explicit_stage() const { return tableau_ && tableau_->explicit_stage(stage_); }
  bool is_static() const { return kind_ == Kind::static_equilibrium; }
  // γ of an SDIRK scheme's stages, else 0.
  double gamma() const { return tableau_ ? tableau_->gamma : 0; }
  // The step just solved's local error estimate from the embedded weights (a scheme that has
  // them: newton_test_refusal in petsc_newton_settings.hpp), d = h Σ (b_i − b̂_i)
  // (V_i, V'_i), as sums over the free unknowns [first, end) of m d_y², m d_v² and m.
  struct ErrorSums {
    double position = 0, velocity = 0, mass = 0;
  };
  ErrorSums local_error(double h, const std::vector<double>& mass, const std::vector<char>& fixed,
                        std::size_t first, std::size_t end) const;

 private:
  enum class Kind { backward_euler, newmark_alpha, sdirk, static_equilibrium } kind_;
  // Generalized-α (Chung & Hulbert 1993); Newmark's average acceleration is α_m = α_f = 0.
  double alpha_m_ = 0, alpha_f_ = 0, beta_ = 0.25, gamma_ = 0.5;
  double inertia_ = 0;
  double potential_weight_ = 1;
  double held_fraction_ = 1;  // where the stage lies in the step, over h: 1 − α_f, or c_i
  std::vector<double> target_;
  // SDIRK: the tableau, the stage being solved, and per stage i its velocity V_i and
  // acceleration Ȧ_i; Ŷ and V̂ of the stage being solved (the explicit part of its sums).
  const SdirkTableau* tableau_ = nullptr;
  int stage_ = 0;
  std::vector<std::vector<double>> stage_velocity_, stage_acceleration_;
  std::vector<double> explicit_position_, explicit_velocity_;
  std::vector<double> stage_contact_;  // contact's acceleration at the last stage solved
  double damping_ = 0;                 // c of the stage being solved
};

}  // namespace fissure
