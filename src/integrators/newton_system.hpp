#pragma once
// The nonlinear system of one implicit step, free of any solver library: the incremental
// potential of implicit_scheme.hpp, its gradient (the residual) and its Hessian, with the
// particles a constraint holds eliminated (their unknowns fixed at the value they must take).
#include <vector>

#include "integrators/implicit_scheme.hpp"
#include "linear/sparse_symmetric.hpp"

namespace fissure {

class NewtonSystem {
 public:
  // tangent: "majoriser" (bond-wise, bond_pattern), or on two_hop_pattern "exact", "projected"
  // (the tangent without compressed bonds' geometric term) or "auto" (either; use_tangent
  // picks). See model.hpp.
  NewtonSystem(Dynamics& dynamics, const std::string& tangent);
  // Switches between "exact" and "projected" (same pattern).
  void use_tangent(const std::string& tangent) {
    if (tangent_ != "majoriser") tangent_ = tangent;
  }

  // Prepares a step of size h from `state`: f = M g + contact at the start of the step, scaled
  // by `load_factor`; held particles fixed. Returns the starting guess z0.
  std::vector<double> begin_step(const ImplicitScheme& scheme, const State& state, double h,
                                 double load_factor);
  // E(z), ∇E(z) (zero on held unknowns), and ∇²E(z) into matrix().values.
  double objective(const double* z);
  void residual(const double* z, double* r);
  void hessian(const double* z);
  const SparseSymmetric& matrix() const { return matrix_; }
  // The size of the terms of the last objective() value: changes of E below about 1e-13 of it
  // are round-off, which no line search can resolve.
  double objective_magnitude() const { return magnitude_; }
  // The constraint reactions at the last residual() point, 3N: −(F_int + f) on held unknowns
  // (their prescribed acceleration does no work), 0 elsewhere.
  std::vector<double> reactions() const;

 private:
  Dynamics& dynamics_;
  std::string tangent_;
  SparseSymmetric matrix_;
  std::vector<int> diagonal_;     // index of entry (r, r) in matrix_
  std::vector<char> fixed_;       // per unknown: held by a constraint
  std::vector<double> mass_;      // per unknown
  std::vector<double> external_;  // f
  std::vector<double> target_;    // ỹ
  std::vector<double> force_;     // scratch: F_int
  double inertia_ = 0;
  double magnitude_ = 0;
};

}  // namespace fissure
