// Rigid motions, force balance, the energy gradient, and momentum over free steps.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "app/energy.hpp"
#include "integrators/integrator.hpp"
#include "model/model.hpp"
#include "support/gradient_check.hpp"
#include "support/scenes.hpp"
#include "support/two_particles.hpp"

namespace fissure {
namespace {

std::vector<double> perturbed(const Particles& p, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  std::vector<double> y = p.reference;
  for (double& v : y) v += u(rng);
  return y;
}

double max_norm(const std::vector<double>& f) {
  double m = 0;
  for (std::size_t i = 0; i < f.size(); i += 3)
    m = std::max(m, std::hypot(f[i], f[i + 1], f[i + 2]));
  return m;
}

class Conservation : public ::testing::TestWithParam<const char*> {};

// Rigid motions (translation and a finite rotation) change no bond length: zero force and
// energy, to round-off relative to a 0.1% strain state.
TEST_P(Conservation, RigidMotionGivesZeroForceAndEnergy) {
  const Scene scene = test::block_scene(0.1, 0.02, 2e6, 1e6, GetParam());
  auto model = make_model(scene);
  const double a = 0.7, c = std::cos(a), s = std::sin(a);
  const double strained[9] = {1.001, 0, 0, 0, 1, 0, 0, 0, 1};
  const auto y_ref = test::deform(scene.particles, strained);
  std::vector<double> f(y_ref.size());
  model->forces(y_ref.data(), f.data());
  const double force_scale = max_norm(f);
  const double energy_scale = model->elastic_energy(y_ref.data());
  const double rotation[9] = {c, -s, 0, s, c, 0, 0, 0, 1};
  auto y = test::deform(scene.particles, rotation);
  for (std::size_t k = 0; k < y.size(); k += 3) y[k] += 3.0, y[k + 2] -= 1.5;
  model->forces(y.data(), f.data());
  EXPECT_LT(max_norm(f), 1e-9 * force_scale);
  EXPECT_LT(std::abs(model->elastic_energy(y.data())), 1e-12 * energy_scale);
}

// Bond forces are equal and opposite along the bond: Σ F = 0 and Σ y × F = 0.
TEST_P(Conservation, InternalForcesBalance) {
  const Scene scene = test::block_scene(0.1, 0.02, 2e6, 1e6, GetParam());
  auto model = make_model(scene);
  const auto y = perturbed(scene.particles, 2e-4, 1);
  std::vector<double> f(y.size());
  model->forces(y.data(), f.data());
  double sum[3] = {0, 0, 0}, moment[3] = {0, 0, 0}, magnitude = 0, lever = 0;
  for (std::size_t i = 0; i < y.size(); i += 3) {
    for (int k = 0; k < 3; ++k) sum[k] += f[i + k];
    moment[0] += y[i + 1] * f[i + 2] - y[i + 2] * f[i + 1];
    moment[1] += y[i + 2] * f[i] - y[i] * f[i + 2];
    moment[2] += y[i] * f[i + 1] - y[i + 1] * f[i];
    magnitude += std::hypot(f[i], f[i + 1], f[i + 2]);
    lever += std::hypot(f[i], f[i + 1], f[i + 2]) * std::hypot(y[i], y[i + 1], y[i + 2]);
  }
  for (int k = 0; k < 3; ++k) {
    EXPECT_LT(std::abs(sum[k]), 1e-12 * magnitude);
    EXPECT_LT(std::abs(moment[k]), 1e-12 * lever);
  }
}

// A bond of zero deformed length has no direction and carries no force (docs/model.md,
// deviation 6). Two particles, one bond (tests/support/two_particles.hpp), brought onto one
// point: the forces are exactly zero, not NaN, while the bond still stores its energy, for
// `lps` 9κV e²/L² with e = −L (to the single-precision weights, 1e-6).
TEST_P(Conservation, CollapsedBondCarriesNoForce) {
  const test::TwoParticles pair;
  const auto file = std::filesystem::temp_directory_path() / "fissure_test_collapsed_pair.txt";
  std::ofstream(file) << pair.points();
  const std::string yaml = "time: {end: 1.0}\nbodies:\n" + pair.body(file.string());
  const std::string model_key = std::string("material: {model: ") + GetParam() + ", ";
  std::string text = yaml;
  text.replace(text.find("material: {"), 11, model_key);
  const Scene scene = build_scene(parse_config(text, "pair.yaml"));
  auto model = make_model(scene);
  ASSERT_EQ(scene.families.directed_bonds(), 2u);
  const std::vector<double> y(6, 0.0);
  std::vector<double> f(6, 1.0);
  model->forces(y.data(), f.data());
  for (double v : f) EXPECT_EQ(v, 0.0);
  const double energy = model->elastic_energy(y.data());
  std::printf("%s: collapsed pair stores %.6e J\n", GetParam(), energy);
  EXPECT_GT(energy, 0.0);
  if (std::string(GetParam()) == "lps") {
    EXPECT_NEAR(energy, pair.energy(-pair.spacing), 1e-6 * energy);
  }
}

// In a block, particle j moved onto its neighbour i: every force stays finite and the collapsed
// bond adds nothing. Its force would be t n with t finite and n undefined; at distance ±η along a
// direction its two one-sided forces are opposite (n flips, e and θ are even in η), so the
// collapsed value must be their mean, ½(F(+η) + F(−η)), to O(η) of the other bonds' stiffness:
// within 1e-6 of the largest force at η = 1e-9 m (a force along any one direction would miss it
// by the one-sided difference, 4e-3). `lps` only: the `paper` variant's Λ = n·ξ/|ξ| flips with
// n, so its θ is not even in η.
TEST(Conservation, CollapsedBondInABlockAddsNothing) {
  const Scene scene = test::block_scene(0.08, 0.02, 2e6, 1e6);
  auto model = make_model(scene);
  const int i = scene.particles.count() / 2;
  const int j = scene.families.neighbors[scene.families.offsets[i]];
  const double eta = 1e-9, n[3] = {0.6, 0.0, 0.8};
  auto forces_with_j_at = [&](double offset) {
    std::vector<double> y = scene.particles.reference, f(y.size());
    for (int k = 0; k < 3; ++k) y[3 * j + k] = y[3 * i + k] + offset * n[k];
    model->forces(y.data(), f.data());
    return f;
  };
  const auto collapsed = forces_with_j_at(0), up = forces_with_j_at(eta),
             down = forces_with_j_at(-eta);
  double scale = 0, worst = 0;
  for (double v : collapsed) {
    ASSERT_TRUE(std::isfinite(v));
    scale = std::max(scale, std::abs(v));
  }
  for (std::size_t k = 0; k < collapsed.size(); ++k)
    worst = std::max(worst, std::abs(collapsed[k] - 0.5 * (up[k] + down[k])));
  std::printf(
      "collapsed bond vs mean of the one-sided forces: %.2e of the largest force; "
      "one side alone differs by %.2e\n",
      worst / scale, std::abs(up[3 * i] - collapsed[3 * i]) / scale);
  EXPECT_LT(worst, 1e-6 * scale);
}

INSTANTIATE_TEST_SUITE_P(Models, Conservation, ::testing::Values("lps", "paper"));

// The LPS forces are the negative gradient of its energy: central differences agree to the
// O(h²) truncation plus round-off of the energy sum (relative 1e-6 is far above both).
TEST(Conservation, LpsForceIsNegativeEnergyGradient) {
  const Scene scene = test::block_scene(0.08, 0.02, 2e6, 1e6);
  auto model = make_model(scene);
  test::expect_force_is_energy_gradient(*model, perturbed(scene.particles, 2e-4, 2));
}

// 1,000 free steps conserve linear and angular momentum to round-off: both explicit schemes
// update v with pairwise central forces and y with the new v.
TEST(Conservation, MomentumOverThousandFreeSteps) {
  for (const std::string type : {"symplectic_euler", "velocity_verlet"}) {
    const Scene scene = test::block_scene(0.08, 0.02, 2e6, 1e6);
    auto model = make_model(scene);
    Dynamics dynamics(scene, *model);
    auto integrator = make_integrator(type, "test");
    State state{perturbed(scene.particles, 2e-4, 3), perturbed(scene.particles, 0.05, 4), 0.0};
    for (std::size_t k = 0; k < state.velocity.size(); ++k)
      state.velocity[k] -= scene.particles.reference[k];
    auto momenta = [&](double* p, double* l, double& scale) {
      p[0] = p[1] = p[2] = l[0] = l[1] = l[2] = scale = 0;
      for (int i = 0; i < scene.particles.count(); ++i) {
        const double m = scene.particles.mass[i];
        const double* y = &state.position[3 * i];
        const double* v = &state.velocity[3 * i];
        for (int k = 0; k < 3; ++k) p[k] += m * v[k];
        l[0] += m * (y[1] * v[2] - y[2] * v[1]);
        l[1] += m * (y[2] * v[0] - y[0] * v[2]);
        l[2] += m * (y[0] * v[1] - y[1] * v[0]);
        scale += m * std::hypot(v[0], v[1], v[2]) * (1 + std::hypot(y[0], y[1], y[2]));
      }
    };
    double p0[3], l0[3], scale0, p1[3], l1[3], scale1;
    momenta(p0, l0, scale0);
    const double dt = 0.5 * model->stable_time_step();
    for (int s = 0; s < 1000; ++s) integrator->step(dynamics, state, dt);
    momenta(p1, l1, scale1);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(p1[k], p0[k], 1e-11 * scale0) << type;
      EXPECT_NEAR(l1[k], l0[k], 1e-11 * scale0) << type;
    }
  }
}

}  // namespace
}  // namespace fissure
