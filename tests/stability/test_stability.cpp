// The stability suite (ctest label `stability`): hard cases stay numerically stable or stop with
// a clear message, never with silent NaN. Each case prints its figures (ledger balance error,
// largest speed, steps) and bounds them: the balance error by what its integrator may do
// (docs/output.md, "Energy ledger"), the largest speed by speed_bound()
// (completed_within_speed_bound()).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>

#include "io/vtu_reader.hpp"
#include "model/model.hpp"
#include "stability/stability_case.hpp"
#include "support/csv.hpp"

namespace fissure {
namespace {

using test::CaseRun;
using test::report;
using test::run_case;

// The explicit stable step estimate of a scene, as the run computes it.
double stable_step(const std::string& yaml) {
  const Scene scene = build_scene(parse_config(yaml, "stable_step.yaml"));
  return make_model(scene)->stable_time_step();
}

// Every number in a CSV file after its header is finite; returns the rows.
std::vector<std::vector<double>> finite_rows(const std::filesystem::path& csv) {
  std::vector<std::vector<double>> rows;
  for (const auto& cells : test::read_csv(csv).rows) {
    std::vector<double> row;
    for (const std::string& cell : cells) {
      row.push_back(std::stod(cell));
      EXPECT_TRUE(std::isfinite(row.back())) << csv << ": row " << rows.size() + 1 << ": " << cell;
    }
    rows.push_back(row);
  }
  return rows;
}

// Glass (Table 1's moduli) bar, clamped at one end and released under gravity: its bending
// period is 4 ms, 70 explicit limits.
const std::string kGlassBar = R"(
time: {end: 0.005, dt: auto}
gravity: [0, 0, -9.81]
bodies:
  - geometry: {box: {min: [0, 0, 0], max: [0.3, 0.05, 0.05]}}
    resolution: 0.025
    material: {density: 2200, bulk_modulus: 3.3e10, shear_modulus: 2.0e10}
constraints:
  - {region: {box: {min: [-1, -1, -1], max: [0.02, 1, 1]}}, fix: true}
output: {every: 0.005, probe_every: 0.0005}
)";

// At 100× the explicit limit every implicit integrator completes. Newmark (average
// acceleration) conserves the energy of a linear problem exactly; what is left is the
// nonlinearity of this small sag and Newton's stopping error. Each step stops with a residual
// below rtol = 1e-6 of its first one, and that residual does spurious work over the step's
// displacement: first order in rtol, since modified Newton (a reused factor) converges
// linearly and need not overshoot the tolerance. The first residual times the step's
// displacement is at most the energy scale, so |balance| ≤ steps × rtol of it (measured 1.3e-6
// over 36 steps with the half-precision factor; 1.7e-9 with the single one, whose Newton
// iterations happened to overshoot). Backward Euler and generalized-α dissipate: they may lose
// energy but not create it, balance ≤ the same allowance for Newton's stopping error
// (docs/output.md: a dissipative integrator's balance is ≤ 0); ARKODE's SDIRK keeps its own
// 1e-6.
TEST(Stability, GlassModuliImplicitAt100TimesTheExplicitLimit) {
  const double dt = 100 * stable_step(kGlassBar);
  struct Variant {
    std::string name, settings;
    bool conserving;
  };
  for (const Variant& v :
       {Variant{"glass_newmark_100x", "--set integrator.scheme=newmark", true},
        Variant{"glass_backward_euler_100x", "--set integrator.scheme=backward_euler", false},
        Variant{"glass_alpha_100x", "--set integrator.scheme=alpha", false}}) {
    const std::string args = fmt::format("--set time.dt={} {}", dt, v.settings);
    const CaseRun run = run_case(v.name, "integrator: {type: petsc_newton}\n" + kGlassBar, args);
    ASSERT_TRUE(test::completed_within_speed_bound(run));
    const double error = run.energy.at("balance_error");
    const double newton_allowance = run.number("steps") * 1e-6;
    if (v.conserving)
      EXPECT_LT(std::abs(error), newton_allowance) << v.name;
    else
      EXPECT_LT(error, newton_allowance) << v.name;
  }
  const CaseRun run =
      run_case("glass_arkode_sdirk_100x",
               "integrator: {type: arkode, method: SDIRK_2_1_2, fixed_step: true}\n" + kGlassBar,
               fmt::format("--set time.dt={}", dt));
  ASSERT_TRUE(test::completed_within_speed_bound(run));
  EXPECT_LT(run.energy.at("balance_error"), 1e-6);
}

// A near-incompressible (ν = 0.49: κ = 49.67 μ) rubber block on a fixed base whose top layer
// is pushed down at 1 m/s for 5 ms (5% of its height), then released to ring: volumetric
// stiffness 50× the shear one, no contact to blur the books.
const std::string kRubberBlock = R"(
time: {end: 0.02, dt: auto}
bodies:
  - geometry: {box: {min: [0, 0, 0], max: [0.1, 0.1, 0.1]}}
    resolution: 0.025
    material: {density: 1100, bulk_modulus: 4.967e7, shear_modulus: 1.0e6}
constraints:
  - {region: {box: {min: [-1, -1, -1], max: [2, 2, 0.005]}}, fix: true}
  - {region: {box: {min: [-1, -1, 0.095], max: [2, 2, 1]}}, velocity: [0, 0, -1], release_at: 0.005}
output: {every: 0.02, probe_every: 0.0005}
)";

// Explicit at dt: auto and backward Euler at 20× the limit both complete. Symplectic Euler
// keeps the books to O(dt): |error| < 0.01 (measured 3.6e-3). Backward Euler may only lose
// energy, up to the same O(dt) booking of the pushing constraint's work, so its balance is
// bounded above by the same 0.01 (measured −1.0: it damps the ringing out).
TEST(Stability, NearIncompressibleBlockExplicitAndImplicit) {
  const CaseRun explicit_run =
      run_case("rubber_nu049_explicit", "integrator: {type: symplectic_euler}\n" + kRubberBlock);
  ASSERT_TRUE(test::completed_within_speed_bound(explicit_run));
  EXPECT_LT(std::abs(explicit_run.energy.at("balance_error")), 0.01);

  const CaseRun implicit_run = run_case(
      "rubber_nu049_backward_euler_20x", "integrator: {type: petsc_newton}\n" + kRubberBlock,
      fmt::format("--set time.dt={}", 20 * stable_step(kRubberBlock)));
  ASSERT_TRUE(test::completed_within_speed_bound(implicit_run));
  EXPECT_LT(implicit_run.energy.at("balance_error"), 0.01);
}

// A 2 kg sphere at 300 m/s through a glass wall (Table 1's glass), explicit at dt: auto: the
// wall shatters, nothing blows up. The balance carries the O(dt) error of the impact's work.
TEST(Stability, ProjectileAt300MetresPerSecondThroughBrittleWall) {
  const CaseRun run = run_case("projectile_300_m_s", R"(
time: {end: 0.0015, dt: auto}
integrator: {type: symplectic_euler}
gravity: [0, 0, -9.81]
bodies:
  - geometry: {box: {min: [0, 0, 0], max: [0.5, 0.05, 0.5]}}
    resolution: 0.025
    material:
      density: 2200
      bulk_modulus: 3.3e10
      shear_modulus: 2.0e10
      fracture: {critical_stretch: 0.0005}
constraints:
  - {region: {box: {min: [-1, -1, -1], max: [2, 2, 0.015]}}, fix: true}
colliders:
  - {sphere: {center: [0.25, -0.06, 0.25], radius: 0.05}, velocity: [0, 300, 0], mass: 2}
output: {every: 0.0015, probe_every: 0.00005}
)");
  ASSERT_TRUE(test::completed_within_speed_bound(run));
  EXPECT_GT(run.number("broken_bonds"), 0);
  EXPECT_GT(run.number("fragments"), 1);
  EXPECT_LT(std::abs(run.energy.at("balance_error")), 0.1);
  finite_rows(run.out / "probes.csv");
}

// A block 0.1 m high whose top layer is driven down through it to 10% of its height (the layer
// ends 0.005 m above the fixed bottom layer, less than a particle spacing): particles pile up,
// pass each other and bonds shrink through zero length. No NaN, no energy from nowhere.
const std::string kCrush = R"(
time: {end: 0.09, dt: auto}
bodies:
  - geometry: {box: {min: [0, 0, 0], max: [0.1, 0.1, 0.1]}}
    resolution: 0.025
    material: {density: 1000, bulk_modulus: 1.0e6, shear_modulus: 5.0e5}
constraints:
  - {region: {box: {min: [-1, -1, -1], max: [2, 2, 0.005]}}, fix: true}
  - {region: {box: {min: [-1, -1, 0.095], max: [2, 2, 1]}}, velocity: [0, 0, -1]}
output: {every: 0.03, probe_every: 0.001}
)";

TEST(Stability, CrushToTenPercentOfHeightStaysFinite) {
  const CaseRun run =
      run_case("crush_to_10_percent", "integrator: {type: symplectic_euler}\n" + kCrush);
  ASSERT_TRUE(test::completed_within_speed_bound(run));
  EXPECT_LT(std::abs(run.energy.at("balance_error")), 0.01);  // O(dt); measured 1.4e-3
  EXPECT_GT(run.energy.at("constraint_work"), 0);
  finite_rows(run.out / "probes.csv");
}

// A 6×6×6 lattice flying apart with v = 20 s⁻¹ (x − c): every bond stretches by 20|ξ|dt in the
// first step, far past s_c δ, so all break at once. With no bond left a particle feels no
// force: between two later frames each keeps its velocity (to 1e-12 m/s) and moves by v Δt (to
// 1e-9 m: the round-off of a few hundred additions), and the energy books stop moving (the
// balance after the first step, Π of the stretched bonds the integrator made without work, stays
// as it is to 1e-9 of the scale).
TEST(Stability, TotalShatteringLeavesEveryParticleBallistic) {
  std::string lattice;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      for (int k = 0; k < 6; ++k) {
        const double x = 0.01 * i, y = 0.01 * j, z = 0.01 * k;
        lattice += fmt::format("{} {} {} 1e-6 {} {} {}\n", x, y, z, 20 * (x - 0.025),
                               20 * (y - 0.025), 20 * (z - 0.025));
      }
  const std::string yaml = R"(
time: {end: 0.02, dt: auto}
bodies:
  - geometry: {points: {file: lattice.txt}}
    resolution: 0.01
    material:
      density: 1000
      bulk_modulus: 1.0e6
      shear_modulus: 5.0e5
      fracture: {critical_stretch: 1.0e-5}
output: {every: 0.01, probe_every: 0.001}
)";
  for (const std::string type : {"symplectic_euler", "petsc_newton"}) {
    const CaseRun run = run_case("shatter_" + type, "integrator: {type: " + type + "}\n" + yaml, "",
                                 {{"lattice.txt", lattice}});
    ASSERT_TRUE(test::completed_within_speed_bound(run));
    EXPECT_EQ(run.number("broken_bonds"), run.number("bonds")) << type;
    EXPECT_EQ(run.number("fragments"), run.number("particles")) << type;
    const auto rows = finite_rows(run.out / "probes.csv");
    ASSERT_GT(rows.size(), 3u);
    for (std::size_t r = 2; r < rows.size(); ++r)
      EXPECT_NEAR(rows[r].back(), rows[1].back(), 1e-9) << type << " row " << r;
    // Frame times from the PVD index.
    const std::string pvd = test::slurp(run.out / "particles.pvd");
    std::vector<double> times;
    static const std::regex timestep(R"re(timestep="([^"]+)")re");
    for (auto it = std::sregex_iterator(pvd.begin(), pvd.end(), timestep);
         it != std::sregex_iterator(); ++it)
      times.push_back(std::stod((*it)[1]));
    ASSERT_EQ(times.size(), 3u) << pvd;
    const VtuGrid first = read_vtu((run.out / "particles_000001.vtu").string());
    const VtuGrid last = read_vtu((run.out / "particles_000002.vtu").string());
    const auto& damage = first.point_data.at("damage").values;
    const auto& v1 = first.point_data.at("velocity").values;
    const auto& v2 = last.point_data.at("velocity").values;
    double velocity_change = 0, path_error = 0;
    for (std::size_t i = 0; i < damage.size(); ++i) {
      EXPECT_EQ(damage[i], 1.0) << type << " particle " << i;
      for (int d = 0; d < 3; ++d) {
        const std::size_t k = 3 * i + d;
        velocity_change = std::max(velocity_change, std::abs(v2[k] - v1[k]));
        path_error = std::max(
            path_error, std::abs(last.points[k] - first.points[k] - v1[k] * (times[2] - times[1])));
      }
    }
    std::printf("[stability] %s: largest velocity change %.2e m/s, path error %.2e m\n",
                type.c_str(), velocity_change, path_error);
    EXPECT_LT(velocity_change, 1e-12) << type;
    EXPECT_LT(path_error, 1e-9) << type;
  }
}

// A plastic bar (the plastic wall's material, γ/|ξ| = 0.05) pulled at 0.5 m/s to 50% strain,
// ten times past the cap on plastic stretch, by backward Euler at 50× the explicit limit: the
// return map runs after each large step and the run stays stable. Backward Euler and the
// return map only take energy out: balance ≤ +0.01.
TEST(Stability, SustainedPlasticFlowWithTheCapUnderLargeImplicitSteps) {
  const std::string yaml = R"(
time: {end: 0.2, dt: auto}
integrator: {type: petsc_newton}
bodies:
  - geometry: {box: {min: [0, 0, 0], max: [0.2, 0.04, 0.04]}}
    resolution: 0.02
    material:
      density: 2200
      bulk_modulus: 3.3e6
      shear_modulus: 2.0e6
      plasticity: {yield_stress: 5.0e4, max_plastic_stretch: 0.05}
constraints:
  - {region: {box: {min: [-1, -1, -1], max: [0.01, 1, 1]}}, fix: true}
  - {region: {box: {min: [0.19, -1, -1], max: [1, 1, 1]}}, velocity: [0.5, 0, 0]}
output: {every: 0.1, probe_every: 0.002}
)";
  const CaseRun run = run_case("plastic_flow_backward_euler_50x", yaml,
                               fmt::format("--set time.dt={}", 50 * stable_step(yaml)));
  ASSERT_TRUE(test::completed_within_speed_bound(run));
  EXPECT_GT(run.energy.at("plastic_dissipation"), 0.0);
  EXPECT_LT(run.energy.at("balance_error"), 0.01);
  finite_rows(run.out / "probes.csv");
}

// Symplectic Euler at 3× the stable estimate (allowed on purpose) on the glass bar: the
// energy-growth check stops the run while every written number is still finite, with status
// `unstable` and a message that names a stable dt. A run too short for that stop is stopped at
// its end.
TEST(Stability, ExplicitAtThreeTimesTheStableStepIsStoppedEarly) {
  const double stable = stable_step(kGlassBar);
  const CaseRun run =
      run_case("explicit_3x_stable_step", "integrator: {type: symplectic_euler}\n" + kGlassBar,
               fmt::format("--set time.dt={} --set integrator.allow_unstable_dt=true", 3 * stable));
  report(run, NAN);
  EXPECT_EQ(run.outcome.exit_code, 3) << run.outcome.output;
  EXPECT_EQ(run.status(), "unstable") << run.outcome.output;
  EXPECT_NE(run.outcome.output.find(fmt::format("a time.dt of at most {:.3g} s", stable)),
            std::string::npos)
      << run.outcome.output;
  EXPECT_EQ(run.outcome.output.find("non-finite"), std::string::npos) << run.outcome.output;
  const double planned = std::ceil(0.005 / (3 * stable));
  EXPECT_LT(run.number("steps"), planned);
  EXPECT_FALSE(finite_rows(run.out / "probes.csv").empty());

  // The same run ended 5 steps before that stop: its energy has grown for the last 5 of its
  // steps, fewer than the 10 in a row that stop a run on its way, and it is judged at its end:
  // stopped, never completed.
  const long stopped_at = static_cast<long>(run.number("steps"));
  ASSERT_GT(stopped_at, 10);
  const long steps = stopped_at - 5;
  const CaseRun shorter = run_case(
      "explicit_3x_stable_step_short", "integrator: {type: symplectic_euler}\n" + kGlassBar,
      fmt::format("--set time.dt={0} --set time.end={1} --set output.every={1} "
                  "--set output.probe_every={1} --set integrator.allow_unstable_dt=true",
                  3 * stable, 3 * stable * steps));
  EXPECT_EQ(shorter.status(), "unstable") << shorter.outcome.output;
  EXPECT_EQ(shorter.number("steps"), steps) << shorter.outcome.output;
}

// Newton limited on the crushed block at 25× the explicit limit. Limited to 2 iterations over
// the first two steps, the first step's Newton already fails (the top layer's impact): with the
// default fallback the failed steps are redone as halves and the run completes. Limited to 4
// iterations with max_step_halvings: 0, it runs 16 steps and stops at the first failure (t =
// 0.077 s) with status `failed` and the solver's reason, every row and frame written before it
// intact.
TEST(Stability, NewtonFailureHalvesTheStepOrStopsWithAClearMessage) {
  const double dt = 25 * stable_step(kCrush);
  const CaseRun halved = run_case(
      "newton_failure_halved", "integrator: {type: petsc_newton}\n" + kCrush,
      fmt::format(
          "--set time.dt={} --set time.end={} --set integrator.petsc_options='-snes_max_it 2'", dt,
          2 * dt));
  ASSERT_TRUE(test::completed_within_speed_bound(halved));
  EXPECT_GT(halved.statistic("step_halvings"), 0);
  EXPECT_LT(halved.energy.at("balance_error"), 0.01);

  const CaseRun stopped =
      run_case("newton_failure_stops", "integrator: {type: petsc_newton}\n" + kCrush,
               fmt::format("--set time.dt={} --set integrator.petsc_options='-snes_max_it 4' "
                           "--set integrator.max_step_halvings=0",
                           dt));
  report(stopped, NAN);
  EXPECT_EQ(stopped.outcome.exit_code, 3) << stopped.outcome.output;
  EXPECT_EQ(stopped.status(), "failed");
  EXPECT_NE(stopped.outcome.output.find("Newton did not converge"), std::string::npos)
      << stopped.outcome.output;
  const auto rows = finite_rows(stopped.out / "probes.csv");
  ASSERT_GT(rows.size(), 1u);  // rows written before the failure
  EXPECT_LT(rows.back()[0], 0.09);
  EXPECT_TRUE(std::filesystem::exists(stopped.out / "particles_000000.vtu"));
}

}  // namespace
}  // namespace fissure
