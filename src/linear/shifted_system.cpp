#include "linear/shifted_system.hpp"

#include <algorithm>

namespace fissure {

double held_scale(const SparseSymmetric& K, const std::vector<int>& diagonal,
                  const std::vector<double>& mass, double inertia) {
  double scale = 0;
  for (int r = 0; r < K.rows; ++r)
    if (diagonal[r] >= 0) scale = std::max(scale, K.values[diagonal[r]] + inertia * mass[r]);
  return scale;
}

void shift_and_fix(SparseSymmetric& K, const std::vector<int>& diagonal,
                   const std::vector<double>& mass, double inertia,
                   const std::vector<char>& fixed) {
  shift_and_fix(K, diagonal, mass, inertia, fixed, held_scale(K, diagonal, mass, inertia));
}

void shift_and_fix(SparseSymmetric& K, const std::vector<int>& diagonal,
                   const std::vector<double>& mass, double inertia, const std::vector<char>& fixed,
                   double scale) {
#pragma omp parallel for schedule(static)
  for (int r = 0; r < K.rows; ++r) {
    if (diagonal[r] < 0) continue;
    for (int k = K.offsets[r]; k < K.offsets[r + 1]; ++k)
      if (fixed[r] || fixed[K.columns[k]]) K.values[k] = 0;
    K.values[diagonal[r]] += fixed[r] ? scale : inertia * mass[r];
  }
}

std::vector<int> diagonal_positions(const SparseSymmetric& K) {
  std::vector<int> diagonal(K.rows);
  for (int r = 0; r < K.rows; ++r) diagonal[r] = K.find(r, r);
  return diagonal;
}

}  // namespace fissure
