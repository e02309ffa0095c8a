#include "parallel/halo.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace fissure {

namespace {

void check(int code, const char* what) {
  if (code != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + what + " failed");
}

}  // namespace

// This rank's own rows and its ghosts (their rows and their particles in the whole scene).
struct Halo::Rows {
  int begin = 0, end = 0;
  std::vector<int> ghost_rows, ghost_ids;
  bool local = false;
};

namespace {

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
  shared.reverses =
      std::make_unique<IndexExchange>(halo.comm(), halo.bond_boundaries(), std::move(needed),
                                      std::move(slots), families.offsets[halo.begin()]);
  return shared;
}

}  // namespace

// The own rows: the particles of this rank's range (whole families) or the range of them
// number_locally kept; the ghosts: the members of the own rows outside them, sorted by their
// particles in the whole scene.
Halo::Rows Halo::own_and_ghost_rows(const Families& families, const std::vector<int>& boundaries,
                                    MPI_Comm comm) {
  const int rank = rank_in_split(comm, boundaries, families.total_rows(), "Halo");
  Halo::Rows rows;
  rows.local = families.whole_rows >= 0;
  rows.begin = rows.local ? families.first_own_row() : boundaries[rank];
  rows.end = rows.local ? families.end_own_row() : boundaries[rank + 1];
  if (rows.end - rows.begin != boundaries[rank + 1] - boundaries[rank] ||
      (rows.local && families.global_row(rows.begin) != boundaries[rank]))
    throw std::invalid_argument("Halo: the families' own rows are not this rank's range");
  for (int i = rows.begin; i < rows.end; ++i)
    for (int b = families.offsets[i]; b < families.offsets[i + 1]; ++b) {
      const int j = families.neighbors[b];
      if (j < rows.begin || j >= rows.end) rows.ghost_rows.push_back(j);
    }
  auto by_id = [&families](int a, int b) {
    return families.global_row(a) < families.global_row(b);
  };
  std::sort(rows.ghost_rows.begin(), rows.ghost_rows.end(), by_id);
  rows.ghost_rows.erase(std::unique(rows.ghost_rows.begin(), rows.ghost_rows.end()),
                        rows.ghost_rows.end());
  for (const int j : rows.ghost_rows) rows.ghost_ids.push_back(families.global_row(j));
  return rows;
}

namespace {

// The first bond of each rank's own rows in the whole families' CSR, and the total.
std::vector<int> own_bond_boundaries(MPI_Comm comm, const Families& families, int begin, int end) {
  int size = 1;
  check(MPI_Comm_size(comm, &size), "MPI_Comm_size");
  const int own = families.offsets[end] - families.offsets[begin];
  std::vector<int> counts(size);
  check(MPI_Allgather(&own, 1, MPI_INT, counts.data(), 1, MPI_INT, comm), "MPI_Allgather");
  std::vector<int> boundaries(size + 1, 0);
  for (int r = 0; r < size; ++r) boundaries[r + 1] = boundaries[r] + counts[r];
  return boundaries;
}

}  // namespace

Halo::Halo(MPI_Comm comm, const Families& families, std::vector<int> boundaries)
    : Halo(comm, families, boundaries, own_and_ghost_rows(families, boundaries, comm)) {}

Halo::Halo(MPI_Comm comm, const Families& families, std::vector<int> boundaries, Rows rows)
    : begin_(rows.begin),
      end_(rows.end),
      ghost_rows_(rows.ghost_rows),
      bond_boundaries_(own_bond_boundaries(comm, families, rows.begin, rows.end)),
      exchange_(comm, std::move(boundaries), std::move(rows.ghost_ids),
                rows.local ? std::move(rows.ghost_rows) : std::vector<int>{},
                rows.local ? rows.begin : -1),
      families_(&families) {}

const SharedBonds& Halo::shared_bonds(const Families& families) const {
  if (&families != families_)
    throw std::invalid_argument("Halo::shared_bonds: not the families the halo was built on");
  if (!shared_bonds_) shared_bonds_ = std::make_shared<SharedBonds>(share_bonds(*this, families));
  return *shared_bonds_;
}

}  // namespace fissure
