#pragma once
// Which rank owns which particles: contiguous ranges of the (Morton-sorted) particle ids, so that
// a rank's range is its PETSc layout; a rank numbers its own particles and its
// ghosts on their own, in the order of their ids (number_locally).
#include <vector>

namespace fissure {

// Splits the rows of a CSR structure (offsets, rows + 1 entries) into `parts` contiguous ranges
// with about equal numbers of bonds: part p owns rows [boundaries[p], boundaries[p + 1]). Each
// boundary is the row whose bond offset is nearest p × bonds / parts, so a part holds its share
// of the bonds to within one row's bonds. Throws std::invalid_argument for parts < 1.
std::vector<int> split_rows_by_bonds(const std::vector<int>& offsets, int parts);

// The part that owns row i under `boundaries` (as split_rows_by_bonds returns).
int owner_of(const std::vector<int>& boundaries, int i);

}  // namespace fissure
