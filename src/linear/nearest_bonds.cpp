#include "linear/nearest_bonds.hpp"

#include <algorithm>

namespace fissure {

std::vector<char> nearest_bonds(const Families& families, int members,
                                const std::function<void(double* reach)>& share_reach) {
  const int n = static_cast<int>(families.offsets.size()) - 1;
  const auto& off = families.offsets;
  const auto& length = families.reference_length;
  // The length of each row's last kept member: its `members`-th smallest bond length.
  std::vector<double> reach(n);
#pragma omp parallel
  {
    std::vector<double> lengths;
#pragma omp for schedule(static)
    for (int i = 0; i < n; ++i) {
      lengths.assign(length.begin() + off[i], length.begin() + off[i + 1]);
      if (static_cast<int>(lengths.size()) <= members) {
        reach[i] = lengths.empty() ? 0.0 : *std::max_element(lengths.begin(), lengths.end());
        continue;
      }
      std::nth_element(lengths.begin(), lengths.begin() + (members - 1), lengths.end());
      reach[i] = lengths[members - 1];
    }
  }
  if (share_reach) share_reach(reach.data());
  std::vector<char> kept(families.directed_bonds());
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i)
    for (int b = off[i]; b < off[i + 1]; ++b)
      kept[b] = length[b] <= std::max(reach[i], reach[families.neighbors[b]]);
  return kept;
}

SparseSymmetric nearest_bond_pattern(const Families& families, const std::vector<char>& kept) {
  return nearest_bond_pattern(families, kept, 0, static_cast<int>(families.offsets.size()) - 1);
}

SparseSymmetric nearest_bond_pattern(const Families& families, const std::vector<char>& kept,
                                     int first, int end) {
  std::vector<std::vector<int>> adjacency(families.offsets.size() - 1);
#pragma omp parallel for schedule(static)
  for (int i = first; i < end; ++i) {
    std::vector<int>& row = adjacency[i];
    for (int b = families.offsets[i]; b < families.offsets[i + 1]; ++b)
      if (kept[b]) row.push_back(families.neighbors[b]);
    row.insert(std::lower_bound(row.begin(), row.end(), i), i);
  }
  return expand_blocks(adjacency);
}

}  // namespace fissure
