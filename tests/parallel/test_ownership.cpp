// Ownership: contiguous ranges of particle ids balanced by bonds.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "parallel/ownership.hpp"
#include "support/scenes.hpp"

namespace fissure {
namespace {

// Every part's bonds differ from the even share by at most the largest row's bonds (a boundary
// is the row nearest its target), the ranges cover every row once, in order; on a real scene.
TEST(Ownership, RangesCoverEveryRowAndBalanceBonds) {
  const Scene scene = test::block_scene(
      {.size = {0.2, 0.1, 0.05}, .resolution = 0.02, .bulk = 1.0e6, .shear = 1.0e6});
  const auto& offsets = scene.families.offsets;
  const int rows = static_cast<int>(offsets.size()) - 1;
  int widest = 0;
  for (int i = 0; i < rows; ++i) widest = std::max(widest, offsets[i + 1] - offsets[i]);
  for (const int parts : {1, 2, 3, 4, 7, 64}) {
    SCOPED_TRACE(parts);
    const std::vector<int> boundaries = split_rows_by_bonds(offsets, parts);
    ASSERT_EQ(boundaries.size(), std::size_t(parts + 1));
    EXPECT_EQ(boundaries.front(), 0);
    EXPECT_EQ(boundaries.back(), rows);
    EXPECT_TRUE(std::is_sorted(boundaries.begin(), boundaries.end()));
    const double share = double(offsets.back()) / parts;
    for (int p = 0; p < parts; ++p) {
      const int bonds = offsets[boundaries[p + 1]] - offsets[boundaries[p]];
      EXPECT_LE(std::abs(bonds - share), widest) << "part " << p;
      for (int i = boundaries[p]; i < boundaries[p + 1]; ++i) ASSERT_EQ(owner_of(boundaries, i), p);
    }
  }
}

// Rows of very different sizes: a split by rows would give part 0 a single row's worth of bonds
// per row; the split by bonds gives the heavy rows a part of their own.
TEST(Ownership, HeavyRowsGetFewerRows) {
  std::vector<int> offsets{0};
  for (int i = 0; i < 10; ++i) offsets.push_back(offsets.back() + (i < 2 ? 100 : 1));
  const std::vector<int> boundaries = split_rows_by_bonds(offsets, 2);
  EXPECT_EQ(boundaries, (std::vector<int>{0, 1, 10}));
  EXPECT_THROW(split_rows_by_bonds(offsets, 0), std::invalid_argument);
}

}  // namespace
}  // namespace fissure
