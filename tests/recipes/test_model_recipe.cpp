// The recipe for adding a model (docs/architecture.md), shown by a test-only one: linear springs
// between family members, F_i = k Σ_j V_i V_j (u_j − u_i) with u = y − x, and its spring
// constant k as material.spring_constant, registered from this file alone, named by a scene and
// run. Its forces and its stable step are checked against those formulas (the lps model's
// differ, and so does a k that did not reach the model), and the run's stable step must be its.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "app/run_fissure.hpp"
#include "app/simulation.hpp"
#include "model/model_registry.hpp"
#include "scene/scene.hpp"
#include "support/error_message.hpp"

namespace fissure {
namespace {

struct SpringOptions final : ModelOptions {
  double spring_constant = 1e9;
};

class LinearSprings final : public Model {
 public:
  LinearSprings(const Scene& scene, MaterialPoints m, double k)
      : Model(scene.particles, scene.families, std::move(m)),
        k_(k),
        intact_(families_.directed_bonds(), 1) {}
  std::string name() const override { return "test_springs"; }
  void forces(const double* y, double* f) override {
    const int n = particles_.count();
    for (int i = 0; i < n; ++i)
      for (int d = 0; d < 3; ++d) {
        double sum = 0;
        for (int b = families_.offsets[i]; b < families_.offsets[i + 1]; ++b)
          if (intact_[b]) sum += particles_.volume[families_.neighbors[b]] * stretch(y, i, b, d);
        f[3 * i + d] = k_ * particles_.volume[i] * sum;
      }
  }
  // W_i = (k/4) Σ_j V_j |u_j − u_i|², so that Σ V_i W_i has the forces above as its gradient.
  void energy_density(const double* y, double* w) override {
    for (int i = 0; i < particles_.count(); ++i) {
      w[i] = 0;
      for (int b = families_.offsets[i]; b < families_.offsets[i + 1]; ++b)
        for (int d = 0; d < 3; ++d)
          if (intact_[b])
            w[i] += 0.25 * k_ * particles_.volume[families_.neighbors[b]] *
                    std::pow(stretch(y, i, b, d), 2);
    }
  }
  // Springs between particles have no volume change of their own: θ = 0 in the frames.
  void dilatation(const double*, double* theta) const override {
    std::fill(theta, theta + particles_.count(), 0.0);
  }
  // 2/ω_max with ω_max² ≤ max_i 2k V_i Σ_j V_j / m_i (Gershgorin).
  double stable_time_step() const override { return stable_step(particles_, families_, k_); }
  void break_bond(int, std::size_t b) override { intact_[b] = 0; }
  bool bond_intact(std::size_t b) const override { return intact_[b]; }
  std::size_t bytes_per_bond() const override { return 1; }
  std::size_t bytes_read_per_bond() const override { return 1; }

  static double stable_step(const Particles& p, const Families& f, double k) {
    double largest = 0;
    for (int i = 0; i < p.count(); ++i) {
      double sum = 0;
      for (int b = f.offsets[i]; b < f.offsets[i + 1]; ++b) sum += p.volume[f.neighbors[b]];
      largest = std::max(largest, 2 * k * p.volume[i] * sum / p.mass[i]);
    }
    return 2 / std::sqrt(largest);
  }

 private:
  // u_j − u_i along d for bond b of row i.
  double stretch(const double* y, int i, int b, int d) const {
    const int j = families_.neighbors[b];
    const double* x = particles_.reference.data();
    return (y[3 * j + d] - x[3 * j + d]) - (y[3 * i + d] - x[3 * i + d]);
  }

  double k_;
  std::vector<char> intact_;
};

// The whole recipe: a name, its keys, their parser and the constructor, in one call.
[[maybe_unused]] const bool registered = [] {
  register_model(
      {"test_springs",
       {"spring_constant"},
       [](const OptionReader& r) {
         auto options = std::make_shared<SpringOptions>();
         options->spring_constant = r.positive("spring_constant", options->spring_constant);
         return options;
       },
       [](const Scene& scene, MaterialPoints m) {
         const auto& options =
             dynamic_cast<const SpringOptions&>(*scene.config.bodies.front().material.options);
         return std::make_unique<LinearSprings>(scene, std::move(m), options.spring_constant);
       }});
  return true;
}();

constexpr double kSpring = 3e9;

std::string scene_yaml(const std::string& material, const std::string& out = "unused") {
  return fmt::format(
      "time: {{end: 1e-4}}\n"
      "bodies:\n"
      "  - geometry: {{box: {{min: [0, 0, 0], max: [0.1, 0.1, 0.1]}}}}\n"
      "    resolution: 0.05\n"
      "    velocity: [0.1, 0, 0]\n"
      "    material: {{density: 1000, bulk_modulus: 1.0e4, shear_modulus: 1.0e4{}}}\n"
      "output: {{dir: {}}}\n",
      material, out);
}

const std::string kSprings = fmt::format(", model: test_springs, spring_constant: {}", kSpring);

TEST(ModelRecipe, ASceneNamesItAndItsOptionAndItRuns) {
  const Scene scene = build_scene(parse_config(scene_yaml(kSprings), "scene.yaml"));
  auto model = make_model(scene);
  EXPECT_EQ(model->name(), "test_springs");
  const Particles& p = scene.particles;
  const Families& f = scene.families;
  // Particle 0 moved by d along x: F_0 = −k V_0 Σ_j V_j d, F_j = k V_j V_0 d for its bonds.
  const double d = 1e-4;
  std::vector<double> y = p.reference, force(y.size());
  y[0] += d;
  model->forces(y.data(), force.data());
  std::vector<double> expected(y.size(), 0.0);
  for (int b = f.offsets[0]; b < f.offsets[1]; ++b) {
    const int j = f.neighbors[b];
    expected[0] -= kSpring * p.volume[0] * p.volume[j] * d;
    expected[3 * j] += kSpring * p.volume[j] * p.volume[0] * d;
  }
  ASSERT_GT(f.offsets[1], 0);
  for (std::size_t u = 0; u < y.size(); ++u)
    EXPECT_NEAR(force[u], expected[u], 1e-9 * std::abs(expected[0])) << "unknown " << u;

  const double stable = LinearSprings::stable_step(p, f, kSpring);
  const auto out = test::scratch_dir("run");
  const RunSummary run =
      run_simulation(parse_config(scene_yaml(kSprings, out.string()), "scene.yaml"), {});
  EXPECT_EQ(run.status, "completed");
  EXPECT_GT(run.steps, 0);
  EXPECT_DOUBLE_EQ(run.stable_dt, stable);
  EXPECT_DOUBLE_EQ(run.dt, 0.9 * stable);
}

TEST(ModelRecipe, ItsOptionIsCheckedWithTheKeyPath) {
  auto error = [](const std::string& material) {
    return test::input_error_message([&] { parse_config(scene_yaml(material), "scene.yaml"); });
  };
  EXPECT_EQ(error(", model: test_springs, spring_constant: -1"),
            "scene.yaml: bodies[0].material.spring_constant: must be positive, got -1");
  EXPECT_EQ(error(", spring_constant: 1"),
            "scene.yaml: bodies[0].material.spring_constant: is an option of test_springs, not "
            "of 'lps'");
  EXPECT_EQ(error(", model: test_spring"),
            "scene.yaml: bodies[0].material.model: unknown model 'test_spring' (valid: lps, "
            "paper, test_springs)");
}

}  // namespace
}  // namespace fissure
