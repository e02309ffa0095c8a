#include "linear/shifted_system.hpp"

#include <algorithm>

namespace fissure {

void shift_and_fix(SparseSymmetric& K, const std::vector<int>& diagonal,
                   const std::vector<double>& mass, double inertia,
                   const std::vector<char>& fixed) {
  double scale = 0;
  for (int r = 0; r < K.rows; ++r)
    scale = std::max(scale, K.values[diagonal[r]] + inertia * mass[r]);
#pragma omp parallel for schedule(static)
  for (int r = 0; r < K.rows; ++r) {
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
