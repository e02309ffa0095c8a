#pragma once
// The matrix implicit steps factorize, A M + K, with unknowns held by constraints taken out.
#include <vector>

#include "linear/sparse_symmetric.hpp"

namespace fissure {

// K ← K + A M (M diagonal, per unknown), then each fixed unknown gets a zero row and column and
// a diagonal the size of the largest other one, so the factorization stays well scaled and the
// solution leaves fixed unknowns unchanged. `diagonal[r]` is the index of entry (r, r).
void shift_and_fix(SparseSymmetric& K, const std::vector<int>& diagonal,
                   const std::vector<double>& mass, double inertia, const std::vector<char>& fixed);

// Index of entry (r, r) for each row.
std::vector<int> diagonal_positions(const SparseSymmetric& K);

}  // namespace fissure
