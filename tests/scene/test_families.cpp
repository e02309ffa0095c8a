// Families: CSR layout, symmetry, the horizon, and tet sampling.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "support/scenes.hpp"

namespace fissure {
namespace {

TEST(Families, SymmetricSortedAndWithinHorizon) {
  const Scene scene = test::block_scene(0.1, 0.02, 1e6, 1e6);
  const Families& f = scene.families;
  const Particles& p = scene.particles;
  const double delta = 1.45 * 0.02;
  ASSERT_EQ(f.offsets.size(), static_cast<std::size_t>(p.count() + 1));
  for (int i = 0; i < p.count(); ++i) {
    for (int b = f.offsets[i]; b < f.offsets[i + 1]; ++b) {
      const int j = f.neighbors[b];
      ASSERT_NE(i, j);
      if (b > f.offsets[i]) {
        ASSERT_LT(f.neighbors[b - 1], j);
      }
      EXPECT_LE(f.reference_length[b], delta);
      const auto begin = f.neighbors.begin() + f.offsets[j];
      const auto end = f.neighbors.begin() + f.offsets[j + 1];
      EXPECT_TRUE(std::binary_search(begin, end, i)) << "bond " << i << "-" << j << " not mutual";
    }
  }
  // Brute force: every pair within δ is in the family.
  long pairs = 0;
  for (int i = 0; i < p.count(); ++i)
    for (int j = 0; j < p.count(); ++j) {
      if (i == j) continue;
      const double d = std::hypot(p.reference[3 * i] - p.reference[3 * j],
                                  p.reference[3 * i + 1] - p.reference[3 * j + 1],
                                  p.reference[3 * i + 2] - p.reference[3 * j + 2]);
      if (d < delta * (1 - 1e-12)) ++pairs;
    }
  EXPECT_EQ(static_cast<std::size_t>(pairs), f.directed_bonds());
}

// One particle per tet, at its barycentre, carrying its volume: the volumes sum to the box's.
TEST(Families, TetSamplingConservesVolumeAndMass) {
  const Scene scene = test::block_scene(0.1, 0.02, 1e6, 1e6);
  double volume = 0, mass = 0;
  for (int i = 0; i < scene.particles.count(); ++i) {
    volume += scene.particles.volume[i];
    mass += scene.particles.mass[i];
  }
  EXPECT_NEAR(volume, 1e-3, 1e-12);
  EXPECT_NEAR(mass, 1.0, 1e-9);
  // An interior family holds the particles of a ball of radius δ: (4/3)πδ³ times the local
  // particle density, measured as the interior particles' count over their volume. Tets are
  // irregular, so single families scatter; the mean over the interior must match within 10%.
  const double delta = 1.45 * 0.02, side = 0.1 - 2 * delta;
  const auto members = test::interior(scene.particles, 0.1, delta);
  double mean = 0;
  for (int i : members) mean += scene.families.offsets[i + 1] - scene.families.offsets[i];
  mean /= members.size();
  const double density = members.size() / std::pow(side, 3);
  const double expected = 4.0 / 3.0 * M_PI * std::pow(delta, 3) * density;
  std::printf("interior family size: %.1f (ball estimate %.1f)\n", mean, expected);
  EXPECT_NEAR(mean / expected, 1.0, 0.10);
}

}  // namespace
}  // namespace fissure
