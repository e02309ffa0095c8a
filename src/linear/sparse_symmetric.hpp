#pragma once
// A sparse symmetric matrix in compressed rows with both triangles stored and columns sorted in
// each row: the layout CHOLMOD (as compressed columns of the transpose) and PETSc's SEQAIJ share.
// Its pattern is fixed when it is built and stays so for a run: broken bonds keep their zeros,
// so a symbolic factorization is done once.
#include <vector>

#include "scene/particles.hpp"

namespace fissure {

struct SparseSymmetric {
  int rows = 0;
  std::vector<int> offsets;  // rows + 1
  std::vector<int> columns;  // sorted in each row
  std::vector<double> values;

  // Index of entry (r, c) in columns/values, or −1 when it is not in the pattern.
  int find(int r, int c) const;
  // y = A x.
  void multiply(const double* x, double* y) const;
};

// 3×3 blocks coupling each particle with itself and its family: the pattern of bond-wise
// stiffness. Row 3i + a holds, for each particle j of {i} ∪ H_i in increasing order, the columns
// 3j, 3j + 1, 3j + 2.
SparseSymmetric bond_pattern(const Families& families);
// The same with the rows of particles [first, end) only, the others empty (an MPI rank's rows:
// the matrix keeps the families' numbering, its memory only the rank's rows).
SparseSymmetric bond_pattern(const Families& families, int first, int end);

// 3×3 blocks coupling each particle with every particle within two family hops: the pattern of
// the exact tangent, whose dilatation terms couple all members of a family with each other.
SparseSymmetric two_hop_pattern(const Families& families);

// One scalar entry coupling each particle with itself and its family (N×N): the pattern of a
// scalar one-hop stiffness (Model::assemble_scalar_stiffness), columns sorted.
SparseSymmetric scalar_bond_pattern(const Families& families);

// 3×3 blocks from a particle adjacency (each particle's row: a sorted list of particles, itself
// included).
SparseSymmetric expand_blocks(const std::vector<std::vector<int>>& adjacency);

// Position of particle i's own block in its row of bond_pattern: the number of family members
// with a smaller index.
int self_position(const Families& families, int i);

}  // namespace fissure
