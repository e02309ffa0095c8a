#include "parallel/halo.hpp"

#include <algorithm>
#include <stdexcept>

namespace fissure {

namespace {

// The family members of rows [begin, end) outside that range, sorted and unique.
std::vector<int> ghosts_of(const Families& families, const std::vector<int>& boundaries,
                           MPI_Comm comm) {
  const int rows = static_cast<int>(families.offsets.size()) - 1;
  const int rank = rank_in_split(comm, boundaries, rows, "Halo");
  const int begin = boundaries[rank], end = boundaries[rank + 1];
  std::vector<int> ghosts;
  for (int i = begin; i < end; ++i)
    for (int b = families.offsets[i]; b < families.offsets[i + 1]; ++b) {
      const int j = families.neighbors[b];
      if (j < begin || j >= end) ghosts.push_back(j);
    }
  std::sort(ghosts.begin(), ghosts.end());
  ghosts.erase(std::unique(ghosts.begin(), ghosts.end()), ghosts.end());
  return ghosts;
}

// A rank's bonds are the CSR range of its rows: bond b of row i pairs with bond reverse[b] of
// row j, in the range of j's rank. The forest numbers bonds as the whole families do; where this
// rank keeps only some rows (Families), its own bonds start at offsets[begin] and each reverse
// lands in its slot of the kept row j.
SharedBonds share_bonds(const Halo& halo, const Families& families) {
  SharedBonds shared;
  std::vector<std::pair<int, int>> reverses;  // whole families' index, slot here
  for (int i = halo.begin(); i < halo.end(); ++i)
    for (int b = families.offsets[i]; b < families.offsets[i + 1]; ++b) {
      const int j = families.neighbors[b];
      if (j >= halo.begin() && j < halo.end()) continue;
      shared.bonds.push_back(b);
      shared.rows.push_back(i);
      reverses.emplace_back(static_cast<int>(families.global_bond(j, families.reverse[b])),
                            families.reverse[b]);
    }
  std::sort(reverses.begin(), reverses.end());
  std::vector<int> needed, slots;
  for (const auto& [global, slot] : reverses) {
    needed.push_back(global);
    slots.push_back(slot);
  }
  const std::vector<int>& whole = families.whole() ? families.offsets : families.global_offsets;
  std::vector<int> bond_boundaries;
  for (const int row : halo.boundaries()) bond_boundaries.push_back(whole[row]);
  shared.reverses =
      std::make_unique<IndexExchange>(halo.comm(), std::move(bond_boundaries), std::move(needed),
                                      std::move(slots), families.offsets[halo.begin()]);
  return shared;
}

}  // namespace

Halo::Halo(MPI_Comm comm, const Families& families, std::vector<int> boundaries)
    : exchange_(comm, boundaries, ghosts_of(families, boundaries, comm)), families_(&families) {}

const SharedBonds& Halo::shared_bonds(const Families& families) const {
  if (&families != families_)
    throw std::invalid_argument("Halo::shared_bonds: not the families the halo was built on");
  if (!shared_bonds_) shared_bonds_ = std::make_shared<SharedBonds>(share_bonds(*this, families));
  return *shared_bonds_;
}

}  // namespace fissure
