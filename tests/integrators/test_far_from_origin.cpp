// A scene moved 1 km from the origin changes nothing but round-off: its mesh, and petsc_newton's
// Newton iterations and answer (docs/integrators.md, "Newton's tests"). Positions 1 km away are
// kept to ε·1e3 ≈ 2e-13 m, far below the 1.2e-4 m the glass bar's tip moves here. Before, the
// box was meshed where it lay (857 particles at the origin, 846 at 1 km), and the residual's
// round-off floor, taken from the Gershgorin bound of the whole row, was 65 times the round-off
// the residual shows at 1 km: Newmark stopped after one Newton iteration where it takes two at
// the origin, and the tip was off by 2.3e-4 of its amplitude within 0.05 s.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "integrators/dynamics.hpp"
#include "model/model.hpp"
#include "scene/config.hpp"
#include "scene/scene.hpp"
#include "support/integrator_statistics.hpp"
#include "support/state.hpp"

namespace fissure {
namespace {

// The glass bar of studies/stiff_glass_bar.yaml (Table 1's glass, 1 m × 0.1 m × 0.1 m at λ =
// 0.05 m), its end x < 0.03 m held, sagging under gravity from rest, with its lowest corner at
// (offset, 0, 0).
std::string glass_bar(double offset, const std::string& integrator) {
  return fmt::format(
      "time: {{end: 1.0}}\n"
      "gravity: [0, 0, -9.81]\n"
      "integrator: {1}\n"
      "bodies:\n"
      "  - geometry: {{box: {{min: [{0}, 0, 0], max: [{2}, 0.1, 0.1]}}}}\n"
      "    resolution: 0.05\n"
      "    material: {{density: 2200, bulk_modulus: 3.3e10, shear_modulus: 2.0e10}}\n"
      "constraints:\n"
      "  - {{region: {{box: {{min: [{3}, -1, -1], max: [{4}, 1, 1]}}}}, fix: true}}\n",
      offset, integrator, offset + 1, offset - 1, offset + 0.03);
}

struct BarRun {
  Particles particles;
  std::vector<double> tip;         // the tip's mean vertical displacement after each step
  std::vector<double> iterations;  // Newton iterations of each step
};

BarRun run_bar(double offset, const std::string& integrator, double dt, int steps) {
  const Scene scene = build_scene(parse_config(glass_bar(offset, integrator), "bar.yaml"));
  auto model = make_model(scene);
  Dynamics dynamics(scene, *model);
  auto stepper = make_integrator(scene.config.integrator, "bar.yaml");
  stepper->check(dynamics);
  State state = test::at_rest(scene.particles);
  std::vector<int> tip;
  for (int i = 0; i < scene.particles.count(); ++i)
    if (scene.particles.reference[3 * i] > offset + 0.97) tip.push_back(i);
  BarRun run{scene.particles, {}, {}};
  double done = 0;
  for (int s = 0; s < steps; ++s) {
    stepper->step(dynamics, state, dt);
    double sag = 0;
    for (int i : tip) sag += state.position[3 * i + 2] - scene.particles.reference[3 * i + 2];
    run.tip.push_back(sag / tip.size());
    const double total = test::statistic(*stepper, "newton_iterations");
    run.iterations.push_back(total - done);
    done = total;
  }
  return run;
}

TEST(FarFromOriginMesh, IsTheSameAKilometreAway) {
  const Scene near = build_scene(parse_config(glass_bar(0, "{type: velocity_verlet}"), "a.yaml"));
  const Scene far = build_scene(parse_config(glass_bar(1000, "{type: velocity_verlet}"), "a.yaml"));
  ASSERT_EQ(near.particles.count(), far.particles.count());
  double moved = 0;
  for (std::size_t k = 0; k < near.particles.reference.size(); ++k) {
    const double shift = k % 3 == 0 ? 1000 : 0;
    moved =
        std::max(moved, std::abs(far.particles.reference[k] - shift - near.particles.reference[k]));
  }
  std::printf("%d particles at both places; reference positions differ by %.3g m\n",
              near.particles.count(), moved);
  // a vertex at 1 km is kept to 1.1e-13 m; a tet's centroid sums four
  EXPECT_LT(moved, 1e-12);
}

struct Case {
  const char* name;
  const char* integrator;
  double dt;
  int steps;
};

void PrintTo(const Case& c, std::ostream* out) { *out << c.name; }

class FarFromOrigin : public ::testing::TestWithParam<Case> {};

// Newmark at 1e-4 s (34 times the explicit estimate) for 0.01 s; ESDIRK4 at 6.55e-4 s (225
// times) for 0.02 s, with its error test (newton_test: auto). The same Newton iterations step by
// step, within one where round-off tips a test, and in all within 1%; the same tip to 1e-6 of its
// amplitude. Positions at 1 km carry 2e-13 m, 2e-9 of the amplitude, and each step's solve
// carries that on; the tips differ by 1.6e-9 (Newmark) and 1.2e-8 (ESDIRK4), where a Newton
// iteration fewer per step (the old floor, or the old step test) leaves 4.3e-5.
TEST_P(FarFromOrigin, NewtonTakesTheSameIterationsAndTheSameTip) {
  const Case c = GetParam();
  const BarRun near = run_bar(0, c.integrator, c.dt, c.steps);
  const BarRun far = run_bar(1000, c.integrator, c.dt, c.steps);
  double amplitude = 0, difference = 0, near_total = 0, far_total = 0, worst = 0;
  for (int s = 0; s < c.steps; ++s) {
    amplitude = std::max(amplitude, std::abs(near.tip[s]));
    difference = std::max(difference, std::abs(far.tip[s] - near.tip[s]));
    near_total += near.iterations[s];
    far_total += far.iterations[s];
    worst = std::max(worst, std::abs(far.iterations[s] - near.iterations[s]));
  }
  std::printf(
      "%s: Newton iterations %.0f at the origin, %.0f at 1 km (at most %.0f apart in a step); "
      "tip amplitude %.3g m, differing by %.3g of it\n",
      c.name, near_total, far_total, worst, amplitude, difference / amplitude);
  EXPECT_LE(worst, 1);
  EXPECT_LE(std::abs(far_total - near_total), 0.01 * near_total);
  EXPECT_LT(difference, 1e-6 * amplitude);
}

INSTANTIATE_TEST_SUITE_P(
    Schemes, FarFromOrigin,
    ::testing::Values(Case{"newmark", "{type: petsc_newton, scheme: newmark}", 1e-4, 100},
                      Case{"esdirk4", "{type: petsc_newton, scheme: esdirk4}", 6.55e-4, 30}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace fissure
