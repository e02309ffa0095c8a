// External loads and kinematic constraints through the integrators: gravity, fixed and moving
// regions with release, and mass-proportional damping, against the exact discrete solutions.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "integrators/integrator.hpp"
#include "model/model.hpp"
#include "scene/config.hpp"
#include "scene/scene.hpp"

namespace fissure {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// A soft material (κ = μ = 2 kPa, ρ = 1000) so a fixed dt of 1 ms is well under the stable
// estimate and the round-off forces of a rigid motion (strain ~1e-15, a ~ κ ε / (ρ λ) ~ 1e-12
// m/s²) are negligible against g.
const char* kMaterial = "{model: lps, density: 1000, bulk_modulus: 2.0e3, shear_modulus: 2.0e3}";

Scene scene_from(const std::string& yaml) { return build_scene(parse_config(yaml, "loads.yaml")); }

State initial_state(const Scene& scene) {
  return State{scene.particles.reference, scene.particles.velocity, 0.0};
}

// Every particle falls with the exact discrete solution of the scheme for a = g (constant):
//   symplectic Euler  v_{n+1} = v_n + Δt g, y_{n+1} = y_n + Δt v_{n+1}
//     ⇒ v_n = n Δt g and y_N − y_0 = Δt Σ_{n=1..N} n Δt g = g Δt² N(N+1)/2;
//   velocity Verlet   v_{n+½} = v_n + ½Δt g, y_{n+1} = y_n + Δt v_{n+½}, v_{n+1} = v_{n+½} + ½Δt g
//     ⇒ v_n = n Δt g and y_N − y_0 = g Δt² Σ_{n=0..N−1} (n + ½) = g (N Δt)²/2.
// The two differ by g Δt² N/2, a relative 1/(N+1) = 0.5%, so each check tells the schemes apart.
// Tolerance 1e-9 × |displacement|: the sum of N = 200 updates has round-off ~N ε |y| ~ 1e-14 m
// and the internal forces of a rigid translation are round-off (see kMaterial), so 1e-9 is
// far above both yet six orders below the 0.5% a wrong scheme would give.
TEST(Loads, FreeFallMatchesExactDiscreteSolution) {
  const std::string yaml = fmt::format(
      "time: {{end: 1.0}}\ngravity: [0, 0, -9.81]\nbodies:\n"
      "  - geometry: {{box: {{min: [0, 0, 0], max: [0.06, 0.06, 0.06]}}}}\n"
      "    resolution: 0.02\n    material: {}\n",
      kMaterial);
  const Scene scene = scene_from(yaml);
  const int n = scene.particles.count();
  ASSERT_GT(n, 10);
  const double g = 9.81, dt = 1e-3;
  const int steps = 200;
  for (const std::string type : {"symplectic_euler", "velocity_verlet"}) {
    auto model = make_model(scene);
    ASSERT_LT(dt, 0.5 * model->stable_time_step());
    Dynamics dynamics(scene, *model);
    auto integrator = make_integrator(type, "loads.yaml");
    State state = initial_state(scene);
    for (int s = 0; s < steps; ++s) integrator->step(dynamics, state, dt);
    const double N = steps;
    const double expected_dz =
        type == "symplectic_euler" ? -g * dt * dt * N * (N + 1) / 2 : -g * (N * dt) * (N * dt) / 2;
    const double expected_vz = -g * N * dt;
    const double tol = 1e-9 * std::abs(expected_dz);
    for (int i = 0; i < n; ++i) {
      const double* x = &scene.particles.reference[3 * i];
      const double* y = &state.position[3 * i];
      const double* v = &state.velocity[3 * i];
      ASSERT_NEAR(y[0] - x[0], 0.0, tol) << type << " particle " << i;
      ASSERT_NEAR(y[1] - x[1], 0.0, tol) << type << " particle " << i;
      ASSERT_NEAR(y[2] - x[2], expected_dz, tol) << type << " particle " << i;
      ASSERT_NEAR(v[2], expected_vz, 1e-9 * std::abs(expected_vz)) << type << " particle " << i;
    }
  }
}

// A 0.1 × 0.04 × 0.04 bar under gravity: x ≤ 0.021 fixed, x ≥ 0.079 moved at v = (0.02, −0.01,
// 0.05) m/s until t = 0.05 s. Fixed particles: v = 0 is assigned and y += Δt·0 is exact, so
// their positions equal the reference bit for bit. Moving particles: v is assigned (exact) and
// y_n = x + Σ Δt v, which differs from x + v t only by the round-off of n additions (and of
// the accumulated t): ≤ 4 n ε max|y| is a safe bound. After release the first free symplectic
// Euler step must be v + Δt (F(y)/m + g) — recomputed here with the model, equal to round-off
// (1e-12 relative to the velocity change) — and must differ from the prescribed velocity.
TEST(Loads, FixedAndMovingConstraintsThenRelease) {
  const std::string yaml = fmt::format(
      "time: {{end: 1.0}}\ngravity: [0, 0, -9.81]\nbodies:\n"
      "  - geometry: {{box: {{min: [0, 0, 0], max: [0.1, 0.04, 0.04]}}}}\n"
      "    resolution: 0.02\n    material: {}\n"
      "constraints:\n"
      "  - {{region: {{box: {{min: [-1, -1, -1], max: [0.021, 1, 1]}}}}, fix: true}}\n"
      "  - {{region: {{box: {{min: [0.079, -1, -1], max: [1, 1, 1]}}}}, velocity: [0.02, -0.01, "
      "0.05], "
      "release_at: 0.05}}\n",
      kMaterial);
  const Scene scene = scene_from(yaml);
  const Particles& p = scene.particles;
  std::vector<int> fixed, moving, rest;
  for (int i = 0; i < p.count(); ++i) {
    const double x = p.reference[3 * i];
    (x <= 0.021 ? fixed : x >= 0.079 ? moving : rest).push_back(i);
  }
  ASSERT_FALSE(fixed.empty());
  ASSERT_FALSE(moving.empty());
  ASSERT_FALSE(rest.empty());
  const double vm[3] = {0.02, -0.01, 0.05};
  const double release = 0.05, dt = 1e-3;

  for (const std::string type : {"symplectic_euler", "velocity_verlet"}) {
    auto model = make_model(scene);
    ASSERT_LT(dt, 0.5 * model->stable_time_step());
    Dynamics dynamics(scene, *model);
    auto integrator = make_integrator(type, "loads.yaml");
    State state = initial_state(scene);
    dynamics.constrain_velocity(0.0, state.velocity.data());  // as the run loop does
    int step = 0;
    // Held phase: stop with a margin of half a step before the release, so round-off in the
    // accumulated time cannot decide which side of release_at a step starts on.
    while (state.time + dt < release - 0.5 * dt) {
      integrator->step(dynamics, state, dt);
      ++step;
      double scale = 0;
      for (double y : state.position) scale = std::max(scale, std::abs(y));
      const double tol = 4 * step * kEps * scale;
      for (int i : fixed)
        for (int k = 0; k < 3; ++k) {
          ASSERT_EQ(state.position[3 * i + k], p.reference[3 * i + k]) << type << " step " << step;
          ASSERT_EQ(state.velocity[3 * i + k], 0.0) << type << " step " << step;
        }
      for (int i : moving)
        for (int k = 0; k < 3; ++k) {
          ASSERT_EQ(state.velocity[3 * i + k], vm[k]) << type << " step " << step;
          ASSERT_NEAR(state.position[3 * i + k], p.reference[3 * i + k] + vm[k] * state.time, tol)
              << type << " step " << step << " particle " << i;
        }
    }
    // The free particles in between did move (gravity and the pull of the moving end).
    double moved = 0;
    for (int i : rest)
      moved = std::max(moved, std::abs(state.position[3 * i + 2] - p.reference[3 * i + 2]));
    EXPECT_GT(moved, 1e-5) << type;

    // Step until the next step starts after the release (again with a half-step margin).
    while (state.time < release + 0.5 * dt) integrator->step(dynamics, state, dt);
    const std::vector<double> y0 = state.position, v0 = state.velocity;
    std::vector<double> f(y0.size());
    model->forces(y0.data(), f.data());
    integrator->step(dynamics, state, dt);
    double departure = 0;
    for (int i : moving)
      for (int k = 0; k < 3; ++k)
        departure = std::max(departure, std::abs(state.velocity[3 * i + k] - vm[k]));
    // Released: no longer at the prescribed velocity. A whole step of gravity alone is 9.8e-3 m/s.
    EXPECT_GT(departure, 1e-4) << type;
    if (type == "symplectic_euler") {
      for (int i : moving)
        for (int k = 0; k < 3; ++k) {
          const double a = f[3 * i + k] / p.mass[i] + (k == 2 ? -9.81 : 0.0);
          const double expected = v0[3 * i + k] + dt * a;
          EXPECT_NEAR(state.velocity[3 * i + k], expected,
                      1e-12 * (std::abs(v0[3 * i + k]) + dt * std::abs(a)) + 1e-15)
              << "particle " << i << " component " << k;
        }
    }
    // The fixed region never releases.
    for (int i : fixed)
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(state.position[3 * i + k], p.reference[3 * i + k]) << type;
        EXPECT_EQ(state.velocity[3 * i + k], 0.0) << type;
      }
  }
}

// A body translating rigidly at v0 with damping c and no other load: a = −c v, so symplectic
// Euler gives v_{n+1} = (1 − cΔt) v_n, i.e. v_N = v0 (1 − cΔt)^N exactly, and
// y_N − x = Δt Σ_{n=1..N} v_n = Δt v0 r (1 − r^N)/(1 − r), r = 1 − cΔt. The continuous answer
// v0 e^{−cNΔt} differs by a relative N(cΔt)²/2 = 2.5e-3 here, so the check is sharp.
// Tolerance 1e-9 relative: N = 200 multiplications carry ~N ε ~ 4e-14 round-off and the
// internal forces of a rigid translation are round-off (see kMaterial).
TEST(Loads, DampingDecaysVelocityGeometrically) {
  const double c = 5.0, dt = 1e-3;
  const int steps = 200;
  const double v0[3] = {0.7, -0.3, 0.2};
  const std::string yaml = fmt::format(
      "time: {{end: 1.0}}\ndamping: {}\nbodies:\n"
      "  - geometry: {{box: {{min: [0, 0, 0], max: [0.06, 0.06, 0.06]}}}}\n"
      "    resolution: 0.02\n    velocity: [{}, {}, {}]\n    material: {}\n",
      c, v0[0], v0[1], v0[2], kMaterial);
  const Scene scene = scene_from(yaml);
  auto model = make_model(scene);
  ASSERT_LT(dt, 0.5 * model->stable_time_step());
  Dynamics dynamics(scene, *model);
  auto integrator = make_integrator("symplectic_euler", "loads.yaml");
  State state = initial_state(scene);
  for (int k = 0; k < 3; ++k) ASSERT_EQ(state.velocity[k], v0[k]);  // body velocity key
  for (int s = 0; s < steps; ++s) integrator->step(dynamics, state, dt);
  const double r = 1 - c * dt, rN = std::pow(r, steps);
  const double travel = dt * r * (1 - rN) / (1 - r);
  for (int i = 0; i < scene.particles.count(); ++i)
    for (int k = 0; k < 3; ++k) {
      ASSERT_NEAR(state.velocity[3 * i + k], v0[k] * rN, 1e-9 * std::abs(v0[k]))
          << "particle " << i << " component " << k;
      ASSERT_NEAR(state.position[3 * i + k] - scene.particles.reference[3 * i + k], v0[k] * travel,
                  1e-9 * std::abs(v0[k] * travel))
          << "particle " << i << " component " << k;
    }
}

// Overlapping regions: the last active constraint holding a particle decides its velocity. Under
// gravity a fixed region overlapped by a later region moving at 1 m/s upward moves at 1 m/s, the
// constraint work over a step is that of holding it against gravity, m g Δz (the body is rigid,
// so internal forces are round-off), and after the later constraint's release the particles
// are held again by the earlier, still active fixed region: velocity zero, position frozen.
TEST(Loads, OverlappingConstraintsLaterOverridesEarlierUntilReleased) {
  const std::string yaml = fmt::format(
      "time: {{end: 1.0}}\ngravity: [0, 0, -9.81]\nbodies:\n"
      "  - geometry: {{box: {{min: [0, 0, 0], max: [0.06, 0.06, 0.06]}}}}\n"
      "    resolution: 0.02\n    material: {}\n"
      "constraints:\n"
      "  - {{region: {{box: {{min: [-1, -1, -1], max: [1, 1, 1]}}}}, fix: true}}\n"
      "  - {{region: {{box: {{min: [-1, -1, -1], max: [1, 1, 1]}}}}, velocity: [0, 0, 1], "
      "release_at: 0.01}}\n",
      kMaterial);
  const Scene scene = scene_from(yaml);
  auto model = make_model(scene);
  Dynamics dynamics(scene, *model);
  auto integrator = make_integrator("symplectic_euler", "loads.yaml");
  State state = initial_state(scene);
  dynamics.constrain_velocity(0.0, state.velocity.data());
  double mass = 0;
  for (double m : scene.particles.mass) mass += m;
  const double dt = 1e-3;
  for (int s = 0; s < 4; ++s) integrator->step(dynamics, state, dt);
  const std::vector<double> before = state.position;
  integrator->step(dynamics, state, dt);
  for (int i = 0; i < scene.particles.count(); ++i) {
    EXPECT_DOUBLE_EQ(state.velocity[3 * i + 2], 1.0);
    EXPECT_NEAR(state.position[3 * i + 2] - scene.particles.reference[3 * i + 2], 5 * dt, 1e-12);
  }
  // m g Δz: holding the weight m g while moving up by 1 m/s × dt; relative 1e-9 covers the
  // round-off internal forces of a rigid body.
  const double work = dynamics.constraints().work(before.data(), state.position.data());
  EXPECT_NEAR(work, mass * 9.81 * dt, 1e-9 * mass * 9.81 * dt);
  while (state.time < 0.01 - 1e-12) integrator->step(dynamics, state, dt);
  const auto released_at = state.position;
  while (state.time < 0.02) integrator->step(dynamics, state, dt);
  for (int i = 0; i < scene.particles.count(); ++i) {
    EXPECT_EQ(state.velocity[3 * i + 2], 0.0) << "particle " << i;
    EXPECT_EQ(state.position[3 * i + 2], released_at[3 * i + 2]) << "particle " << i;
  }
}

// A region held by a rotating constraint (angular_velocity about z through the block's centre)
// turns rigidly: after a quarter turn every particle sits at its reference position rotated by
// 90° about that axis. Each step moves a held particle by Δt times the prescribed velocity at one
// end of the step, a first-order quadrature of its exact path: after sweeping π/2 the error is
// below ω Δt r_max π/2 ≈ 1.0e-4 m (r_max = 0.042 m); bound 2 ω Δt r_max = 1.3e-4 m, measured
// 3.9e-5 m. A wrong axis, sense or centre would be off by centimetres.
TEST(Loads, RotatingConstraintTurnsTheHeldRegionRigidly) {
  const std::string yaml = fmt::format(
      "time: {{end: 1.0}}\nbodies:\n"
      "  - geometry: {{box: {{min: [0, 0, 0], max: [0.06, 0.06, 0.06]}}}}\n"
      "    resolution: 0.02\n    material: {}\n"
      "constraints:\n  - {{region: {{box: {{min: [-1, -1, -1], max: [1, 1, 1]}}}}, "
      "angular_velocity: [0, 0, {}], center: [0.03, 0.03, 0.03]}}\n",
      kMaterial, M_PI / 2);
  const Scene scene = scene_from(yaml);
  const double omega = M_PI / 2, dt = 1e-3, r_max = std::sqrt(2.0) * 0.03;
  for (const std::string type : {"symplectic_euler", "velocity_verlet"}) {
    auto model = make_model(scene);
    Dynamics dynamics(scene, *model);
    auto integrator = make_integrator(type, "loads.yaml");
    State state = initial_state(scene);
    dynamics.constrain_velocity(0.0, state.velocity.data());
    for (int s = 0; s < 1000; ++s) integrator->step(dynamics, state, dt);
    double worst = 0;
    const auto& x = scene.particles.reference;
    for (int i = 0; i < scene.particles.count(); ++i) {
      // (x, y) − c rotated by 90°: (−(y − c), x − c)
      const double ex = 0.03 - (x[3 * i + 1] - 0.03), ey = 0.03 + (x[3 * i] - 0.03);
      worst = std::max({worst, std::abs(state.position[3 * i] - ex),
                        std::abs(state.position[3 * i + 1] - ey),
                        std::abs(state.position[3 * i + 2] - x[3 * i + 2])});
    }
    std::printf("%s: quarter turn, largest position error %.2e m (bound %.2e m)\n", type.c_str(),
                worst, 2 * omega * dt * r_max);
    EXPECT_LT(worst, 2 * omega * dt * r_max) << type;
  }
}

}  // namespace
}  // namespace fissure
