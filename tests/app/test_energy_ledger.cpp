// The energy ledger's books on a case whose numbers are known exactly: a free-falling block
// (uniform velocity field, no strain). Symplectic Euler takes v_n = g n h and drops
// ½ g h² n(n+1), so K = ½ M g² h² n² against gravity's work M g² h² n(n+1)/2: the books are off
// by exactly −1/(n+1) of the work. Velocity Verlet is exact for a constant acceleration, so its
// books balance to round-off.
#include <gtest/gtest.h>

#include "app/run_fissure.hpp"
#include "stability/stability_case.hpp"

namespace fissure {
namespace {

const char* kFreeFall = R"(
time: {end: 0.1, dt: 0.001}
gravity: [0, 0, -9.81]
bodies:
  - geometry: {box: {min: [0, 0, 0], max: [0.1, 0.1, 0.1]}}
    resolution: 0.05
    material: {density: 1000, bulk_modulus: 1.0e5, shear_modulus: 5.0e4}
output: {every: 0.1, probe_every: 0.01}
)";

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

}  // namespace
}  // namespace fissure
