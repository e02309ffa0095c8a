// What the ranks agree on: an error raised on one rank stops every rank with its message within
// the test's timeout; and the owned pieces gathered on rank 0.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <petscsys.h>

#include <string>
#include <vector>

#include "core/error.hpp"
#include "parallel/collective.hpp"
#include "ranks.hpp"

namespace fissure {
namespace {

// What agree() threw on this rank: its message, and whether it kept the InputError type.
struct Outcome {
  std::string message;
  bool input_error = false;
};

template <class Work>
Outcome outcome(Work&& work) {
  try {
    agree(PETSC_COMM_WORLD, work);
  } catch (const InputError& e) {
    return {e.what(), true};
  } catch (const RunError& e) {
    return {e.what(), false};
  }
  return {};
}

TEST(Collective, AnErrorOnOneRankStopsEveryRankWithItsMessage) {
  const int last = test::ranks() - 1;
  const Outcome o = outcome([&] {
    if (test::rank() == last) throw InputError("scene.yaml", "bodies[0].resolution", "must be > 0");
  });
  if (test::rank() == last) {
    EXPECT_TRUE(o.input_error);  // the rank that raised it keeps its own exception
    EXPECT_EQ(o.message, "scene.yaml: bodies[0].resolution: must be > 0");
  } else {
    EXPECT_EQ(o.message,
              fmt::format("rank {}: scene.yaml: bodies[0].resolution: must be > 0", last));
  }
}

// Every rank but 0 fails (rank 0 alone on one rank): rank 0 hears rank 1, the others keep their
// own.
TEST(Collective, TheLowestFailingRankSpeaksForAll) {
  const Outcome o = outcome([&] {
    if (test::rank() > 0 || test::ranks() == 1)
      throw RunError(fmt::format("rank {} failed", test::rank()));
  });
  EXPECT_EQ(o.message, test::rank() == 0 && test::ranks() > 1
                           ? std::string("rank 1: rank 1 failed")
                           : fmt::format("rank {} failed", test::rank()));
}

TEST(Collective, NothingThrownWhenNoRankFails) {
  EXPECT_EQ(outcome([] {}).message, "");
}

TEST(Collective, GatherOwnedPutsEveryRankPieceInPlaceOnRankZero) {
  std::vector<int> boundaries{0};
  for (int r = 0; r < test::ranks(); ++r) boundaries.push_back(boundaries.back() + 5 + 3 * r);
  const int n = boundaries.back(), width = 3;
  // each rank holds its own piece only
  std::vector<double> own;
  for (int i = boundaries[test::rank()]; i < boundaries[test::rank() + 1]; ++i)
    for (int k = 0; k < width; ++k) own.push_back(10.0 * i + k);
  const std::vector<double> gathered =
      gather_owned(PETSC_COMM_WORLD, boundaries, own.data(), width);
  if (test::rank() != 0) {
    EXPECT_TRUE(gathered.empty());
    return;
  }
  ASSERT_EQ(gathered.size(), std::size_t(n) * width);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < width; ++k) EXPECT_EQ(gathered[std::size_t(i) * width + k], 10.0 * i + k);
}

}  // namespace
}  // namespace fissure
