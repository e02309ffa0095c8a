#include "parallel/halo.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace fissure {

namespace {

// The family members of rows [begin, end) outside that range, sorted and unique.
std::vector<int> ghosts_of(const Families& families, const std::vector<int>& boundaries,
                           MPI_Comm comm) {
  int rank = 0, size = 0;
  if (MPI_Comm_rank(comm, &rank) != MPI_SUCCESS || MPI_Comm_size(comm, &size) != MPI_SUCCESS)
    throw std::runtime_error("Halo: MPI_Comm_rank or MPI_Comm_size failed");
  const int rows = static_cast<int>(families.offsets.size()) - 1;
  if (static_cast<int>(boundaries.size()) != size + 1 || boundaries.front() != 0 ||
      boundaries.back() != rows || !std::is_sorted(boundaries.begin(), boundaries.end()))
    throw std::invalid_argument(fmt::format(
        "Halo: {} boundaries for {} ranks and {} rows; expected {} ascending from 0 to {}",
        boundaries.size(), size, rows, size + 1, rows));
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

}  // namespace

Halo::Halo(MPI_Comm comm, const Families& families, std::vector<int> boundaries)
    : exchange_(comm, boundaries, ghosts_of(families, boundaries, comm)) {}

}  // namespace fissure
