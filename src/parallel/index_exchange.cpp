#include "parallel/index_exchange.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "parallel/ownership.hpp"

namespace fissure {

namespace {

void check(PetscErrorCode code, const char* what) {
  if (code != 0) throw std::runtime_error(fmt::format("PETSc: {} failed (error {})", what, code));
}

}  // namespace

int rank_in_split(MPI_Comm comm, const std::vector<int>& boundaries, int total, const char* who) {
  int rank = 0, size = 0;
  if (MPI_Comm_rank(comm, &rank) != MPI_SUCCESS || MPI_Comm_size(comm, &size) != MPI_SUCCESS)
    throw std::runtime_error(fmt::format("{}: MPI_Comm_rank or MPI_Comm_size failed", who));
  if (static_cast<int>(boundaries.size()) != size + 1 || boundaries.front() != 0 ||
      boundaries.back() != total || !std::is_sorted(boundaries.begin(), boundaries.end()))
    throw std::invalid_argument(fmt::format(
        "{}: {} boundaries for {} ranks and {} entries; expected {} ascending from 0 to {}", who,
        boundaries.size(), size, total, size + 1, total));
  return rank;
}

IndexExchange::IndexExchange(MPI_Comm comm, std::vector<int> boundaries, std::vector<int> needed,
                             std::vector<int> slots, long own_first)
    : comm_(comm),
      boundaries_(std::move(boundaries)),
      needed_(std::move(needed)),
      slots_(std::move(slots)),
      own_first_(own_first) {
  PetscBool initialized = PETSC_FALSE;
  check(PetscInitialized(&initialized), "PetscInitialized");
  if (!initialized) throw std::logic_error("IndexExchange: PETSc is not initialised");
  if (boundaries_.empty()) throw std::invalid_argument("IndexExchange: no boundaries");
  rank_ = rank_in_split(comm_, boundaries_, boundaries_.back(), "IndexExchange");
  for (std::size_t k = 0; k < needed_.size(); ++k)
    if (needed_[k] < 0 || needed_[k] >= boundaries_.back() ||
        (needed_[k] >= begin() && needed_[k] < end()) || (k > 0 && needed_[k] <= needed_[k - 1]))
      throw std::invalid_argument(fmt::format(
          "IndexExchange: needed entry {} is outside [0, {}), this rank's own or out of order",
          needed_[k], boundaries_.back()));
  if (!slots_.empty() && slots_.size() != needed_.size())
    throw std::invalid_argument("IndexExchange: one slot per needed entry expected");
  if (own_first_ < 0) own_first_ = begin();
  std::vector<PetscSFNode> remote(needed_.size());
  for (std::size_t k = 0; k < needed_.size(); ++k) {
    const int owner = owner_of(boundaries_, needed_[k]);
    remote[k].rank = owner;
    remote[k].index = needed_[k] - boundaries_[owner];
  }
  check(PetscSFCreate(comm_, &forest_), "PetscSFCreate");
  check(PetscSFSetGraph(forest_, end() - begin(), static_cast<PetscInt>(remote.size()), nullptr,
                        PETSC_COPY_VALUES, remote.data(), PETSC_COPY_VALUES),
        "PetscSFSetGraph");
  check(PetscSFSetUp(forest_), "PetscSFSetUp");
}

// A destructor cannot report a failure: both calls only release what the constructor and fill
// made.
IndexExchange::~IndexExchange() {
  PetscSFDestroy(&forest_);
  for (auto& [bytes, type] : units_) MPI_Type_free(&type);
}

MPI_Datatype IndexExchange::unit(std::size_t entry_bytes) const {
  if (const auto found = units_.find(entry_bytes); found != units_.end()) return found->second;
  MPI_Datatype type = MPI_DATATYPE_NULL;
  if (MPI_Type_contiguous(static_cast<int>(entry_bytes), MPI_BYTE, &type) != MPI_SUCCESS ||
      MPI_Type_commit(&type) != MPI_SUCCESS)
    throw std::runtime_error("IndexExchange: MPI_Type_contiguous or MPI_Type_commit failed");
  units_[entry_bytes] = type;
  return type;
}

void IndexExchange::fill_bytes(void* values, std::size_t entry_bytes) const {
  if (entry_bytes == 0) throw std::invalid_argument("IndexExchange::fill: empty entries");
  const MPI_Datatype type = unit(entry_bytes);
  buffer_.resize(needed_.size() * entry_bytes);
  auto* bytes = static_cast<unsigned char*>(values);
  const unsigned char* roots = bytes + static_cast<std::size_t>(own_first_) * entry_bytes;
  check(PetscSFBcastBegin(forest_, type, roots, buffer_.data(), MPI_REPLACE), "PetscSFBcastBegin");
  check(PetscSFBcastEnd(forest_, type, roots, buffer_.data(), MPI_REPLACE), "PetscSFBcastEnd");
  const std::vector<int>& slots = slots_.empty() ? needed_ : slots_;
  for (std::size_t k = 0; k < needed_.size(); ++k)
    std::memcpy(bytes + static_cast<std::size_t>(slots[k]) * entry_bytes,
                buffer_.data() + k * entry_bytes, entry_bytes);
}

}  // namespace fissure
