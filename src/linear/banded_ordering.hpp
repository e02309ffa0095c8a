#pragma once
// A banded fill-reducing ordering: reverse Cuthill–McKee (George and Liu, "Computer Solution of
// Large Sparse Positive Definite Systems", 1981, §4.3): the level sets of a breadth-first search
// from a pseudo-peripheral row, each row's new neighbours by increasing degree, reversed. On an
// elongated body the levels are its cross-sections, so the factor of a one- or two-hop stiffness
// is a band as wide as one cross-section's couplings: on the glass cantilever (1 m × 0.1 m ×
// 0.1 m, two-hop tangent) 0.45 of the fill of METIS's nested dissection, which CHOLMOD picks
// without it (docs/integrators.md, "The linear solves"). SupernodalCholesky offers it to CHOLMOD
// as a candidate next to AMD and METIS.
#include <vector>

#include "linear/sparse_symmetric.hpp"

namespace fissure {

// perm[k] = the row of A that comes k-th (CHOLMOD's convention); every row once, each connected
// component's rows together. A's pattern must be symmetric (both triangles stored, as
// bond_pattern and two_hop_pattern store them).
std::vector<int> reverse_cuthill_mckee(const SparseSymmetric& A);

}  // namespace fissure
