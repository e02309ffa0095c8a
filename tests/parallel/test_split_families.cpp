// Families split over ranks (issue 18: memory per rank that scales): each rank keeps its own
// rows and its ghosts' rows of the whole families, numbered in a CSR of its own, with the whole
// families' bond numbering at hand for checkpoints and the bond star forest; and the fragments
// of a run are counted from every rank's rows.
#include <gtest/gtest.h>
#include <petscsys.h>

#include <set>
#include <vector>

#include "fracture/fragments.hpp"
#include "parallel/ownership.hpp"
#include "ranks.hpp"

namespace fissure {
namespace {

// The slab built again, split over the ranks as `fissure run` splits it.
Scene split_slab(const Scene& whole) {
  const int parts = test::ranks();
  return build_scene(whole.config, {[parts](const std::vector<int>& offsets) {
                                      return split_rows_by_bonds(offsets, parts);
                                    },
                                    test::rank()});
}

TEST(SplitFamilies, KeepTheOwnAndGhostRowsOfTheWholeFamilies) {
  const Scene whole = test::slab();
  const Scene split = split_slab(whole);
  const Families& w = whole.families;
  const Families& f = split.families;
  const std::vector<int> boundaries = split_rows_by_bonds(w.offsets, test::ranks());
  ASSERT_EQ(split.boundaries, boundaries);
  ASSERT_FALSE(f.whole());
  EXPECT_EQ(f.global_offsets, w.offsets);
  EXPECT_EQ(f.total_directed_bonds(), w.directed_bonds());
  const int begin = boundaries[test::rank()], end = boundaries[test::rank() + 1];
  EXPECT_EQ(f.first_own_row(), begin);
  EXPECT_EQ(f.end_own_row(), end);
  const Halo halo(PETSC_COMM_WORLD, w, boundaries);
  const std::set<int> ghosts(halo.ghosts().begin(), halo.ghosts().end());
  // counted, not asserted: every rank must reach the collective calls below
  long wrong_rows = 0, wrong_bonds = 0, wrong_reverses = 0;
  for (int i = 0; i < whole.particles.count(); ++i) {
    const bool own = i >= begin && i < end, kept = own || ghosts.count(i);
    const int size = f.offsets[i + 1] - f.offsets[i];
    if (size != (kept ? w.offsets[i + 1] - w.offsets[i] : 0)) {
      ++wrong_rows;
      continue;
    }
    for (int b = f.offsets[i]; b < f.offsets[i + 1]; ++b) {
      const long g = f.global_bond(i, b);
      wrong_bonds +=
          f.neighbors[b] != w.neighbors[g] || f.reference_length[b] != w.reference_length[g];
      // an own row's every reverse is kept here, and is the whole families' reverse
      if (own)
        wrong_reverses +=
            f.reverse[b] < 0 || f.global_bond(f.neighbors[b], f.reverse[b]) != w.reverse[g];
    }
  }
  EXPECT_EQ(wrong_rows, 0);
  EXPECT_EQ(wrong_bonds, 0);
  EXPECT_EQ(wrong_reverses, 0);
  // a checkpoint's per-bond array lands on the same bonds
  std::vector<double> numbered(w.directed_bonds());
  for (std::size_t g = 0; g < numbered.size(); ++g) numbered[g] = double(g);
  const std::vector<double> local = f.localize(numbered);
  ASSERT_EQ(local.size(), f.directed_bonds());
  long misplaced = 0;
  for (int i = 0; i < whole.particles.count(); ++i)
    for (int b = f.offsets[i]; b < f.offsets[i + 1]; ++b)
      misplaced += local[b] != double(f.global_bond(i, b));
  EXPECT_EQ(misplaced, 0);
  // what the split is for: a rank keeps its share of the bonds and its ghosts', not all
  if (test::ranks() > 1) {
    EXPECT_LT(f.directed_bonds(), w.directed_bonds());
    EXPECT_LT(test::sum_over_ranks(long(f.offsets[end] - f.offsets[begin])),
              long(w.directed_bonds()) + 1);
  }
}

// Two cuts across the slab's length break it into three pieces; the count over the ranks,
// each from its own rows' flags, is the whole families' count.
TEST(SplitFamilies, FragmentsCountedOverTheRanksEqualOneRank) {
  const Scene whole = test::slab();
  const Scene split = split_slab(whole);
  const Families& w = whole.families;
  const auto& x = whole.particles.reference;
  std::vector<std::uint8_t> broken(w.directed_bonds(), 0);
  for (int i = 0; i < whole.particles.count(); ++i)
    for (int b = w.offsets[i]; b < w.offsets[i + 1]; ++b) {
      const double a = x[3 * i], c = x[3 * w.neighbors[b]];
      for (const double cut : {0.1, 0.2}) broken[b] |= (a - cut) * (c - cut) < 0;
    }
  const long expected = count_fragments(w, broken);
  ASSERT_EQ(expected, 3);
  const long counted =
      count_fragments(PETSC_COMM_WORLD, split.families, split.families.localize(broken));
  if (test::rank() == 0) {
    EXPECT_EQ(counted, expected);
  } else {
    EXPECT_EQ(counted, 0);
  }
  // nothing broken: one piece
  const long one = count_fragments(PETSC_COMM_WORLD, split.families, {});
  if (test::rank() == 0) {
    EXPECT_EQ(one, 1);
  }
}

}  // namespace
}  // namespace fissure
