// Elastic runs at 100× the explicit stable estimate (the paper's stated limitation, §7): an
// anchored bar released from a stretched and bent state, as the armadillo is in Figure 13.
#include <gtest/gtest.h>

#include <cmath>

#include "app/energy.hpp"
#include "support/vibration.hpp"

namespace fissure {
namespace {

struct Anchored {
  Scene scene;
  std::unique_ptr<Model> model;
  std::unique_ptr<Dynamics> dynamics;
  State initial;
};

// A 0.2 × 0.05 × 0.05 m bar held at x < 0.03, stretched 1% and bent by 2% of its length.
std::unique_ptr<Anchored> anchored_bar() {
  auto a = std::make_unique<Anchored>();
  const std::string yaml =
      "time: {end: 1.0}\nbodies:\n  - geometry: {box: {min: [0, 0, 0], max: [0.2, 0.05, 0.05]}}\n"
      "    resolution: 0.02\n    material: {density: 1000, bulk_modulus: 2.0e6, shear_modulus: "
      "1.0e6}\nconstraints:\n  - {region: {box: {min: [-1, -1, -1], max: [0.03, 1, 1]}}, fix: "
      "true}\n";
  a->scene = build_scene(parse_config(yaml, "anchored.yaml"));
  a->model = make_model(a->scene);
  a->dynamics = std::make_unique<Dynamics>(a->scene, *a->model);
  const Particles& p = a->scene.particles;
  a->initial = {p.reference, std::vector<double>(p.reference.size(), 0.0), 0.0};
  for (int i = 0; i < p.count(); ++i) {
    const double x = p.reference[3 * i];
    a->initial.position[3 * i] += 0.01 * x;
    a->initial.position[3 * i + 2] += 0.02 * x * x / 0.2;
  }
  return a;
}

double energy(Anchored& a, const State& s) {
  return kinetic_energy(a.scene.particles.mass, s.velocity) +
         a.model->elastic_energy(s.position.data());
}

// The static equilibrium with the anchor where the deformed start put it.
std::vector<double> static_shape(Anchored& a) {
  IntegratorSettings settings;
  settings.type = "petsc_newton";
  settings.scheme = "static";
  settings.petsc_options = "-snes_rtol 1e-10";
  auto integrator = make_integrator(settings, "test");
  State s = a.initial;
  integrator->step(*a.dynamics, s, 1.0);
  return s.position;
}

// 200 backward-Euler steps at 100× the estimate: finite throughout, the energy never grows (1e-9
// relative slack for the Newton tolerance) and the bar comes to rest in the static shape (1e-6
// of the largest displacement, the Newton tolerance: backward Euler shrinks every mode by
// 1/√(1 + (ωh)²) each step; measured 1.5e-10).
// Newmark, generalized-α and ARKODE's SDIRK do not yet converge at this step on this case: near
// buckling the compressed bar's tangent is indefinite and the projected one converges too slowly
// (docs/integrators.md, open items).
TEST(LargeStep, BackwardEulerAtHundredTimesTheExplicitLimit) {
  auto a = anchored_bar();
  const double dt = 100 * a->model->stable_time_step();
  IntegratorSettings settings;
  settings.type = "petsc_newton";
  settings.scheme = "backward_euler";
  auto integrator = make_integrator(settings, "test");
  State s = a->initial;
  const double e0 = energy(*a, s);
  double previous = e0, worst_growth = 0;
  for (int step = 0; step < 200; ++step) {
    integrator->step(*a->dynamics, s, dt);
    for (double y : s.position) ASSERT_TRUE(std::isfinite(y)) << "step " << step;
    const double e = energy(*a, s);
    worst_growth = std::max(worst_growth, (e - previous) / e0);
    previous = e;
  }
  const auto rest = static_shape(*a);
  const double distance = test::max_difference(s.position, rest);
  const double reach = test::max_difference(a->initial.position, rest);
  std::printf(
      "backward Euler at dt = %.3g s (100x): max energy growth per step %.2e E0, final E %.2e "
      "E0, distance to static shape %.2e of the largest displacement\n",
      dt, worst_growth, previous / e0, distance / reach);
  for (const auto& [name, value] : integrator->statistics())
    std::printf("  %s %.0f", name.c_str(), value);
  std::printf("\n");
  EXPECT_LT(worst_growth, 1e-9);
  EXPECT_LT(distance, 1e-6 * reach);
}

}  // namespace
}  // namespace fissure
