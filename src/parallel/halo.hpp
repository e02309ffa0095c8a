#pragma once
// The ghosts of one rank's rows: the family members it does not own, filled from their owners
// through a PetscSF (issue 18, item 1). Per-particle arrays keep the global numbering on every
// rank: a rank reads and writes its own range and the ghosts' entries only.
#include <mpi.h>
#include <petscsf.h>

#include <map>
#include <vector>

#include "scene/particles.hpp"

namespace fissure {

class Halo {
 public:
  // This rank (of comm) owns rows [boundaries[rank], boundaries[rank + 1]) of families; every
  // rank passes the same boundaries (split_rows_by_bonds). PETSc must be initialised. Collective.
  Halo(MPI_Comm comm, const Families& families, std::vector<int> boundaries);
  ~Halo();
  Halo(const Halo&) = delete;
  Halo& operator=(const Halo&) = delete;

  int begin() const { return begin_; }
  int end() const { return end_; }
  int rank() const { return rank_; }
  int ranks() const { return static_cast<int>(boundaries_.size()) - 1; }
  // The ghosts, sorted: every family member of an owned row that this rank does not own.
  const std::vector<int>& ghosts() const { return ghosts_; }
  // Copies each ghost's `width` values (values[width * j .. width * j + width)) from its owner's
  // array into this rank's. Collective: every rank calls it with the same width.
  void fill(double* values, int width) const;
  // Bytes one fill of `width` doubles receives on this rank.
  std::size_t received_bytes(int width) const { return ghosts_.size() * width * sizeof(double); }

 private:
  PetscSF sf_for(int width) const;

  MPI_Comm comm_;
  int rank_ = 0;
  std::vector<int> boundaries_;
  int begin_ = 0, end_ = 0;
  std::vector<int> ghosts_;
  // One star forest per width, each entry of a particle a leaf or root of its own; made on first
  // use, so a fill of a width no one asked for costs nothing.
  mutable std::map<int, PetscSF> forests_;
  mutable std::vector<double> buffer_;
};

}  // namespace fissure
