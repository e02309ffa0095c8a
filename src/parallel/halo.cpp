#include "parallel/halo.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "parallel/ownership.hpp"

namespace fissure {

namespace {

static_assert(std::is_same_v<PetscReal, double>, "the halo sends doubles as MPIU_REAL");

void check(PetscErrorCode code, const char* what) {
  if (code != 0) throw std::runtime_error(fmt::format("PETSc: {} failed (error {})", what, code));
}

}  // namespace

Halo::Halo(MPI_Comm comm, const Families& families, std::vector<int> boundaries)
    : comm_(comm), boundaries_(std::move(boundaries)) {
  PetscBool initialized = PETSC_FALSE;
  check(PetscInitialized(&initialized), "PetscInitialized");
  if (!initialized) throw std::logic_error("Halo: PETSc is not initialised");
  int size = 0;
  if (MPI_Comm_rank(comm_, &rank_) != MPI_SUCCESS || MPI_Comm_size(comm_, &size) != MPI_SUCCESS)
    throw std::runtime_error("Halo: MPI_Comm_rank or MPI_Comm_size failed");
  const int rows = static_cast<int>(families.offsets.size()) - 1;
  if (static_cast<int>(boundaries_.size()) != size + 1 || boundaries_.front() != 0 ||
      boundaries_.back() != rows || !std::is_sorted(boundaries_.begin(), boundaries_.end()))
    throw std::invalid_argument(fmt::format(
        "Halo: {} boundaries for {} ranks and {} rows; expected {} ascending from 0 to {}",
        boundaries_.size(), size, rows, size + 1, rows));
  begin_ = boundaries_[rank_];
  end_ = boundaries_[rank_ + 1];
  for (int i = begin_; i < end_; ++i)
    for (int b = families.offsets[i]; b < families.offsets[i + 1]; ++b) {
      const int j = families.neighbors[b];
      if (j < begin_ || j >= end_) ghosts_.push_back(j);
    }
  std::sort(ghosts_.begin(), ghosts_.end());
  ghosts_.erase(std::unique(ghosts_.begin(), ghosts_.end()), ghosts_.end());
}

Halo::~Halo() {
  for (auto& [width, sf] : forests_) PetscSFDestroy(&sf);
}

// Roots: this rank's owned entries, width per particle, in order; leaves: the ghosts' entries in a
// contiguous buffer, each pointing at its owner's root.
PetscSF Halo::sf_for(int width) const {
  if (const auto found = forests_.find(width); found != forests_.end()) return found->second;
  std::vector<PetscSFNode> remote(ghosts_.size() * width);
  for (std::size_t g = 0; g < ghosts_.size(); ++g) {
    const int owner = owner_of(boundaries_, ghosts_[g]);
    for (int k = 0; k < width; ++k) {
      remote[g * width + k].rank = owner;
      remote[g * width + k].index = (ghosts_[g] - boundaries_[owner]) * width + k;
    }
  }
  if (static_cast<long long>(boundaries_.back()) * width > std::numeric_limits<PetscInt>::max())
    throw std::runtime_error(
        fmt::format("Halo: {} particles × {} values exceed PETSc's {}-bit indices",
                    boundaries_.back(), width, 8 * sizeof(PetscInt)));
  PetscSF sf = nullptr;
  check(PetscSFCreate(comm_, &sf), "PetscSFCreate");
  forests_[width] = sf;
  check(PetscSFSetGraph(sf, static_cast<PetscInt>((end_ - begin_) * width),
                        static_cast<PetscInt>(remote.size()), nullptr, PETSC_COPY_VALUES,
                        remote.data(), PETSC_COPY_VALUES),
        "PetscSFSetGraph");
  check(PetscSFSetUp(sf), "PetscSFSetUp");
  return sf;
}

void Halo::fill(double* values, int width) const {
  if (width < 1) throw std::invalid_argument("Halo::fill: width must be at least 1");
  const PetscSF sf = sf_for(width);
  buffer_.resize(ghosts_.size() * width);
  const double* roots = values + static_cast<std::size_t>(begin_) * width;
  check(PetscSFBcastBegin(sf, MPIU_REAL, roots, buffer_.data(), MPI_REPLACE), "PetscSFBcastBegin");
  check(PetscSFBcastEnd(sf, MPIU_REAL, roots, buffer_.data(), MPI_REPLACE), "PetscSFBcastEnd");
  for (std::size_t g = 0; g < ghosts_.size(); ++g)
    std::copy_n(buffer_.data() + g * width, width,
                values + static_cast<std::size_t>(ghosts_[g]) * width);
}

}  // namespace fissure
