#pragma once
// The ghosts of one rank's rows: the family members it does not own, filled from their owners
// (docs/mpi.md). Per-particle arrays are numbered as the families' rows: locally
// (number_locally: the own rows and the ghosts, in the order of their ids) or, for whole
// families, as the scene.
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
  // This rank (of comm) owns particles [boundaries[rank], boundaries[rank + 1]) of the whole
  // scene; every rank passes the same boundaries (split_rows_by_bonds). `families` are whole
  // (those particles are its rows) or this rank's numbered locally (number_locally).
  // PETSc must be initialised. Collective.
  Halo(MPI_Comm comm, const Families& families, std::vector<int> boundaries);

  // The own rows, in the families' numbering.
  int begin() const { return begin_; }
  int end() const { return end_; }
  // This rank's first particle in the whole scene (its PETSc layout starts there).
  int first_global() const { return exchange_.begin(); }
  MPI_Comm comm() const { return exchange_.comm(); }
  // Which rank owns which particles of the whole scene (split_rows_by_bonds).
  const std::vector<int>& boundaries() const { return exchange_.boundaries(); }
  // The first bond of each rank's rows in the whole families' CSR, and their bond count last.
  const std::vector<int>& bond_boundaries() const { return bond_boundaries_; }
  // The ghosts' rows, in the order of their particles in the whole scene: every family member
  // of an own row that this rank does not own.
  const std::vector<int>& ghosts() const { return ghost_rows_; }
  // Copies each ghost's `width` values (values[width * j .. width * j + width)) from its owner's
  // array into this rank's. Collective: every rank calls it with the same width.
  void fill(double* values, int width) const { exchange_.fill(values, width); }
  // Bytes one fill of `width` doubles receives on this rank.
  std::size_t received_bytes(int width) const {
    return ghost_rows_.size() * width * sizeof(double);
  }
  // The pairs this rank shares with others (SharedBonds below) for the families it was built
  // on, made at the first call and kept, so that the model and the fracture post-step use one
  // star forest. Collective at the first call; throws std::invalid_argument for other families.
  const SharedBonds& shared_bonds(const Families& families) const;

 private:
  struct Rows;
  static Rows own_and_ghost_rows(const Families& families, const std::vector<int>& boundaries,
                                 MPI_Comm comm);
  Halo(MPI_Comm comm, const Families& families, std::vector<int> boundaries, Rows rows);

  int begin_ = 0, end_ = 0;
  std::vector<int> ghost_rows_, bond_boundaries_;
  IndexExchange exchange_;
  const Families* families_ = nullptr;
  mutable std::shared_ptr<const SharedBonds> shared_bonds_;
};

// The pairs a rank shares with other ranks (the bond star forest): the bonds of
// its rows whose other end is owned elsewhere, in CSR order, their rows, and the exchange that
// copies, per bond array in CSR order, each such bond's reverse (families.reverse) from the rank
// that owns it, into that reverse's entry here (in this rank's CSR, Families).
struct SharedBonds {
  std::vector<int> bonds, rows;
  std::unique_ptr<IndexExchange> reverses;
};

}  // namespace fissure
