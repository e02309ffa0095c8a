// Self-contact's Verlet list against a brute-force search of every pair: the list is a cache, so
// the forces must be those of all unbonded pairs within reach whatever moved or broke since the
// list was built.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "contact/self_contact.hpp"
#include "model/model.hpp"
#include "scene/config.hpp"
#include "support/contact_sizes.hpp"

namespace fissure {
namespace {

using test::ContactSizes;

// Two blocks of separate bodies overlapping by 0.02 m in x (no bonds between them).
const char* kTwoBlocks =
    "time: {end: 1.0}\ncontact: {self: true}\nbodies:\n"
    "  - geometry: {box: {min: [0, 0, 0], max: [0.1, 0.1, 0.1]}}\n    resolution: 0.02\n"
    "    material: {density: 1000, bulk_modulus: 1.0e6, shear_modulus: 1.0e6}\n"
    "  - geometry: {box: {min: [0.08, 0, 0], max: [0.18, 0.1, 0.1]}}\n    resolution: 0.02\n"
    "    material: {density: 1000, bulk_modulus: 2.0e6, shear_modulus: 1.0e6}\n";

// Whether i and j are bonded by an intact bond: a plain scan of i's family row.
bool bonded(const Scene& scene, const Model& model, int i, int j) {
  const Families& fam = scene.families;
  for (int b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b)
    if (fam.neighbors[b] == j) return model.bond_intact(b);
  return false;
}

ContactSizes documented_sizes(const Scene& scene) {
  return test::documented_sizes(scene, {1.0e6, 2.0e6});  // kTwoBlocks' bulk moduli
}

// Every pair, the formula of docs/config.md (contact.self): k (r_i + r_j − d) n, k the mean of
// the two particles' stiffness, pairs bonded by an intact bond left out.
std::vector<double> brute_force(const Scene& scene, const ContactSizes& c, const Model& model,
                                const std::vector<double>& y) {
  const int n = scene.particles.count();
  std::vector<double> f(3 * n, 0.0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      if (j == i) continue;
      double d[3];
      for (int k = 0; k < 3; ++k) d[k] = y[3 * i + k] - y[3 * j + k];
      const double distance = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      const double reach = c.radius[i] + c.radius[j];
      if (distance >= reach || distance == 0 || bonded(scene, model, i, j)) continue;
      const double push = 0.5 * (c.stiffness[i] + c.stiffness[j]) * (reach - distance);
      for (int k = 0; k < 3; ++k) f[3 * i + k] += push * d[k] / distance;
    }
  return f;
}

std::vector<double> contact_forces(SelfContact& contact, const std::vector<double>& y) {
  std::vector<double> f(y.size(), 0.0);
  contact.add_forces(y.data(), f.data());
  return f;
}

// Largest force component of the reference, and the largest difference from it.
struct Difference {
  double largest = 0, difference = 0;
};
Difference compare(const std::vector<double>& f, const std::vector<double>& reference) {
  Difference d;
  for (std::size_t k = 0; k < f.size(); ++k) {
    d.largest = std::max(d.largest, std::abs(reference[k]));
    d.difference = std::max(d.difference, std::abs(f[k] - reference[k]));
  }
  return d;
}

// Adds to every particle a displacement of random direction and length up to `length`.
void move_randomly(std::vector<double>& y, double length, std::mt19937& random) {
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (std::size_t i = 0; 3 * i < y.size(); ++i) {
    double u[3] = {normal(random), normal(random), normal(random)};
    const double norm = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    const double l = length * uniform(random);
    for (int k = 0; k < 3; ++k) y[3 * i + k] += l * u[k] / norm;
  }
}

// The list against every pair, the list built at the first state and rebuilt only when needed:
// pairs near the list's cutoff brought within reach by moves just under skin/2 (on the fine and
// on a coarsened grid), random moves below skin/2, bonds between touching particles broken,
// moves above skin/2 (a block, one particle, two particles), a particle far away (a coarsened
// grid), the whole scene translated (no rebuild). A list built at another state gives the same
// bits, and a non-finite state adds nothing.
TEST(SelfContact, VerletListMatchesEveryPairAsParticlesMoveAndBondsBreak) {
  const Scene scene = build_scene(parse_config(kTwoBlocks, "two_blocks.yaml"));
  auto model = make_model(scene);
  SelfContact contact(scene, *model);
  const int n = scene.particles.count();
  const double skin = contact.skin();
  ASSERT_GT(skin, 0);
  const ContactSizes c = documented_sizes(scene);
  const Families& fam = scene.families;
  const auto reach_of = [&](int i, int j) { return c.radius[i] + c.radius[j]; };
  auto distance_between = [&](const std::vector<double>& x, int i, int j) {
    double d2 = 0;
    for (int k = 0; k < 3; ++k) d2 += std::pow(x[3 * i + k] - x[3 * j + k], 2);
    return std::sqrt(d2);
  };
  auto break_between = [&](int i, int j) {
    for (int b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b)
      if (fam.neighbors[b] == j && model->bond_intact(b)) {
        model->break_bond(i, b);
        model->break_bond(j, fam.reverse[b]);
      }
  };
  std::mt19937 random(17);
  std::vector<double> y = scene.particles.reference;
  move_randomly(y, 0.2 * skin, random);

  auto check = [&](const char* state, std::size_t builds) {
    const auto f = contact_forces(contact, y);
    const auto reference = brute_force(scene, c, *model, y);
    const auto d = compare(f, reference);
    std::printf("%-52s builds %zu, largest force %.4e N, largest difference %.2e N\n", state,
                contact.builds(), d.largest, d.difference);
    EXPECT_GT(d.largest, 0) << state;  // the blocks overlap: there is contact to get right
    EXPECT_LE(d.difference, 1e-12 * d.largest) << state;
    EXPECT_EQ(contact.builds(), builds) << state;
    return f;
  };
  // Pairs between 0.9 and 1 skin beyond their reach, where the list was just built, each
  // particle in one pair at most, the bond between them broken: each particle moves 0.49 skin
  // straight at its partner, which brings some within reach without a rebuild.
  auto near_cutoff = [&](const char* state, std::size_t builds) {
    std::vector<char> used(n, 0);
    std::vector<double> moved = y;
    int pairs = 0, within = 0;
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n && !used[i]; ++j) {
        const double distance = distance_between(y, i, j);
        if (used[j] || distance <= reach_of(i, j) + 0.9 * skin || distance >= reach_of(i, j) + skin)
          continue;
        used[i] = used[j] = 1;
        break_between(i, j);
        for (int k = 0; k < 3; ++k) {
          const double step = 0.49 * skin * (y[3 * j + k] - y[3 * i + k]) / distance;
          moved[3 * i + k] += step;
          moved[3 * j + k] -= step;
        }
        ++pairs;
        within += distance_between(moved, i, j) < reach_of(i, j);
      }
    y = moved;
    std::printf("%d pairs near the cutoff, %d of them brought within reach\n", pairs, within);
    EXPECT_GT(within, 10) << state;
    check(state, builds);
  };
  std::printf("%d particles, skin %.4f m\n", n, skin);
  check("start", 1);
  const std::vector<double> first_build = y;
  near_cutoff("pairs near the cutoff moved 0.49 skin each", 1);

  // Every particle moved by less than skin/2 from where the list was built: no rebuild.
  y = first_build;
  move_randomly(y, 0.49 * skin, random);
  const auto before_breaking = check("moved < skin/2", 1);

  // Bonds between particles within reach of each other break (both rows): those pairs repel
  // now, with the same list.
  int broken = 0;
  for (int i = 0; i < n && broken < 20; i += 7)
    for (int b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b) {
      const int j = fam.neighbors[b];
      if (distance_between(y, i, j) >= reach_of(i, j) || !model->bond_intact(b)) continue;
      break_between(i, j);
      ++broken;
      break;
    }
  ASSERT_GT(broken, 5);
  const auto after_breaking = check("bonds within reach broken", 1);
  EXPECT_GT(compare(after_breaking, before_breaking).difference, 0)
      << "the broken bonds changed no force";

  // The right block moved 2 skins towards the left one, every particle a little more: pairs
  // that were beyond the list's cutoff come within reach.
  for (int i = 0; i < n; ++i)
    if (scene.particles.body[i] == 1) y[3 * i] -= 2 * skin;
  move_randomly(y, 0.2 * skin, random);
  check("right block moved 2 skins", 2);

  // A pair beyond the list's cutoff when it was built (at the previous state), between
  // reach + skin and reach + `beyond` skins apart, the bond between them broken if any, brought
  // straight together by `approach` (i moves by `share` of it, j by the rest). Checks the pair
  // repels afterwards.
  auto bring_together = [&](const char* state, std::size_t builds, double beyond, auto approach,
                            double share) {
    int mover = -1, target = -1;
    for (int i = 0; i < n && target < 0; i += 5)
      for (int j = 0; j < n && target < 0; ++j) {
        const double distance = distance_between(y, i, j);
        if (j != i && distance > reach_of(i, j) + skin &&
            distance < reach_of(i, j) + beyond * skin) {
          mover = i;
          target = j;
        }
      }
    ASSERT_GE(target, 0) << state;
    const double distance = distance_between(y, mover, target);
    double d[3];
    for (int k = 0; k < 3; ++k) d[k] = y[3 * target + k] - y[3 * mover + k];
    break_between(mover, target);
    const double step = approach(distance, reach_of(mover, target));
    ASSERT_LT(distance - step, reach_of(mover, target)) << state;
    for (int k = 0; k < 3; ++k) {
      y[3 * mover + k] += share * step * d[k] / distance;
      y[3 * target + k] -= (1 - share) * step * d[k] / distance;
    }
    const auto f = check(state, builds);
    double pushed = 0;
    for (int k = 0; k < 3; ++k) pushed += f[3 * mover + k] * d[k];
    EXPECT_LT(pushed, 0) << state << ": the pair does not repel";
  };
  // One particle moved onto the other to 0.8 of their reach, more than the skin.
  bring_together(
      "one particle moved > skin onto another", 3, 2.0,
      [](double distance, double reach) { return distance - 0.8 * reach; }, 1.0);
  // Both moved 0.9 skin, each between skin/2 and the skin: a list rebuilt only once a particle
  // moved a whole skin would miss the pair.
  bring_together(
      "two particles moved 0.9 skin towards each other", 4, 1.2,
      [&](double, double) { return 1.8 * skin; }, 0.5);

  // One particle 100 m away: the grid coarsens to keep within its memory budget.
  y[0] += 100;
  const auto far = check("one particle 100 m away", 5);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(far[k], 0.0);
  near_cutoff("on the coarsened grid, pairs near the cutoff moved", 5);

  // Back (a rebuild), then everything translated by 10 skins along each axis: no rebuild, as
  // moving together does not count.
  y[0] -= 100;
  check("back", 6);
  for (std::size_t k = 0; k < y.size(); ++k) y[k] += (k % 3 == 1 ? -10 : 10) * skin;
  const auto kept = check("translated by 17 skins", 6);
  // Results do not depend on when the list was built: a new one, built here and not before the
  // translation, gives the same bits.
  SelfContact fresh(scene, *model);
  EXPECT_EQ(contact_forces(fresh, y), kept);

  // A non-finite state adds nothing.
  y[4] = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> f(y.size(), 1.0);
  contact.add_forces(y.data(), f.data());
  EXPECT_EQ(f, std::vector<double>(y.size(), 1.0));
  EXPECT_EQ(contact.builds(), 6u);
}

}  // namespace
}  // namespace fissure
