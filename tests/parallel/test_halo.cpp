// The halo: each rank's ghosts are exactly the family members of its rows
// that it does not own, and a fill gives each of them its owner's values and touches nothing
// else.
#include <gtest/gtest.h>
#include <petscsys.h>

#include <cmath>
#include <limits>
#include <set>
#include <vector>

#include "parallel/halo.hpp"
#include "parallel/ownership.hpp"
#include "ranks.hpp"

namespace fissure {
namespace {

TEST(Halo, GhostsAreTheFamilyMembersOwnedElsewhere) {
  const Scene scene = test::slab();
  const Families& families = scene.families;
  const Halo halo(PETSC_COMM_WORLD, families, split_rows_by_bonds(families.offsets, test::ranks()));
  std::set<int> expected;
  for (int i = halo.begin(); i < halo.end(); ++i)
    for (int b = families.offsets[i]; b < families.offsets[i + 1]; ++b)
      if (families.neighbors[b] < halo.begin() || families.neighbors[b] >= halo.end())
        expected.insert(families.neighbors[b]);
  EXPECT_EQ(halo.ghosts(), std::vector<int>(expected.begin(), expected.end()));
  if (test::ranks() > 1) {
    EXPECT_FALSE(halo.ghosts().empty());  // a slab cut across has ghosts
  }
}

// Each rank writes a value only its own rows can know (rank and id); after the fill every
// ghost holds its owner's value, every other entry it does not own keeps NaN.
TEST(Halo, FillCopiesTheOwnersValuesIntoTheGhostsOnly) {
  const Scene scene = test::slab();
  const int n = scene.particles.count();
  const std::vector<int> boundaries = split_rows_by_bonds(scene.families.offsets, test::ranks());
  const Halo halo(PETSC_COMM_WORLD, scene.families, boundaries);
  for (const int width : {1, 3, 4}) {
    SCOPED_TRACE(width);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    std::vector<double> values(std::size_t(n) * width, nan);
    const auto value = [&](int i, int k) {
      return 1000.0 * owner_of(boundaries, i) + i + 0.125 * k;
    };
    for (int i = halo.begin(); i < halo.end(); ++i)
      for (int k = 0; k < width; ++k) values[std::size_t(i) * width + k] = value(i, k);
    halo.fill(values.data(), width);
    const std::set<int> ghosts(halo.ghosts().begin(), halo.ghosts().end());
    // counted, not asserted: a rank that left early would leave the others in the next fill
    int wrong = 0;
    for (int i = 0; i < n; ++i) {
      const bool known = ghosts.count(i) || (i >= halo.begin() && i < halo.end());
      for (int k = 0; k < width; ++k) {
        const double v = values[std::size_t(i) * width + k];
        wrong += known ? v != value(i, k) : !std::isnan(v);
      }
    }
    EXPECT_EQ(wrong, 0);
  }
}

TEST(Halo, RefusesBoundariesOfAnotherScene) {
  const Scene scene = test::slab();
  std::vector<int> boundaries = split_rows_by_bonds(scene.families.offsets, test::ranks());
  boundaries.back() += 1;
  EXPECT_THROW(Halo(PETSC_COMM_WORLD, scene.families, boundaries), std::invalid_argument);
}

}  // namespace
}  // namespace fissure
