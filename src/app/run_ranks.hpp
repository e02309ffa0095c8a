#pragma once
// The ranks one run is spread over (docs/mpi.md): which rows this rank owns, the halo
// of their ghosts, and the reductions the run loop and its observers make over the ranks. On one
// rank every reduction is the value itself and no MPI call is made.
#include <mpi.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "parallel/halo.hpp"
#include "scene/scene.hpp"

namespace fissure {

// The ranks mpirun started this process among (Open MPI's OMPI_COMM_WORLD_SIZE, MPICH's
// PMI_SIZE), 1 without mpirun; and this process's rank among them. Read without MPI.
int launched_ranks();
int launched_rank();

class RunRanks {
 public:
  // Over `comm`, or MPI_COMM_NULL for the ranks mpirun started (PETSC_COMM_WORLD, PETSc
  // initialised here when there are several). Several ranks split the scene's rows by bonds
  // (as the scene was split, when build_scene was given split_over()) and build the halo.
  // Collective.
  RunRanks(const Scene& scene, MPI_Comm comm);
  // The split build_scene makes over the ranks of `comm` (as above), so that each rank keeps
  // only its rows' families and its ghosts'; one rank: none.
  static RowSplit split_over(MPI_Comm comm);

  bool distributed() const { return halo_ != nullptr; }
  int rank() const { return rank_; }
  int size() const { return size_; }
  // The rank that writes the run's shared files (summary.json, probes.csv, the PVD, the
  // checkpoint): rank 0.
  bool root() const { return rank_ == 0; }
  // The ranks' communicator, when distributed().
  MPI_Comm comm() const { return comm_; }
  // This rank's own rows, in the scene's numbering (over several ranks its own, Families).
  int begin() const { return begin_; }
  int end() const { return end_; }
  // begin() to end(), listed (Model::rows_energy); empty on one rank.
  const std::vector<int>& rows() const { return rows_; }
  // The halo, when distributed().
  const Halo& halo() const { return *halo_; }
  // Over the ranks; collective. Sums in rank order (sum_over_ranks).
  void sum(std::vector<double>& values) const;
  double sum(double value) const;
  double max(double value) const;
  int min(int value) const;
  // The owned rows of a per-particle array of `width` values per particle, whole on the root
  // (in place on one rank: the array itself); empty elsewhere. Collective.
  std::vector<double> gather(const std::vector<double>& values, int width) const;
  // A per-bond array (CSR order), whole on the root; empty stays empty. Collective.
  std::vector<std::uint8_t> gather_bonds(const std::vector<std::uint8_t>& values) const;
  std::vector<double> gather_bonds(const std::vector<double>& values) const;
  // Rank-local work that makes no collective call: an exception it raises on any rank is
  // raised on every rank (parallel/collective.hpp, agree()). Collective.
  void agree(const std::function<void()>& work) const;
  // Rank-local file work: an OutputError it raises on any rank is raised on every rank (the
  // same path and reason), so that every rank stops the run the same way. Collective.
  void write(const std::function<void()>& work) const;

 private:
  MPI_Comm comm_ = MPI_COMM_NULL;
  int rank_ = 0, size_ = 1, begin_ = 0, end_ = 0;
  std::vector<int> rows_;
  int first_bond_ = 0;  // this rank's first bond in its families' CSR
  std::unique_ptr<Halo> halo_;
};

}  // namespace fissure
