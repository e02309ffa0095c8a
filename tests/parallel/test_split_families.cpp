// Families split over ranks (so that memory per rank scales): each rank keeps its own
// rows of the whole families and, of its ghosts' rows, their bonds to its own rows, and only
// those particles, numbered on their own in the order of their ids in the whole scene and the whole
// families' bond numbering at hand for checkpoints and the bond star forest; a model on them gets
// the forces, stable step and nearest members one rank gets; and the fragments of a run are counted
// from every rank's rows.
#include <gtest/gtest.h>
#include <petscsys.h>

#include <algorithm>
#include <cstring>
#include <set>
#include <string>
#include <vector>

#include "app/run_ranks.hpp"
#include "fracture/fragments.hpp"
#include "linear/nearest_bonds.hpp"
#include "model/model.hpp"
#include "parallel/ownership.hpp"
#include "ranks.hpp"

namespace fissure {
namespace {

// The slab built again, split over the ranks as `fissure run` splits it (each rank counting
// its share of the families); on one rank too, into one part.
Scene split_slab(const Scene& whole) {
  RowSplit split = RunRanks::split_over(PETSC_COMM_WORLD);
  if (!split.boundaries)
    split = {
        [](const std::vector<int>& offsets) { return split_rows_by_bonds(offsets, 1); }, 0, 1, {}};
  return build_scene(whole.config, split);
}

TEST(SplitFamilies, KeepTheOwnAndGhostRowsOfTheWholeFamilies) {
  const Scene whole = test::slab();
  const Scene split = split_slab(whole);
  const Families& w = whole.families;
  const Families& f = split.families;
  const std::vector<int> boundaries = split_rows_by_bonds(w.offsets, test::ranks());
  ASSERT_EQ(split.boundaries, boundaries);
  ASSERT_FALSE(f.whole());
  EXPECT_EQ(f.total_directed_bonds(), w.directed_bonds());
  EXPECT_EQ(f.total_rows(), whole.particles.count());
  const int begin = boundaries[test::rank()], end = boundaries[test::rank() + 1];
  // the rows: the own particles and the ghosts (the whole families' halo), by id
  const Halo halo(PETSC_COMM_WORLD, w, boundaries);
  std::vector<int> expected_ids(halo.ghosts().begin(), halo.ghosts().end());
  for (int i = begin; i < end; ++i) expected_ids.push_back(i);
  std::sort(expected_ids.begin(), expected_ids.end());
  ASSERT_EQ(f.global_id, expected_ids);
  const int first = f.first_own_row(), own = end - begin;
  EXPECT_EQ(f.global_row(first), begin);
  EXPECT_EQ(f.end_own_row(), first + own);
  ASSERT_EQ(split.particles.count(), f.rows());
  // counted, not asserted: every rank must reach the collective calls below
  long wrong_particles = 0, wrong_rows = 0, wrong_bonds = 0, wrong_reverses = 0, unsorted = 0;
  for (int i = 0; i < f.rows(); ++i) {
    const int g = f.global_row(i);
    for (int k = 0; k < 3; ++k)
      wrong_particles +=
          split.particles.reference[3 * i + k] != whole.particles.reference[3 * g + k] ||
          split.particles.velocity[3 * i + k] != whole.particles.velocity[3 * g + k];
    wrong_particles += split.particles.volume[i] != whole.particles.volume[g] ||
                       split.particles.mass[i] != whole.particles.mass[g] ||
                       split.particles.body[i] != whole.particles.body[g];
    // an own row whole, a ghost's row its members among the own rows
    const bool own_row = i >= first && i < first + own;
    int expected = 0;
    for (int b = w.offsets[g]; b < w.offsets[g + 1]; ++b)
      expected += own_row || (w.neighbors[b] >= begin && w.neighbors[b] < end);
    if (f.offsets[i + 1] - f.offsets[i] != expected || f.global_offsets[i] != w.offsets[g]) {
      ++wrong_rows;
      continue;
    }
    for (int b = f.offsets[i]; b < f.offsets[i + 1]; ++b) {
      const long gb = f.global_bond(i, b);
      unsorted += b > f.offsets[i] && f.neighbors[b] <= f.neighbors[b - 1];
      wrong_bonds += f.global_row(f.neighbors[b]) != w.neighbors[gb] ||
                     f.reference_length[b] != w.reference_length[gb];
      // every reverse is kept here, and is the whole families' reverse
      wrong_reverses +=
          f.reverse[b] < 0 || f.global_bond(f.neighbors[b], f.reverse[b]) != w.reverse[gb];
    }
  }
  EXPECT_EQ(wrong_particles, 0);
  EXPECT_EQ(wrong_rows, 0);
  EXPECT_EQ(wrong_bonds, 0);
  EXPECT_EQ(wrong_reverses, 0);
  EXPECT_EQ(unsorted, 0);
  // a checkpoint's per-bond and per-particle arrays land on the same bonds and particles
  std::vector<double> numbered(w.directed_bonds());
  for (std::size_t g = 0; g < numbered.size(); ++g) numbered[g] = double(g);
  const std::vector<double> local = f.localize(numbered);
  ASSERT_EQ(local.size(), f.directed_bonds());
  long misplaced = 0;
  for (int i = 0; i < f.rows(); ++i)
    for (int b = f.offsets[i]; b < f.offsets[i + 1]; ++b)
      misplaced += local[b] != double(f.global_bond(i, b));
  std::vector<double> ids(2 * std::size_t(whole.particles.count()));
  for (std::size_t k = 0; k < ids.size(); ++k) ids[k] = double(k);
  const std::vector<double> local_ids = f.localize_rows(ids, 2);
  ASSERT_EQ(local_ids.size(), 2 * std::size_t(f.rows()));
  for (int i = 0; i < f.rows(); ++i)
    for (int k = 0; k < 2; ++k)
      misplaced += local_ids[2 * i + k] != double(2 * f.global_row(i) + k);
  EXPECT_EQ(misplaced, 0);
  // what the split is for: the ranks' own rows hold every bond once, and a rank keeps fewer
  // bonds and particles
  EXPECT_EQ(test::sum_over_ranks(long(f.offsets[first + own] - f.offsets[first])),
            long(w.directed_bonds()));
  if (test::ranks() > 1) {
    EXPECT_LT(f.directed_bonds(), w.directed_bonds());
    EXPECT_LT(f.rows(), whole.particles.count());
  }
}

// A model on split families, distributed, against the whole scene's on each rank: the forces
// of every own row bitwise at a perturbed state (so every weight of a pair shared with another
// rank and every ghost's set-up value it reads), the stable step, and the nearest members'
// flags of the own rows' bonds (the ghosts' reach from their ranks).
TEST(SplitFamilies, ModelOnThemEqualsOneRankBitwise) {
  std::vector<test::ModelCase> cases = test::model_cases();
  cases.push_back({"plastic, pre-cracked", ", plasticity: {yield_stress: 2.0e3}", true});
  for (const test::ModelCase& c : cases) {
    SCOPED_TRACE(c.name);
    const Scene whole = test::slab(c.material);
    const Scene split = split_slab(whole);
    const int n = whole.particles.count();
    const std::vector<double> y = test::perturbed(whole.particles);
    auto reference = make_model(whole);
    auto part = make_model(split);
    if (c.cracked) {
      test::break_crack_bonds(whole, *reference, 0, n);
      test::break_crack_bonds(split, *part, 0, split.particles.count());
    }
    std::vector<double> expected(3 * std::size_t(n));
    reference->forces(y.data(), expected.data());
    const Halo halo(PETSC_COMM_WORLD, split.families, split.boundaries);
    part->distribute(halo);
    const std::vector<double> local_y = split.families.localize_rows(y, 3);
    std::vector<double> force(local_y.size(), 0.0);
    part->forces(test::known_positions(local_y, halo).data(), force.data());
    int differing = 0;  // counted, not asserted: every rank must reach the collective calls
    for (int i = halo.begin(); i < halo.end(); ++i)
      differing +=
          std::memcmp(&force[3 * i], &expected[3 * std::size_t(split.families.global_row(i))],
                      3 * sizeof(double)) != 0;
    EXPECT_EQ(differing, 0);
    EXPECT_EQ(part->stable_time_step(), reference->stable_time_step());
    const std::vector<char> kept = nearest_bonds(whole.families, kNearestMembers);
    const std::vector<char> split_kept = nearest_bonds(
        split.families, kNearestMembers, [&halo](double* reach) { halo.fill(reach, 1); });
    long different_flags = 0;
    for (int i = halo.begin(); i < halo.end(); ++i)
      for (int b = split.families.offsets[i]; b < split.families.offsets[i + 1]; ++b)
        different_flags += split_kept[b] != kept[split.families.global_bond(i, b)];
    EXPECT_EQ(different_flags, 0);
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
