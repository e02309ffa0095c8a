// Fracture over several ranks: a slab with a pre-crack across the ranks'
// cuts, stretched in steps; at every step each rank's rows lose exactly the bonds one rank's
// do, their damage and their forces are bitwise one rank's, and a pair whose rows live on two
// ranks breaks on both in the same step, also where only the other row's criterion is exceeded
// (α > 0: each row's threshold grows with its own damage). Without the exchange of the other
// row's criterion this fails on 2 ranks (checked by removing it). A step where a rank's own rows
// exceed nothing while another rank's row exceeds a shared pair does not occur here; it does in
// test_distributed_run.cpp, which failed when that rank skipped breaking.
#include <gtest/gtest.h>
#include <petscsys.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "fracture/bond_breaking.hpp"
#include "model/model.hpp"
#include "ranks.hpp"

namespace fissure {
namespace {

Scene cracked_slab() {
  return test::slab(", fracture: {critical_stretch: 0.02, alpha: 2.0}",
                    "initial_cracks:\n"
                    "  - {plane: {point: [0.15, 0, 0], normal: [1, 0, 0], region: {box: {min: "
                    "[-1, -1, -1], max: [1, 0.05, 1]}}}}\n");
}

// Step k: stretched along x by 0.6% per step about the crack, opened at the crack's mouth,
// with a different small displacement on every particle.
std::vector<double> stretched(const Particles& p, int k) {
  std::vector<double> y(p.reference);
  for (int i = 0; i < p.count(); ++i) {
    const double* x = &p.reference[3 * i];
    const double opening = 0.006 * k * (x[0] - 0.15) * (1.5 - 10 * x[1]);
    y[3 * i] += opening;
    for (int c = 0; c < 3; ++c) y[3 * i + c] += 2e-5 * std::sin(7.31 * (3 * i + c) + k);
  }
  return y;
}

TEST(DistributedFracture, EveryStepBreaksTheBondsOfOneRank) {
  const Scene scene = cracked_slab();
  const Families& families = scene.families;
  auto whole_model = make_model(scene);
  auto part_model = make_model(scene);
  BondBreaking whole(scene, *whole_model);
  BondBreaking part(scene, *part_model);
  const Halo halo = test::split_halo(scene);
  part_model->distribute(halo);
  part.distribute(halo);
  const auto owned = [&](int j) { return j >= halo.begin() && j < halo.end(); };
  long shared_broken = 0;
  // Mismatches are counted, not asserted: a rank that left the test early would leave the
  // others waiting in the next collective call.
  for (int k = 1; k <= 8; ++k) {
    SCOPED_TRACE(k);
    const std::vector<double> y = stretched(scene.particles, k);
    const std::size_t whole_pairs = whole.run(y.data());
    const std::vector<double> known = test::known_positions(y, halo);
    // every rank returns the pairs broken on all ranks in this step: one rank's count
    EXPECT_EQ(part.run(known.data()), whole_pairs);
    std::vector<double> expected(y.size()), force(y.size());
    whole_model->forces(y.data(), expected.data());
    part_model->forces(known.data(), force.data());
    int bonds_differing = 0, damage_differing = 0, forces_differing = 0;
    for (int i = halo.begin(); i < halo.end(); ++i) {
      for (int b = families.offsets[i]; b < families.offsets[i + 1]; ++b)
        bonds_differing += part.broken()[b] != whole.broken()[b];
      damage_differing += part.damage()[i] != whole.damage()[i];
      forces_differing += std::memcmp(&force[3 * i], &expected[3 * i], 3 * sizeof(double)) != 0;
    }
    EXPECT_EQ(bonds_differing, 0);
    EXPECT_EQ(damage_differing, 0);
    EXPECT_EQ(forces_differing, 0);
  }
  for (int i = halo.begin(); i < halo.end(); ++i)
    for (int b = families.offsets[i]; b < families.offsets[i + 1]; ++b)
      shared_broken += part.broken()[b] && !owned(families.neighbors[b]);
  // the bonds broken over all ranks, each pair counted on each of its rows' ranks, are one
  // rank's: directed bonds, summed
  long directed = 0;
  for (int i = halo.begin(); i < halo.end(); ++i)
    for (int b = families.offsets[i]; b < families.offsets[i + 1]; ++b)
      directed += part.broken()[b];
  long whole_directed = 0;
  for (const auto flag : whole.broken()) whole_directed += flag;
  EXPECT_EQ(test::sum_over_ranks(directed), whole_directed);
  EXPECT_GT(static_cast<long>(whole.broken_bonds()), 0);
  const long initial = static_cast<long>(BondBreaking(scene, *make_model(scene)).broken_bonds());
  EXPECT_GT(static_cast<long>(whole.broken_bonds()), initial);  // the stretch broke bonds
  if (test::ranks() > 1) {
    EXPECT_GT(test::sum_over_ranks(shared_broken), 0);  // pairs across the cuts broke
  }
}

}  // namespace
}  // namespace fissure
