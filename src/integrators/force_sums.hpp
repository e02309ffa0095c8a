#pragma once
// The two sums a force load needs: adding its force to a total, and its work over a step.
#include <cstddef>
#include <vector>

namespace fissure {

// f += source, in parallel.
inline void add_to(const std::vector<double>& source, double* f) {
  const std::size_t n = source.size();
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < n; ++k) f[k] += source[k];
}

// Σ F·Δy over a step from `before` to `after` [J] (the ledger's load work).
inline double work_of(const std::vector<double>& force, const double* before, const double* after) {
  double sum = 0;
  const std::size_t n = force.size();
#pragma omp parallel for reduction(+ : sum) schedule(static)
  for (std::size_t k = 0; k < n; ++k) sum += force[k] * (after[k] - before[k]);
  return sum;
}

}  // namespace fissure
