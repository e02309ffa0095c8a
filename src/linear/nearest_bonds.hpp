#pragma once
// A sparse one-hop pattern for preconditioners of large scenes: of each family only the bonds to
// its nearest members. The one-hop 3N×3N pattern of a whole family (bond_pattern) has a Cholesky
// factor too large to keep at 1e5 particles; keeping a fixed number of nearest members thins the
// separators that fill-in grows with, while the bonds kept still carry bending, which a scalar
// matrix (scalar_bond_pattern) does not.
#include <functional>
#include <vector>

#include "linear/sparse_symmetric.hpp"

namespace fissure {

// The members kept by the `nearest` preconditioner (petsc_newton's and arkode's). Measured on the
// glass cantilever (bench_implicit_step, backward Euler at 300× the explicit estimate, 127
// members per interior family): CG iterations per Newton iteration 30 / 15 / 11 / 9 keeping
// 12 / 20 / 30 / 45 members (6.5 with every member), and at 95,187 particles 20 members take
// 7.2 s per step and 5.7 GB, 30 members 6.3 s and 7.9 GB.
constexpr int kNearestMembers = 20;

// One flag per directed bond: whether the bond joins particles of which one counts the other
// among its `members` nearest family members (ties at the last length kept), so that
// kept[b] == kept[reverse[b]]. A family of at most `members` members keeps every bond.
// Over several ranks with split families (a ghost's row holds only some of its members),
// `share_reach` gives the ghosts their own ranks' reach (one double per particle, the length of
// a row's last kept member) before the flags are set.
std::vector<char> nearest_bonds(const Families& families, int members,
                                const std::function<void(double* reach)>& share_reach = {});

// 3×3 blocks coupling each particle with itself and the members its kept bonds join, in
// increasing order (bond_pattern's layout over the kept bonds only).
SparseSymmetric nearest_bond_pattern(const Families& families, const std::vector<char>& kept);
// The same with the rows of particles [first, end) only, the others empty (bond_pattern).
SparseSymmetric nearest_bond_pattern(const Families& families, const std::vector<char>& kept,
                                     int first, int end);

}  // namespace fissure
