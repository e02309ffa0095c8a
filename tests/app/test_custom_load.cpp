// The "add a load" recipe (docs/architecture.md): a test-only load, a uniform body force
// F_i = m_i a₀, registered from this file alone. Every integrator must feel it (the block moves)
// and the ledger must book its work in an entry of its own (body_force_work, after the built-in
// loads' entries) and count it in the balance. On a free block the motion is rigid, so the
// numbers are known exactly: symplectic Euler takes v_n = a₀ h n and y_n − y_0 = a₀ h² n(n+1)/2,
// so K = ½ M|a₀|² h² n² against the load's work M|a₀|² h² n(n+1)/2 and the balance error is
// −1/(n+1); the other integrators are exact for a constant acceleration: work = K = ½ M|a₀|² t²,
// balance 0. A ledger that ignored the registered load would miss the entry or show a balance
// error near −1; an integrator that ignored it would leave the block at rest (K = 0).
#include <gtest/gtest.h>

#include <cmath>

#include "app/run_fissure.hpp"
#include "app/simulation.hpp"
#include "integrators/force_sums.hpp"
#include "integrators/load_registry.hpp"
#include "support/free_block.hpp"

namespace fissure {
namespace {

constexpr double kA[3] = {0.3, -0.4, 1.2};  // a₀ [m/s²], |a₀| = 1.3

// The body force m a₀ on every particle; its work over a step is Σ F·Δy.
class BodyForce : public Load {
 public:
  explicit BodyForce(const Scene& scene) : force_(3 * scene.particles.mass.size()) {
    for (std::size_t i = 0; i < scene.particles.mass.size(); ++i)
      for (int k = 0; k < 3; ++k) force_[3 * i + k] = scene.particles.mass[i] * kA[k];
  }
  void add(double, const double*, const double*, double* f) override { add_to(force_, f); }
  double booked(const BookedStep& step) const override {
    return work_of(force_, step.before, step.after);
  }

 private:
  std::vector<double> force_;
};

const bool registered = [] {
  register_load({"body_force_work", Booking::work, [](const Scene& scene, const Model&) {
                   return std::make_unique<BodyForce>(scene);
                 }});
  return true;
}();

const std::string kBlock = test::free_block_yaml("output: {every: 0.1, probe_every: 0.01}\n");

TEST(CustomLoad, BodyForceIsFeltByEveryIntegratorAndBookedInTheLedger) {
  ASSERT_TRUE(registered);
  for (const std::string type : {"symplectic_euler", "velocity_verlet", "petsc_newton", "arkode"}) {
    const auto dir = test::scratch_dir(type);
    std::vector<std::string> overrides = {"integrator.type=" + type};
    if (type == "petsc_newton") overrides.push_back("integrator.scheme=newmark");
    Config config = parse_config(kBlock, (dir / "block.yaml").string(), overrides);
    config.output.dir = dir.string();
    const RunSummary summary = run_simulation(config, {});
    std::map<std::string, double> e(summary.energy.begin(), summary.energy.end());
    std::vector<std::string> names;
    for (const auto& [name, value] : summary.energy) names.push_back(name);

    const double mass = 1000 * 0.001, a2 = 1.3 * 1.3, h = 0.001, n = 100, t = 0.1;
    const bool euler = type == "symplectic_euler";
    const double work = euler ? mass * a2 * h * h * n * (n + 1) / 2 : mass * a2 * t * t / 2;
    const double kinetic = mass * a2 * t * t / 2;
    const double balance_error = euler ? -1 / (n + 1) : 0.0;
    std::printf(
        "%s: body_force_work %.9g J (expected %.9g), kinetic %.9g J (expected %.9g), "
        "balance error %.3g (expected %.3g)\n",
        type.c_str(), e.at("body_force_work"), work, e.at("kinetic"), kinetic,
        e.at("balance_error"), balance_error);
    EXPECT_NEAR(e.at("body_force_work"), work, 1e-6 * work) << type;
    EXPECT_NEAR(e.at("kinetic"), kinetic, 1e-6 * kinetic) << type;
    EXPECT_NEAR(e.at("balance_error"), balance_error, 1e-6) << type;
    EXPECT_EQ(e.at("gravity_work"), 0.0) << type;
    // Its entry comes after the built-in loads' and before the post-step's, in probes.csv too.
    const auto at = [&](const char* name) { return std::find(names.begin(), names.end(), name); };
    EXPECT_EQ(at("body_force_work"), at("contact_loss") + 1) << type;
    EXPECT_EQ(at("plastic_dissipation"), at("body_force_work") + 1) << type;
    const std::string header = test::slurp(dir / "probes.csv").substr(0, 400);
    EXPECT_NE(header.find("contact_loss,body_force_work,plastic_dissipation"), std::string::npos)
        << header;
  }
}

}  // namespace
}  // namespace fissure
