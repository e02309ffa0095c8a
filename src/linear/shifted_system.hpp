#pragma once
// The matrix implicit steps factorize, A M + K, with unknowns held by constraints taken out.
#include <vector>

#include "linear/sparse_symmetric.hpp"

namespace fissure {

// K ← K + A M (M diagonal, per unknown), then each fixed unknown gets a zero row and column and
// a diagonal of `scale` (held_scale()), so the factorization stays well scaled and the solution
// leaves fixed unknowns unchanged. `diagonal[r]` is the index of entry (r, r), −1 for an empty
// row (a row another MPI rank holds), which is left as it is.
void shift_and_fix(SparseSymmetric& K, const std::vector<int>& diagonal,
                   const std::vector<double>& mass, double inertia, const std::vector<char>& fixed,
                   double scale);
// The same with the scale of its own rows.
void shift_and_fix(SparseSymmetric& K, const std::vector<int>& diagonal,
                   const std::vector<double>& mass, double inertia, const std::vector<char>& fixed);
// The largest diagonal entry of K + A M over the rows that are not empty.
double held_scale(const SparseSymmetric& K, const std::vector<int>& diagonal,
                  const std::vector<double>& mass, double inertia);

// Index of entry (r, r) for each row, −1 where the row is empty.
std::vector<int> diagonal_positions(const SparseSymmetric& K);

}  // namespace fissure
