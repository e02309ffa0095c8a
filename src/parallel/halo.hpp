#pragma once
// The ghosts of one rank's rows: the family members it does not own, filled from their owners
// (issue 18, item 1). Per-particle arrays keep the global numbering on every rank: a rank reads
// and writes its own range and the ghosts' entries only.
#include <mpi.h>

#include <cstddef>
#include <memory>
#include <vector>

#include "parallel/index_exchange.hpp"
#include "scene/particles.hpp"

namespace fissure {

struct SharedBonds;

class Halo {
 public:
  // This rank (of comm) owns rows [boundaries[rank], boundaries[rank + 1]) of families; every
  // rank passes the same boundaries (split_rows_by_bonds). PETSc must be initialised. Collective.
  Halo(MPI_Comm comm, const Families& families, std::vector<int> boundaries);

  int begin() const { return exchange_.begin(); }
  int end() const { return exchange_.end(); }
  MPI_Comm comm() const { return exchange_.comm(); }
  // Which rank owns which particles (split_rows_by_bonds).
  const std::vector<int>& boundaries() const { return exchange_.boundaries(); }
  // The ghosts, sorted: every family member of an owned row that this rank does not own.
  const std::vector<int>& ghosts() const { return exchange_.needed(); }
  // Copies each ghost's `width` values (values[width * j .. width * j + width)) from its owner's
  // array into this rank's. Collective: every rank calls it with the same width.
  void fill(double* values, int width) const { exchange_.fill(values, width); }
  // Bytes one fill of `width` doubles receives on this rank.
  std::size_t received_bytes(int width) const { return ghosts().size() * width * sizeof(double); }
  // The pairs this rank shares with others (SharedBonds below) for the families it was built
  // on, made at the first call and kept, so that the model and the fracture post-step use one
  // star forest. Collective at the first call; throws std::invalid_argument for other families.
  const SharedBonds& shared_bonds(const Families& families) const;

 private:
  IndexExchange exchange_;
  const Families* families_ = nullptr;
  mutable std::shared_ptr<const SharedBonds> shared_bonds_;
};

// The pairs a rank shares with other ranks (issue 18, item 1: the bond star forest): the bonds of
// its rows whose other end is owned elsewhere, in CSR order, their rows, and the exchange that
// copies, per bond array in CSR order, each such bond's reverse (families.reverse) from the rank
// that owns it, into that reverse's entry here (in this rank's CSR, Families).
struct SharedBonds {
  std::vector<int> bonds, rows;
  std::unique_ptr<IndexExchange> reverses;
};

}  // namespace fissure
