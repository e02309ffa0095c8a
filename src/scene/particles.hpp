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
struct Families {
  std::vector<int> offsets;              // count + 1
  std::vector<int> neighbors;            // j for each bond, rows sorted by j
  std::vector<double> reference_length;  // |ξ| = |x_j - x_i|
  std::vector<int> reverse;              // index of the same bond in row j (j → i)
  std::size_t directed_bonds() const { return neighbors.size(); }
};

// Builds the families: every particle of the same body within `horizon[body]` (δ in metres),
// found with a k-d tree.
Families build_families(const Particles& particles, const std::vector<double>& horizon_of_body);

// Reorders particles along a Morton curve of cell size `cell` so that families are near in
// memory. Returns the permutation: new index k holds the particle that had index order[k].
std::vector<int> sort_spatially(Particles& particles, double cell);

}  // namespace fissure
