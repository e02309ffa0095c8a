// The recipe for adding an integrator (docs/architecture.md), shown by a test-only one: forward
// Euler in `integrator.substeps` parts of each step, registered from this file alone with its
// option, named by a scene and run. Under gravity from rest it must reach forward Euler's
// y = y0 + h²g m(m−1)/2 after m parts of h = dt/substeps (symplectic Euler, the default, gives
// m(m+1)/2), so a run that used another integrator or lost the option fails.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>

#include "app/run_fissure.hpp"
#include "app/simulation.hpp"
#include "integrators/registry.hpp"
#include "model/model.hpp"
#include "scene/scene.hpp"
#include "support/error_message.hpp"

namespace fissure {
namespace {

struct SubstepOptions final : IntegratorOptions {
  int substeps = 1;
};

// y += h v, v += h a(y, v), both from the start of each of `substeps` parts of a step.
class ForwardEuler final : public Integrator {
 public:
  explicit ForwardEuler(int substeps) : substeps_(substeps) {}
  double step(Dynamics& dynamics, State& state, double dt) override {
    const double h = dt / substeps_, start = state.time;
    acceleration_.resize(state.position.size());
    for (int k = 0; k < substeps_; ++k) {
      const double t = start + k * h;
      dynamics.acceleration(t, state.position.data(), state.velocity.data(), acceleration_.data());
      for (std::size_t u = 0; u < acceleration_.size(); ++u) {
        state.position[u] += h * state.velocity[u];
        state.velocity[u] += h * acceleration_[u];
      }
      dynamics.constrain_velocity(t + h, state.velocity.data());
      ++taken_;
    }
    state.time = start + dt;
    return dt;
  }
  bool explicit_step() const override { return true; }
  Statistics statistics() const override { return {{"substeps", double(taken_)}}; }

 private:
  int substeps_;
  long taken_ = 0;
  std::vector<double> acceleration_;
};

// The whole recipe: a name, its keys, their parser and the constructor, in one call.
[[maybe_unused]] const bool registered = [] {
  register_integrator({"test_forward_euler",
                       {"substeps"},
                       [](const OptionReader& r) {
                         auto options = std::make_shared<SubstepOptions>();
                         options->substeps = r.whole("substeps", options->substeps, 1, 1000);
                         return options;
                       },
                       [](const IntegratorSettings& settings, const std::string&) {
                         return std::make_unique<ForwardEuler>(
                             options_of<SubstepOptions>(settings).substeps);
                       }});
  return true;
}();

constexpr double kDt = 1e-4, kGravity = -10;
constexpr int kSteps = 5;

std::string scene_yaml(const std::string& integrator, const std::string& out = "unused") {
  return fmt::format(
      "time: {{end: {}, dt: {}}}\n"
      "integrator: {}\n"
      "gravity: [0, 0, {}]\n"
      "bodies:\n"
      "  - geometry: {{box: {{min: [0, 0, 0], max: [0.1, 0.1, 0.1]}}}}\n"
      "    resolution: 0.05\n"
      "    material: {{density: 1000, bulk_modulus: 1.0e4, shear_modulus: 1.0e4}}\n"
      "output: {{dir: {}}}\n",
      kSteps * kDt, kDt, integrator, kGravity, out);
}

// The largest |z − z0 − expected| over the particles after kSteps steps of the scene's
// integrator, relative to |expected|.
double fall_error(const std::string& integrator, double expected) {
  const Config config = parse_config(scene_yaml(integrator), "scene.yaml");
  auto stepper = make_integrator(config.integrator, config.file);
  const Scene scene = build_scene(config);
  auto model = make_model(scene);
  Dynamics dynamics(scene, *model);
  State s{scene.particles.reference, scene.particles.velocity, 0};
  for (int k = 0; k < kSteps; ++k) stepper->step(dynamics, s, kDt);
  double worst = 0;
  for (int i = 0; i < scene.particles.count(); ++i) {
    const double fall = s.position[3 * i + 2] - scene.particles.reference[3 * i + 2];
    worst = std::max(worst, std::abs(fall - expected) / std::abs(expected));
  }
  return worst;
}

double forward_euler_fall(int substeps) {
  const double h = kDt / substeps, m = kSteps * substeps;
  return kGravity * h * h * m * (m - 1) / 2;
}

TEST(IntegratorRecipe, ASceneNamesItAndItsOptionAndItRuns) {
  const std::string four = "{type: test_forward_euler, substeps: 4}";
  EXPECT_LT(fall_error(four, forward_euler_fall(4)), 1e-9);
  EXPECT_GT(fall_error(four, forward_euler_fall(1)), 0.1) << "substeps must change the result";
  EXPECT_LT(fall_error("{type: test_forward_euler}", forward_euler_fall(1)), 1e-9);

  const auto out = test::scratch_dir("run");
  const RunSummary run =
      run_simulation(parse_config(scene_yaml(four, out.string()), "scene.yaml"), {});
  EXPECT_EQ(run.status, "completed");
  EXPECT_EQ(run.integrator, "test_forward_euler");
  ASSERT_EQ(run.integrator_statistics.size(), 1u);
  EXPECT_EQ(run.integrator_statistics[0].first, "substeps");
  EXPECT_EQ(run.integrator_statistics[0].second, 4.0 * run.steps);
  EXPECT_EQ(run.steps, kSteps);
}

TEST(IntegratorRecipe, ItsOptionIsCheckedWithTheKeyPath) {
  auto error = [](const std::string& integrator) {
    return test::input_error_message([&] { parse_config(scene_yaml(integrator), "scene.yaml"); });
  };
  EXPECT_EQ(error("{type: test_forward_euler, substeps: 0}"),
            "scene.yaml: integrator.substeps: must be positive, got 0");
  EXPECT_EQ(error("{type: test_forward_euler, substeps: 2.5}"),
            "scene.yaml: integrator.substeps: must be a whole number from 1 to 1000, got 2.5");
  EXPECT_EQ(error("{type: test_forward_euler, substep: 2}"),
            "scene.yaml: integrator.substep: unknown key; did you mean 'substeps'?");
  EXPECT_EQ(error("{type: symplectic_euler, substeps: 2}"),
            "scene.yaml: integrator.substeps: is an option of test_forward_euler, not of "
            "'symplectic_euler'");
}

}  // namespace
}  // namespace fissure
