// Rigid motions, force balance, the energy gradient, and momentum over free steps.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "app/energy.hpp"
#include "integrators/integrator.hpp"
#include "model/model.hpp"
#include "support/gradient_check.hpp"
#include "support/scenes.hpp"

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
