#pragma once
// Particles and their families as flat arrays (structure of arrays; bonds in CSR order).
#include <cstddef>
#include <vector>

namespace fissure {

struct Particles {
  std::vector<double> reference;  // x_i, 3 * count, xyz interleaved
  std::vector<double> velocity;   // initial velocity, 3 * count
  std::vector<double> volume;     // V_i
  std::vector<double> mass;       // ρ V_i
  std::vector<int> body;          // index into Config::bodies
  int count() const { return static_cast<int>(volume.size()); }
};

// Family H_i of every particle (paper §3), as directed bonds: each pair appears in both rows.
// Over several ranks (docs/mpi.md) a rank keeps only the rows it needs (split_families): its own
// rows whole, and of each ghost's row only its bonds to the own rows (the reverses of the own
// rows' bonds to it). number_locally then keeps only those rows, numbered on their own in the
// order of their ids in the whole scene (global_id), so that nothing here grows with the whole
// scene. Bonds are numbered in this CSR, and global_offsets keeps each row's offset in
// the whole families' CSR, in which checkpoints and the bond star forest number the bonds.
struct Families {
  std::vector<int> offsets;              // count + 1
  std::vector<int> neighbors;            // j for each bond, rows sorted by j
  std::vector<double> reference_length;  // |ξ| = |x_j - x_i|
  std::vector<int> reverse;              // index of the same bond in row j (j → i)
  // Each row's offset in the whole families' CSR, and their bond count last; empty: these are
  // whole.
  std::vector<int> global_offsets;
  int own_begin = 0, own_end = -1;  // the rows this rank owns; −1: to the last row
  // Per bond of a ghost's row, in CSR order: its position in the whole row.
  std::vector<int> trimmed_position;
  // Numbered locally (number_locally): each row's particle in the whole scene, and the
  // particles of the whole scene. Empty and −1: the rows are the scene's particles.
  std::vector<int> global_id;
  int whole_rows = -1;
  std::size_t directed_bonds() const { return neighbors.size(); }
  bool whole() const { return global_offsets.empty(); }
  int rows() const { return static_cast<int>(offsets.size()) - 1; }
  // The particle of row i in the whole scene, and the whole scene's particle count.
  int global_row(int i) const { return global_id.empty() ? i : global_id[i]; }
  int total_rows() const { return whole_rows < 0 ? rows() : whole_rows; }
  // The rows kept whole, [first_own_row(), end_own_row()): all of them unless split.
  int first_own_row() const { return own_begin; }
  int end_own_row() const { return own_end < 0 ? rows() : own_end; }
  // Bonds of the whole families, on every rank.
  std::size_t total_directed_bonds() const {
    return whole() ? neighbors.size() : static_cast<std::size_t>(global_offsets.back());
  }
  // The whole families' index of bond b of row i.
  long global_bond(int i, int b) const {
    if (whole()) return b;
    if (i >= own_begin && i < end_own_row()) return long(global_offsets[i]) + (b - offsets[i]);
    const int own_bonds = offsets[end_own_row()] - offsets[own_begin];
    return long(global_offsets[i]) + trimmed_position[b < offsets[own_begin] ? b : b - own_bonds];
  }
  // A per-bond array of the whole families (a checkpoint's) in this CSR: the kept bonds'
  // entries. Returned as given when the families are whole or its size is not theirs.
  template <class T>
  std::vector<T> localize(const std::vector<T>& whole_array) const {
    if (whole() || whole_array.size() != total_directed_bonds()) return whole_array;
    std::vector<T> local(directed_bonds());
    for (int i = 0; i < rows(); ++i)
      for (int b = offsets[i]; b < offsets[i + 1]; ++b) local[b] = whole_array[global_bond(i, b)];
    return local;
  }
  // A per-particle array of the whole scene (`width` values per particle) in these rows.
  // Returned as given when the rows are the scene's or its size is not the scene's.
  template <class T>
  std::vector<T> localize_rows(const std::vector<T>& whole_array, int width) const {
    if (whole_rows < 0 || whole_array.size() != std::size_t(width) * total_rows())
      return whole_array;
    std::vector<T> local(std::size_t(width) * rows());
    for (int i = 0; i < rows(); ++i)
      for (int k = 0; k < width; ++k)
        local[std::size_t(width) * i + k] = whole_array[std::size_t(width) * global_id[i] + k];
    return local;
  }
};

// Builds the families: every particle of the same body within `horizon[body]` (δ in metres),
// found with a k-d tree.
Families build_families(const Particles& particles, const std::vector<double>& horizon_of_body);

// What a split over ranks needs before any family is kept: each particle's number of family
// members and the distance to its nearest member (+∞ without one).
struct FamilySizes {
  std::vector<int> members;     // per particle
  std::vector<double> nearest;  // per particle
  // The whole families' CSR offsets. Throws std::length_error past the 2^31 bonds of int.
  std::vector<int> offsets() const;
};
// Of the particles [first, end); the others get 0 members and +∞.
FamilySizes count_families(const Particles& particles, const std::vector<double>& horizon_of_body,
                           int first, int end);

// The rows [begin, end) of the whole families, and of their members' rows (the ghosts) the bonds
// to those rows; the other rows empty (Families above); `offsets` from count_families.
Families split_families(const Particles& particles, const std::vector<double>& horizon_of_body,
                        const std::vector<int>& offsets, int begin, int end);

// The rows split_families kept (its own rows and its ghosts'), numbered locally (Families) in
// the order of their ids; `particles` keeps those rows' particles, in that order.
Families number_locally(Families split, Particles& particles);

// Reorders particles along a Morton curve of cell size `cell` so that families are near in
// memory. Returns the permutation: new index k holds the particle that had index order[k].
std::vector<int> sort_spatially(Particles& particles, double cell);

}  // namespace fissure
