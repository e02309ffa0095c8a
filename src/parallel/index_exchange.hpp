#pragma once
// Copies entries of an array split over ranks into the ranks that need them: the index space
// [0, boundaries.back()) is owned in contiguous ranges (rank p owns [boundaries[p],
// boundaries[p + 1])), and each rank names the entries it needs from others. A rank keeps the
// array in the global numbering or in one of its own (`slots`); a fill writes only the needed
// entries. One PETSc
// star forest for all entry sizes, each size an MPI datatype of its own (used for particles'
// ghosts and bonds' reverses).
#include <mpi.h>
#include <petscsf.h>

#include <cstddef>
#include <map>
#include <vector>

namespace fissure {

// This rank in comm, after checking that `boundaries` splits [0, total) over comm's ranks (one
// more entry than ranks, ascending from 0 to total); throws std::invalid_argument naming `who`.
int rank_in_split(MPI_Comm comm, const std::vector<int>& boundaries, int total, const char* who);

class IndexExchange {
 public:
  // `boundaries`: as rank_in_split over [0, boundaries.back()); `needed`: sorted, unique, none in
  // this rank's own range. PETSc must be initialised. Collective over comm.
  // Where this rank keeps the array in a numbering of its own (a rank's bonds, Families): its
  // own entries start at `own_first`, and needed[k] is written to entry slots[k]. By default
  // both are the global numbering's.
  IndexExchange(MPI_Comm comm, std::vector<int> boundaries, std::vector<int> needed,
                std::vector<int> slots = {}, long own_first = -1);
  ~IndexExchange();
  IndexExchange(const IndexExchange&) = delete;
  IndexExchange& operator=(const IndexExchange&) = delete;

  int begin() const { return boundaries_[rank_]; }
  int end() const { return boundaries_[rank_ + 1]; }
  MPI_Comm comm() const { return comm_; }
  const std::vector<int>& boundaries() const { return boundaries_; }
  // values[k * width .. k * width + width) of every needed k from its owner. Collective: every
  // rank calls it with the same T and width.
  template <class T>
  void fill(T* values, int width) const {
    fill_bytes(values, sizeof(T) * static_cast<std::size_t>(width));
  }

 private:
  void fill_bytes(void* values, std::size_t entry_bytes) const;
  MPI_Datatype unit(std::size_t entry_bytes) const;

  MPI_Comm comm_;
  int rank_ = 0;
  std::vector<int> boundaries_;
  std::vector<int> needed_;
  std::vector<int> slots_;  // where each needed entry is written; empty: at needed_
  long own_first_ = 0;      // where this rank's own entries start
  // Roots: this rank's own entries; leaves: the needed ones, in a contiguous buffer.
  PetscSF forest_ = nullptr;
  // An entry of each size filled so far, as MPI_BYTE × size.
  mutable std::map<std::size_t, MPI_Datatype> units_;
  mutable std::vector<unsigned char> buffer_;
};

}  // namespace fissure
