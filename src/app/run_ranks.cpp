#include "app/run_ranks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <climits>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "core/error.hpp"
#include "integrators/petsc_session.hpp"
#include "parallel/collective.hpp"
#include "parallel/ownership.hpp"

namespace fissure {

namespace {

int from_environment(const char* open_mpi, const char* mpich, int otherwise) {
  for (const char* name : {open_mpi, mpich})
    if (const char* value = std::getenv(name)) return std::max(0, std::atoi(value));
  return otherwise;
}

void check(int code, const char* what) {
  if (code != MPI_SUCCESS) throw RunError(fmt::format("MPI: {} failed", what));
}

// Sends `text` from rank `from` to every rank of comm.
void broadcast(MPI_Comm comm, std::string& text, int from) {
  int length = static_cast<int>(text.size());
  check(MPI_Bcast(&length, 1, MPI_INT, from, comm), "MPI_Bcast");
  text.resize(length);
  check(MPI_Bcast(text.data(), length, MPI_CHAR, from, comm), "MPI_Bcast");
}

}  // namespace

int launched_ranks() {
  return std::max(1, from_environment("OMPI_COMM_WORLD_SIZE", "PMI_SIZE", 1));
}

int launched_rank() { return from_environment("OMPI_COMM_WORLD_RANK", "PMI_RANK", 0); }

namespace {

// comm, or for MPI_COMM_NULL the ranks mpirun started (PETSc initialised when there are
// several), or MPI_COMM_NULL on one rank; its size and this rank.
MPI_Comm run_comm(MPI_Comm comm, int& size, int& rank) {
  size = 1;
  rank = 0;
  if (comm == MPI_COMM_NULL) {
    if (launched_ranks() == 1) return MPI_COMM_NULL;
    ensure_petsc();
    comm = PETSC_COMM_WORLD;
  }
  check(MPI_Comm_size(comm, &size), "MPI_Comm_size");
  check(MPI_Comm_rank(comm, &rank), "MPI_Comm_rank");
  return size == 1 ? MPI_COMM_NULL : comm;
}

}  // namespace

RowSplit RunRanks::split_over(MPI_Comm comm) {
  int size = 1, rank = 0;
  comm = run_comm(comm, size, rank);
  if (comm == MPI_COMM_NULL) return {};
  // each rank counted its share of the particles (RowSplit): every rank gets every count
  auto share_counts = [comm, size](FamilySizes& sizes) {
    const long n = static_cast<long>(sizes.members.size());
    std::vector<int> counts(size), first(size);
    for (int r = 0; r < size; ++r) {
      first[r] = static_cast<int>(n * r / size);
      counts[r] = static_cast<int>(n * (r + 1) / size) - first[r];
    }
    check(MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, sizes.members.data(), counts.data(),
                         first.data(), MPI_INT, comm),
          "MPI_Allgatherv");
    check(MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, sizes.nearest.data(), counts.data(),
                         first.data(), MPI_DOUBLE, comm),
          "MPI_Allgatherv");
  };
  return {[size](const std::vector<int>& offsets) { return split_rows_by_bonds(offsets, size); },
          rank, size, share_counts};
}

RunRanks::RunRanks(const Scene& scene, MPI_Comm comm) : end_(scene.particles.count()) {
  comm = run_comm(comm, size_, rank_);
  if (comm == MPI_COMM_NULL) {
    if (!scene.boundaries.empty())
      throw std::invalid_argument("RunRanks: the scene was split over ranks, but runs on one");
    return;
  }
  comm_ = comm;
  const Families& families = scene.families;
  std::vector<int> boundaries = scene.boundaries;
  if (boundaries.empty())
    boundaries = split_rows_by_bonds(families.offsets, size_);
  else if (static_cast<int>(boundaries.size()) != size_ + 1 || scene.part != rank_)
    throw std::invalid_argument(
        fmt::format("RunRanks: the scene was split for part {} of {}, not for rank {} of {}",
                    scene.part, boundaries.size() - 1, rank_, size_));
  halo_ = std::make_unique<Halo>(comm, families, std::move(boundaries));
  begin_ = halo_->begin();
  end_ = halo_->end();
  first_bond_ = families.offsets[begin_];
  for (int i = begin_; i < end_; ++i) rows_.push_back(i);
}

void RunRanks::sum(std::vector<double>& values) const {
  if (distributed()) sum_over_ranks(comm_, values);
}

double RunRanks::sum(double value) const {
  return distributed() ? sum_over_ranks(comm_, value) : value;
}

double RunRanks::max(double value) const {
  return distributed() ? max_over_ranks(comm_, value) : value;
}

int RunRanks::min(int value) const { return distributed() ? min_over_ranks(comm_, value) : value; }

std::vector<double> RunRanks::gather(const std::vector<double>& values, int width) const {
  if (!distributed()) return values;
  return gather_owned(comm_, halo_->boundaries(), values.data() + std::ptrdiff_t(width) * begin_,
                      width);
}

std::vector<std::uint8_t> RunRanks::gather_bonds(const std::vector<std::uint8_t>& values) const {
  // empty on every rank without fracture
  if (!distributed() || values.empty()) return values;
  return gather_owned(comm_, halo_->bond_boundaries(), values.data() + first_bond_, 1);
}

std::vector<double> RunRanks::gather_bonds(const std::vector<double>& values) const {
  if (!distributed() || values.empty()) return values;
  return gather_owned(comm_, halo_->bond_boundaries(), values.data() + first_bond_, 1);
}

void RunRanks::agree(const std::function<void()>& work) const {
  if (!distributed()) return work();
  fissure::agree(comm_, work);
}

void RunRanks::write(const std::function<void()>& work) const {
  if (!distributed()) return work();
  std::string path, reason;
  bool failed = true;
  try {
    work();
    failed = false;
  } catch (const OutputError& e) {
    path = e.path();
    reason = e.reason();
  } catch (const std::filesystem::filesystem_error& e) {  // removing an earlier run's files
    path = e.path1().string();
    reason = e.code().message();
  } catch (const std::exception& e) {
    reason = e.what();
  }
  const int first = min_over_ranks(comm_, failed ? rank_ : INT_MAX);
  if (first == INT_MAX) return;
  broadcast(comm_, path, first);
  broadcast(comm_, reason, first);
  throw OutputError(path, first == 0 ? reason : fmt::format("{} (on rank {})", reason, first));
}

}  // namespace fissure
