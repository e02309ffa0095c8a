#pragma once
// Preconditioned conjugate gradients (Hestenes–Stiefel; Saad, Iterative Methods, Alg. 9.1) for an
// SPD operator given as a product, with the stopping test left to the caller: the caller knows
// in which norm its residual is judged (ARKODE's stage systems: arkode_linear_solver.cpp).
#include <functional>
#include <utility>
#include <vector>

namespace fissure {

class ConjugateGradient {
 public:
  using Product = std::function<void(const double* in, double* out)>;
  // True when the residual r = b − A x is small enough.
  using Test = std::function<bool(const double* r)>;
  enum class Outcome {
    converged,
    iteration_limit,  // `limit` products with A did not reach the test
    breakdown,        // pᵀAp ≤ 0: A (or the preconditioner) is not positive definite
  };
  // Σ over the parts of a vector split over MPI ranks (each rank's dot product in, the whole
  // one out; the same on every rank); empty on one rank.
  using Sum = std::function<double(double)>;
  explicit ConjugateGradient(std::size_t n, Sum sum = {})
      : r_(n), z_(n), p_(n), q_(n), sum_(std::move(sum)) {}
  // x = A⁻¹ b from x = 0, preconditioned by P (z = P⁻¹ r), with at most `limit` products with A.
  Outcome solve(const Product& A, const Product& P, const Test& done, int limit, const double* b,
                double* x);
  // Products with A in the last solve.
  int iterations() const { return iterations_; }

 private:
  double dot(const std::vector<double>& a, const std::vector<double>& b) const;

  std::vector<double> r_, z_, p_, q_;
  Sum sum_;
  int iterations_ = 0;
};

}  // namespace fissure
