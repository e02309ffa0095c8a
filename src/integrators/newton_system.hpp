#pragma once
// The nonlinear system of one implicit step, free of any solver library: the incremental
// potential of implicit_scheme.hpp with the loads' potentials B (colliders; Load::potential),
//   E(z) = (A/2)(z − ỹ)ᵀ M (z − ỹ) + Π(z) + S(z) + w B(p(z)) − fᵀz,   p(z) = y_n + s (z − y_n)
// (S the smooth potentials, B contact's: LoadPotential::contact; w and s the scheme's
// ImplicitScheme::potential_weight and potential_scale), its gradient (the residual) and the
// product of its Hessian A M + K + ∇²S⁺ + w s² ∇²B⁺ with a vector (matrix-free; ∇²S⁺, ∇²B⁺ the
// loads' positive-semidefinite Hessians: blocks per particle, and for a pair potential the
// blocks between particles), with the particles a constraint
// holds eliminated (their unknowns fixed at the value they must take). The energy and the forces at
// a point come from one pass over the bonds and are kept, so that a line search asking for the
// objective and then the residual at the same point pays once.
#include <string>
#include <vector>

#include "integrators/implicit_scheme.hpp"
#include "integrators/petsc_newton_settings.hpp"
#include "linear/sparse_symmetric.hpp"

namespace fissure {

class NewtonSystem {
 public:
  using Tangent = PetscNewtonSettings::Tangent;
  // tangent: majoriser (bond-wise, assembled on bond_pattern), or matrix-free exact, projected
  // (the tangent without compressed bonds' geometric term) or automatic (either; use_tangent
  // picks). See model.hpp.
  NewtonSystem(Dynamics& dynamics, Tangent tangent);
  // Switches between exact and projected.
  void use_tangent(Tangent tangent) {
    if (tangent_ != Tangent::majoriser) tangent_ = tangent;
  }
  Tangent tangent() const { return tangent_; }

  // Prepares a stage of size h from `state` (the scheme predicted it): f = M g + the other loads
  // that give no potential at the start of the step, scaled by `load_factor`; the potentials'
  // stage begun; held particles fixed. Returns the starting guess z0, within the potentials'
  // bounds (max_step).
  // `acceleration`: a_n, which the scheme predicted with.
  std::vector<double> begin_step(const ImplicitScheme& scheme, const State& state,
                                 const std::vector<double>& acceleration, double h,
                                 double load_factor);
  // E(z) and ∇E(z) (zero on held unknowns).
  double objective(const double* z);
  void residual(const double* z, double* r);
  // Sets the point the Newton matrix is taken at (computed on the first product).
  void linearize(const double* z);
  // out = (A M + K) v on free unknowns, A m v on held ones (their rows decoupled).
  void apply(const double* v, double* out);
  // The largest fraction α ≤ 1 of the update dz from z that the loads' potentials admit (contact's
  // at p)
  // (LoadPotential::max_step); collective.
  double max_step(const double* z, const double* dz) const;
  bool has_potentials() const { return !potentials_.empty(); }
  // Whether some potential is contact's (LoadPotential::contact).
  bool has_contact() const { return has_contact_; }
  // Sets `blocks` to the loads' Hessian blocks, ∇²S⁺(z) + w s² ∇²B⁺(p(z)) (9 per particle, this
  // rank's rows); false (and `blocks` untouched) when the scene has no potentials.
  bool add_potential_blocks(const double* z, std::vector<double>& blocks);
  // Contact's acceleration −M⁻¹∇B(p(z)) (3N, zero on held unknowns and other ranks' rows), for
  // ImplicitScheme::finish_stage and correct; empty when the scene has no contact potential.
  // Collective.
  void potential_acceleration(const double* z, std::vector<double>& out);
  // What preconditioners need: the unknowns' masses, which are held, the current A.
  const std::vector<double>& mass() const { return mass_; }
  const std::vector<char>& fixed() const { return fixed_; }
  double inertia() const { return inertia_; }
  Dynamics& dynamics() { return dynamics_; }

  // Over several ranks (Dynamics::distribute) the system's arrays stay 3N over the rank's rows
  // (its own and its ghosts), but it reads and writes only its own unknowns [first_unknown(),
  // end_unknown()), and the points it is given must have current ghosts (Dynamics::share);
  // objective(), residual(), apply() and begin_step() are then collective, and objective()
  // returns the whole system's E. On one rank: all unknowns.
  std::size_t first_unknown() const { return first_; }
  std::size_t end_unknown() const { return end_; }
  bool distributed() const { return dynamics_.halo() != nullptr; }
  // Σ over the ranks of `value` (in rank order: the same bits on every rank); value on one rank.
  double sum_over_ranks(double value) const;

  // The size of the terms of the last objective() value: changes of E below about 1e-13 of it
  // are round-off, which no line search can resolve.
  double objective_magnitude() const { return magnitude_; }
  // The constraint reactions at the last evaluated point, 3N: −(F_int + f) on held unknowns
  // (their prescribed acceleration does no work), 0 elsewhere.
  std::vector<double> reactions() const;

  // Model passes (forces and energy together) and the requests the kept one answered.
  long residual_passes = 0, objective_passes = 0, cache_hits = 0, tangent_products = 0,
       linearizations = 0;

 private:
  // p(z): z itself where s = 1, else written to `out`.
  const double* potential_point(const double* z, std::vector<double>& out) const;
  // F_int(z) and Π(z) into force_ and elastic_, and the potentials' S(z), B(p(z)) and their
  // gradients into smooth_, contact_ and their gradients, unless z is the point they were computed
  // at and the model has not changed since (Model::revision).
  void evaluate(const double* z, long& passes);
  // out += the potentials' coupling blocks (LoadPotential::add_coupling) times v, at the
  // linearization point.
  void add_coupling(const double* v, double* out);

  Dynamics& dynamics_;
  std::vector<LoadPotential*> potentials_;
  bool has_contact_ = false;         // some potential is contact's
  bool has_coupling_ = false;        // some potential couples particles (LoadPotential::couples)
  std::vector<double> coupling_;     // scratch: the coupling blocks' product
  double weight_ = 1, scale_ = 1;    // w and s of the stage
  std::vector<double> origin_;       // y_n, for p(z) where s ≠ 1
  std::vector<double> mapped_;       // scratch: p(z)
  double smooth_ = 0, contact_ = 0;  // S and B at point_
  std::vector<double> smooth_gradient_;  // ∇S and ∇B at point_ (3N, when there are potentials)
  std::vector<double> contact_gradient_;
  std::vector<double> blocks_;  // ∇²S⁺ + w s² ∇²B⁺ at linearization_, 9 per particle
  Tangent tangent_;
  std::size_t first_ = 0, end_ = 0;  // this rank's unknowns
  std::vector<char> fixed_;          // per unknown: held by a constraint
  std::vector<double> mass_;         // per unknown
  std::vector<double> external_;     // f
  std::vector<double> target_;       // ỹ
  std::vector<double> force_;        // F_int at point_
  std::vector<double> point_;        // where force_ and elastic_ were computed
  double elastic_ = 0;
  bool cached_ = false;
  std::size_t revision_ = 0;           // the model's, at point_
  std::vector<double> linearization_;  // where the Newton matrix is taken
  bool linearized_ = false;            // the model holds linearization_'s tangent
  Tangent linearized_tangent_ = Tangent::automatic;
  SparseSymmetric majoriser_;   // tangent: majoriser, assembled at linearization_
  std::vector<double> masked_;  // scratch: v with held unknowns zeroed
  double inertia_ = 0;
  double magnitude_ = 0;
};

}  // namespace fissure
