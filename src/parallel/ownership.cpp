#include "parallel/ownership.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>

namespace fissure {

std::vector<int> split_rows_by_bonds(const std::vector<int>& offsets, int parts) {
  if (parts < 1) throw std::invalid_argument("split_rows_by_bonds: parts must be at least 1");
  if (offsets.empty()) throw std::invalid_argument("split_rows_by_bonds: offsets is empty");
  const int rows = static_cast<int>(offsets.size()) - 1;
  const std::int64_t bonds = offsets.back() - offsets.front();
  std::vector<int> boundaries(parts + 1);
  boundaries[0] = 0;
  boundaries[parts] = rows;
  for (int p = 1; p < parts; ++p) {
    const std::int64_t target = offsets.front() + bonds * p / parts;
    // the first row starting at or past the target, or the one before if that one is nearer
    int row = static_cast<int>(std::lower_bound(offsets.begin(), offsets.end() - 1, target) -
                               offsets.begin());
    if (row > 0 && target - offsets[row - 1] < offsets[row] - target) --row;
    boundaries[p] = std::clamp(row, boundaries[p - 1], rows);
  }
  return boundaries;
}

int owner_of(const std::vector<int>& boundaries, int i) {
  return static_cast<int>(std::upper_bound(boundaries.begin(), boundaries.end(), i) -
                          boundaries.begin()) -
         1;
}

}  // namespace fissure
