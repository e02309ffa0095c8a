// The colliders as a potential of the positions (Colliders::potential, docs/integrators.md,
// "Contact"): the penalty ½ k p² and the lagged friction D, their gradient and Hessian blocks,
// checked against central differences on a block pressed into a plane, a sphere and a box, with
// contacts sticking and sliding. Central differences of a C² function at step ε err by O(ε²): at
// ε = 1e-9 m on slips of 3e-7 m and more and depths of 1e-3 m, far below the 1e-6 asked. A
// gradient off by a constant factor, a friction force of the wrong sign or scale, or a Hessian
// block missing a term fails; the sphere's blocks leave out its curvature term −k p (I − n nᵀ)/|d|
// on purpose (positive-semidefinite projection), so there the difference must be negative
// semidefinite. The step bound keeps each particle's centre outside.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "contact/colliders.hpp"
#include "core/error.hpp"
#include "support/potential_evaluation.hpp"
#include "support/scenes.hpp"

namespace fissure {
namespace {

// A 10 cm block on the plane z = 0 (48 particles), with `collider`, friction μ = 0.4 (or none:
// the secant penalty is taken only without friction, Colliders::begin_stage).
Scene scene_with(const std::string& collider, double friction = 0.4) {
  test::Block b{{0.1, 0.1, 0.1}, 0.05, 1e6, 1e6};
  b.scene =
      "contact: {friction: " + std::to_string(friction) + "}\ncolliders:\n  - " + collider + "\n";
  return test::block_scene(b);
}

// The contact's start y: the block lowered by 2 mm into the collider's top at z = 0; the
// end z: y moved by a slip along x of 3e-7 m (sticking: below ε_v s = 1e-6 m at s = 1e-3 s) on
// even particles and 1e-4 m (sliding) on odd ones, and a random normal motion of ±0.5 mm.
struct Points {
  std::vector<double> start, end;
};
Points pressed(const Scene& scene) {
  Points p{scene.particles.reference, {}};
  for (std::size_t i = 0; i < p.start.size() / 3; ++i) p.start[3 * i + 2] -= 2e-3;
  p.end = p.start;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> normal(-5e-4, 5e-4);
  for (std::size_t i = 0; i < p.end.size() / 3; ++i) {
    p.end[3 * i] += i % 2 == 0 ? 3e-7 : 1e-4;
    p.end[3 * i + 2] += normal(random);
  }
  return p;
}

// For the secant penalty (contact/secant_penalty.hpp), start and end depths in each of its
// branches, taken in turn by the bottom layer's particles: pressed 2 mm in at the start and
// moving ±0.5 mm, entering from a 1 mm gap to 0.5 mm deep, leaving from 0.2 mm deep to a 0.3 mm
// gap.
Points crossing(const Scene& scene) {
  Points p = pressed(scene);
  const double start[3] = {-2e-3, 1e-3, -2e-4}, end[3] = {0, -1.5e-3, 5e-4};
  int bottom = 0;
  for (std::size_t i = 0; i < p.start.size() / 3; ++i) {
    const double z = scene.particles.reference[3 * i + 2];
    const int branch = z < 0.025 ? bottom++ % 3 : 0;
    const double shift = z + start[branch] - p.start[3 * i + 2];  // from pressed()'s start
    p.start[3 * i + 2] += shift;
    p.end[3 * i + 2] += shift + end[branch];
  }
  return p;
}

using test::evaluate;
using test::Evaluation;

// Checks the gradient and Hessian blocks at the pressed end point against central differences
// along each particle's axes; `exact` whether the blocks are the whole Hessian; `secant` the
// penalty's secant from the start (with crossing() points). Returns the number of particles in
// contact.
int check_against_differences(const std::string& collider, bool exact, bool secant = false) {
  const Scene scene = scene_with(collider, secant ? 0.0 : 0.4);
  Colliders colliders(scene);
  const Points p = secant ? crossing(scene) : pressed(scene);
  colliders.begin_stage(p.start.data(), p.start.data(), 1e-3, 1e-3, secant);
  const Evaluation at = evaluate(colliders, p.end);
  const double eps = 1e-9;
  int touching = 0;
  for (std::size_t i = 0; i < p.end.size() / 3; ++i) {
    const double* block = &at.blocks[9 * i];
    if (block[8] == 0) continue;
    ++touching;
    double hessian[3][3];
    const double gradient_scale =
        std::max({std::abs(at.gradient[3 * i]), std::abs(at.gradient[3 * i + 1]),
                  std::abs(at.gradient[3 * i + 2])});
    for (int b = 0; b < 3; ++b) {
      std::vector<double> plus = p.end, minus = p.end;
      plus[3 * i + b] += eps;
      minus[3 * i + b] -= eps;
      const Evaluation up = evaluate(colliders, plus), down = evaluate(colliders, minus);
      const double slope = (up.energy - down.energy) / (2 * eps);
      const double g = at.gradient[3 * i + b];
      EXPECT_NEAR(g, slope, 1e-6 * gradient_scale)
          << collider << ", particle " << i << ", axis " << b;
      for (int a = 0; a < 3; ++a)
        hessian[a][b] = (up.gradient[3 * i + a] - down.gradient[3 * i + a]) / (2 * eps);
    }
    double scale = 0;
    for (const auto& row : hessian)
      for (double v : row) scale = std::max(scale, std::abs(v));
    if (exact) {
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          EXPECT_NEAR(block[3 * a + b], hessian[a][b], 1e-6 * scale)
              << collider << ", particle " << i << ", entry " << a << b;
      continue;
    }
    // the left-out part H − B is negative semidefinite: no positive diagonal entry, and its
    // leading 2×2 minor not negative
    double difference[3][3];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) difference[a][b] = hessian[a][b] - block[3 * a + b];
    for (int a = 0; a < 3; ++a) EXPECT_LE(difference[a][a], 1e-6 * scale) << collider << " " << i;
    EXPECT_GE(difference[0][0] * difference[1][1] - difference[0][1] * difference[1][0],
              -1e-6 * scale * scale)
        << collider << " " << i;
  }
  return touching;
}

TEST(ColliderPotential, PlaneGradientAndHessianMatchDifferences) {
  EXPECT_GE(check_against_differences("{plane: {point: [0, 0, 0], normal: [0, 0, 1]}}", true), 8);
}

TEST(ColliderPotential, BoxGradientAndHessianMatchDifferences) {
  EXPECT_GE(check_against_differences("{box: {min: [-1, -1, -1], max: [1, 1, 0]}}", true), 8);
}

TEST(ColliderPotential, SphereGradientMatchesAndHessianIsItsProjection) {
  EXPECT_GE(check_against_differences("{sphere: {center: [0.05, 0.05, -1], radius: 1}}", false), 4);
}

TEST(ColliderPotential, SecantPenaltyGradientAndHessianMatchDifferences) {
  EXPECT_GE(check_against_differences("{plane: {point: [0, 0, 0], normal: [0, 0, 1]}}", true, true),
            8);
  EXPECT_GE(check_against_differences("{box: {min: [-1, -1, -1], max: [1, 1, 0]}}", true, true), 8);
  EXPECT_GE(
      check_against_differences("{sphere: {center: [0.05, 0.05, -1], radius: 1}}", false, true), 4);
}

// At rest in contact the penalty holds nothing and friction is zero: the start as sampled (the
// bottom particles within their radius of the plane) stores no energy.
TEST(ColliderPotential, BodyTouchingAsSampledStartsWithoutEnergy) {
  const Scene scene = scene_with("{plane: {point: [0, 0, 0], normal: [0, 0, 1]}}");
  Colliders colliders(scene);
  const std::vector<double>& x = scene.particles.reference;
  EXPECT_EQ(colliders.energy(x.data()), 0.0);
  colliders.begin_stage(x.data(), x.data(), 1e-3, 1e-3);
  std::vector<double> gradient(x.size(), 0.0);
  EXPECT_EQ(colliders.potential(x.data(), gradient.data(), nullptr), 0.0);
  for (double g : gradient) EXPECT_EQ(g, 0.0);
  // 0.1 mm further in, the bottom particles press: ½ k p² each
  std::vector<double> lower = x;
  for (std::size_t i = 0; i < lower.size() / 3; ++i) lower[3 * i + 2] -= 1e-4;
  EXPECT_GT(colliders.energy(lower.data()), 0.0);
}

// The step bound: an update that would drive the bottom particles 5 cm down (through the plane)
// is cut where the deepest one's centre reaches the plane, and a particle already deeper than its
// reach may move but not deeper.
TEST(ColliderPotential, StepBoundKeepsCentresOutside) {
  const Scene scene = scene_with("{plane: {point: [0, 0, 0], normal: [0, 0, 1]}}");
  Colliders colliders(scene);
  const std::vector<double>& x = scene.particles.reference;
  colliders.begin_stage(x.data(), x.data(), 1e-3, 1e-3);
  std::vector<double> down(x.size(), 0.0);
  double lowest = 1;
  for (std::size_t i = 0; i < x.size() / 3; ++i) {
    down[3 * i + 2] = -0.05;
    lowest = std::min(lowest, x[3 * i + 2]);
  }
  const double alpha = colliders.max_step(x.data(), down.data());
  EXPECT_NEAR(alpha, lowest / 0.05, 1e-9);
  std::vector<double> up(x.size(), 0.0);
  for (std::size_t i = 0; i < x.size() / 3; ++i) up[3 * i + 2] = 0.05;
  EXPECT_EQ(colliders.max_step(x.data(), up.data()), 1.0);
}

// A body whose particles' centres start inside a collider is refused, naming the collider, the
// body and the overlap.
TEST(ColliderPotential, BodyStartingInsideIsRefused) {
  try {
    const Scene scene = scene_with("{plane: {point: [0, 0, 0.03], normal: [0, 0, 1]}}");
    Colliders colliders(scene);
    FAIL() << "a body with particles below the plane was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "colliders[0]");
    EXPECT_NE(std::string(e.what()).find("starts inside this plane"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace fissure
