// The energy ledger's books on a case whose numbers are known exactly: a free-falling block
// (uniform velocity field, no strain). Symplectic Euler takes v_n = g n h and drops
// ½ g h² n(n+1), so K = ½ M g² h² n² against gravity's work M g² h² n(n+1)/2: the books are off
// by exactly −1/(n+1) of the work. Velocity Verlet is exact for a constant acceleration, so its
// books balance to round-off.
#include <gtest/gtest.h>

#include "app/run_fissure.hpp"
#include "stability/stability_case.hpp"
#include "support/free_block.hpp"
#include "support/two_particles.hpp"

namespace fissure {
namespace {

const std::string kFreeFall =
    test::free_block_yaml("gravity: [0, 0, -9.81]\noutput: {every: 0.1, probe_every: 0.01}\n");

TEST(EnergyLedger, FreeFallBooksGravityWorkExactly) {
  for (const std::string type : {"symplectic_euler", "velocity_verlet"}) {
    const test::CaseRun run =
        test::run_case("ledger_free_fall_" + type, kFreeFall, "--set integrator.type=" + type);
    ASSERT_EQ(run.outcome.exit_code, 0) << run.outcome.output;
    const auto& e = run.energy;
    const double n = 100, work = e.at("gravity_work");
    // Gravity's work is M g Δz with Δz = ½ g t² (Verlet) or ½ g h² n(n+1) (symplectic Euler).
    const double drop =
        type == "velocity_verlet" ? 0.5 * 9.81 * 0.01 : 0.5 * 9.81 * 1e-6 * n * (n + 1);
    const double mass = 1000 * 0.001;
    EXPECT_NEAR(work, mass * 9.81 * drop, 1e-9 * work) << type;
    EXPECT_NEAR(e.at("kinetic"), 0.5 * mass * 9.81 * 9.81 * 0.01, 1e-9 * work) << type;
    EXPECT_LT(std::abs(e.at("elastic")), 1e-12 * work) << type;
    const double expected = type == "velocity_verlet" ? 0.0 : -1.0 / (n + 1);
    EXPECT_NEAR(e.at("balance_error"), expected, 1e-9) << type;
    std::printf("%s: gravity work %.6g J, balance error %.6g (expected %.6g)\n", type.c_str(), work,
                e.at("balance_error"), expected);
  }
}

// fracture_release against the energy the bond held when it broke. Two particles, one bond
// (tests/support/two_particles.hpp): A held still, B held moving away along the bond at V, so
// after step n the extension is e_n = V n h exactly. The bond breaks after the first step with
// e_n > s_c δ (Eqs 18–19, α = 0, ω|ξ| = δ), here n* = ⌈s_c δ/(V h)⌉ = 112, and releases all it
// stored: Π(e) = Σ_i V_i ½κθ_i² with θ_i = 3e/L (Eq 6, plain weights), i.e. 9κV e²/L². Bound
// 1e-6 relative: the model keeps its bond weights in single precision (relative 6e-8 in θ,
// docs/model.md), the rest is round-off.
TEST(EnergyLedger, FractureReleaseIsTheBondsEnergyAtTheBreakingStretch) {
  test::TwoParticles pair;
  const double sc = 0.01, speed = 0.1, h = 1.3e-5;
  pair.material_extra = fmt::format(", fracture: {{critical_stretch: {}}}", sc);
  const double delta = 1.45 * pair.spacing;
  const double r = 0.3 * pair.spacing;
  const std::string yaml = fmt::format(
      "time: {{end: {0}, dt: {1}}}\nintegrator: {{type: velocity_verlet}}\nbodies:\n{2}"
      "constraints:\n"
      "  - {{region: {{sphere: {{center: [0, 0, 0], radius: {3}}}}}, fix: true}}\n"
      "  - {{region: {{sphere: {{center: [{4}, 0, 0], radius: {3}}}}}, velocity: [{5}, 0, 0]}}\n"
      "output: {{every: {0}}}\n",
      150 * h, h, pair.body("pair.txt"), r, pair.spacing, speed);
  const test::CaseRun run =
      test::run_case("ledger_fracture", yaml, "", {{"pair.txt", pair.points()}});
  ASSERT_EQ(run.outcome.exit_code, 0) << run.outcome.output;
  const double breaking_step = std::ceil(sc * delta / (speed * h));
  ASSERT_EQ(breaking_step, 112);
  const double released = pair.energy(speed * h * breaking_step);
  const auto& e = run.energy;
  std::printf("fracture_release %.9e J, the bond's energy at e = %.4g m: %.9e J (relative %.2e)\n",
              e.at("fracture_release"), speed * h * breaking_step, released,
              e.at("fracture_release") / released - 1);
  EXPECT_EQ(run.number("broken_bonds"), 1);
  EXPECT_NEAR(e.at("fracture_release"), released, 1e-6 * released);
  EXPECT_EQ(e.at("elastic"), 0.0);  // a broken bond stores nothing
  // The constraint's work, booked with the reaction k_s e_k at each step's end (docs/output.md),
  // is Σ_{k ≤ n*} k_s e_k V h = ½ k_s (V h)² n*(n* + 1): the stored energy times (n* + 1)/n*.
  EXPECT_NEAR(e.at("constraint_work"), released * (breaking_step + 1) / breaking_step,
              1e-6 * released);
}

}  // namespace
}  // namespace fissure
