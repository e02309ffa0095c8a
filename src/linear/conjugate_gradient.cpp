#include "linear/conjugate_gradient.hpp"

#include <algorithm>

namespace fissure {

double ConjugateGradient::dot(const std::vector<double>& a, const std::vector<double>& b) const {
  double sum = 0;
  for (std::size_t k = 0; k < a.size(); ++k) sum += a[k] * b[k];
  return sum_ ? sum_(sum) : sum;
}

ConjugateGradient::Outcome ConjugateGradient::solve(const Product& A, const Product& P,
                                                    const Test& done, int limit, const double* b,
                                                    double* x) {
  const std::size_t n = r_.size();
  iterations_ = 0;
  std::fill(x, x + n, 0.0);
  std::copy(b, b + n, r_.begin());
  if (done(r_.data())) return Outcome::converged;
  P(r_.data(), z_.data());
  p_ = z_;
  double rz = dot(r_, z_);
  while (iterations_ < limit) {
    A(p_.data(), q_.data());
    ++iterations_;
    const double curvature = dot(p_, q_);
    if (!(curvature > 0) || !(rz > 0)) return Outcome::breakdown;
    const double alpha = rz / curvature;
    for (std::size_t k = 0; k < n; ++k) {
      x[k] += alpha * p_[k];
      r_[k] -= alpha * q_[k];
    }
    if (done(r_.data())) return Outcome::converged;
    P(r_.data(), z_.data());
    const double next = dot(r_, z_);
    const double beta = next / rz;
    rz = next;
    for (std::size_t k = 0; k < n; ++k) p_[k] = z_[k] + beta * p_[k];
  }
  return Outcome::iteration_limit;
}

}  // namespace fissure
