// fissure study on a tiny study: it writes results.csv, results.md and the work–precision plot,
// and the error falls with dt at the rate of each integrator's order.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "app/run_fissure.hpp"
#include "support/csv.hpp"

namespace fissure {
namespace {

namespace fs = std::filesystem;

// The coarse bar swing (60 particles) for 10 ms, compared at 5 and 10 ms with a VERNER_8_5_6
// reference at rtol 1e-12. Steps from 0.55× down to 0.14× the stable estimate (3.6e-5 s).
const char* kStudy = R"(scene: {scene}
set: ["time.end=0.01", "bodies[0].resolution=0.1"]
every: 0.005
reference: {integrator: {type: arkode, method: VERNER_8_5_6, rtol: 1.0e-12, atol: 1.0e-15}}
runs:
  - {name: symplectic_euler, integrator: {type: symplectic_euler}, dt: [2.0e-5, 1.0e-5, 5.0e-6]}
  - {name: velocity_verlet, integrator: {type: velocity_verlet}, dt: [2.0e-5, 1.0e-5, 5.0e-6]}
  - name: backward_euler
    integrator: {type: petsc_newton, scheme: backward_euler, petsc_options: "-snes_rtol 1e-12 -snes_atol 1e-14"}
    dt: [2.0e-5, 1.0e-5, 5.0e-6]
  - name: newmark
    integrator: {type: petsc_newton, scheme: newmark, petsc_options: "-snes_rtol 1e-12 -snes_atol 1e-14"}
    dt: [2.0e-5, 1.0e-5, 5.0e-6]
output: {dir: {out}}
)";

// Order observed between the two smallest steps (ω_max h ≤ 0.23 there, the asymptotic regime;
// at 0.46 Verlet and Newmark still show 1.4 and 1.2), within ±0.3 of nominal, and the error falls
// at every halving.
TEST(Study, ErrorFallsWithDtAtEachIntegratorsOrder) {
  const fs::path dir = test::scratch_dir("study");
  std::string text = kStudy;
  text.replace(text.find("{scene}"), 7,
               std::string(FISSURE_SOURCE_DIR) + "/configs/compare/bar_swing.yaml");
  text.replace(text.find("{out}"), 5, (dir / "out").string());
  test::write_file(dir / "order.yaml", text);
  const auto outcome = test::run_fissure("study " + (dir / "order.yaml").string());
  ASSERT_EQ(outcome.exit_code, 0) << outcome.output;
  for (const char* file : {"results.csv", "results.md", "work_precision.png", "work_precision.svg"})
    EXPECT_TRUE(fs::exists(dir / "out" / file)) << file;
  const auto rows = test::read_records(dir / "out" / "results.csv");
  const std::map<std::string, double> order = {
      {"symplectic_euler", 1}, {"velocity_verlet", 2}, {"backward_euler", 1}, {"newmark", 2}};
  std::map<std::string, std::vector<double>> errors;  // by run, in the order of falling dt
  for (const auto& row : rows) {
    ASSERT_EQ(row.at("status"), "ok") << row.at("run") << " " << row.at("value");
    errors[row.at("run")].push_back(std::stod(row.at("error_max")));
  }
  ASSERT_EQ(errors.size(), order.size());
  for (const auto& [run, e] : errors) {
    ASSERT_EQ(e.size(), 3u) << run;
    const double observed = std::log2(e[1] / e[2]);
    std::printf("%s: errors %.3g %.3g %.3g, observed order %.2f\n", run.c_str(), e[0], e[1], e[2],
                observed);
    EXPECT_LT(e[1], e[0]) << run;
    EXPECT_LT(e[2], e[1]) << run;
    EXPECT_NEAR(observed, order.at(run), 0.3) << run;
  }
}

// dt: auto takes the scene's stable estimate (rounded down to divide `every`); the probe error
// over the amplitude is the probe error over d times d / amplitude, with the amplitude read from
// the reference's probes.csv; the target table names, per run, its fastest point within the
// target and its speed-up over the baseline, and "none" for a run with no point within it.
TEST(Study, AutoStepAmplitudeErrorAndTargetTable) {
  const fs::path dir = test::scratch_dir("study_target");
  const std::string scene = std::string(FISSURE_SOURCE_DIR) + "/configs/compare/bar_swing.yaml";
  test::write_file(
      dir / "target.yaml",
      "scene: " + scene +
          "\nset: [\"time.end=0.01\", \"bodies[0].resolution=0.1\"]\nevery: 0.005\n"
          "reference: {integrator: {type: velocity_verlet}, dt: 2.5e-6}\n"
          "target: {probe_error: 0.05, baseline: velocity_verlet}\nruns:\n"
          "  - {name: velocity_verlet, integrator: {type: velocity_verlet}, dt: [auto]}\n"
          "  - {name: coarse, integrator: {type: petsc_newton, scheme: "
          "backward_euler}, dt: [0.005]}\n"
          "output: {dir: " +
          (dir / "out").string() + "}\n");
  const auto outcome = test::run_fissure("study " + (dir / "target.yaml").string());
  ASSERT_EQ(outcome.exit_code, 0) << outcome.output;
  const auto rows = test::read_records(dir / "out" / "results.csv");
  ASSERT_EQ(rows.size(), 2u);
  // The stable estimate of this scene (fissure info) times the default safety, divided down.
  const auto info = test::run_fissure("info " + scene + " --set bodies[0].resolution=0.1");
  const auto at = info.output.find("stable dt estimate: ");
  ASSERT_NE(at, std::string::npos) << info.output;
  const double stable = std::stod(info.output.substr(at + 20));
  const double dt = std::stod(rows[0].at("dt"));
  std::printf("dt: auto -> %.4g s (stable estimate %.4g s)\n", dt, stable);
  EXPECT_LE(dt, stable);
  EXPECT_GT(dt, 0.5 * stable);
  // a whole number of steps per compare interval, to the 6 digits results.csv keeps
  EXPECT_NEAR(0.005 / dt, std::round(0.005 / dt), 1e-5 * 0.005 / dt);
  // The reference's amplitude from its own probes.csv.
  const auto reference = test::read_records(dir / "out" / "reference" / "probes.csv");
  double amplitude = 0;
  for (const auto& row : reference) {
    double d2 = 0;
    for (const char* c : {"tip.pos_x", "tip.pos_y", "tip.pos_z"})
      d2 += std::pow(std::stod(row.at(c)) - std::stod(reference.front().at(c)), 2);
    amplitude = std::max(amplitude, std::sqrt(d2));
  }
  // Both errors are the same distance over d and over the amplitude: d = amplitude × ratio is
  // one value for every row, the particles' bounding-box diagonal (below the 1.01 m of the box).
  std::vector<double> diagonal;
  for (const auto& row : rows) {
    const double over_d = std::stod(row.at("probe_error"));
    const double over_amplitude = std::stod(row.at("probe_error_amplitude"));
    diagonal.push_back(over_amplitude * amplitude / over_d);
    std::printf("%s: probe error / amplitude %.3g, amplitude %.3g m, implied d %.4g m\n",
                row.at("run").c_str(), over_amplitude, amplitude, diagonal.back());
  }
  EXPECT_NEAR(diagonal[0], diagonal[1], 1e-5 * diagonal[1]);  // 6 digits per CSV value
  EXPECT_GT(diagonal[0], 0.8);
  EXPECT_LT(diagonal[0], 1.01);
  const double verlet = std::stod(rows[0].at("probe_error_amplitude"));
  const double coarse = std::stod(rows[1].at("probe_error_amplitude"));
  EXPECT_LT(verlet, 0.05);
  // two backward Euler steps over the first 10 ms of the fall from rest: first order, far off
  EXPECT_GT(coarse, 0.05);
  const std::string md = test::slurp(dir / "out" / "results.md");
  EXPECT_NE(md.find("| velocity_verlet | "), std::string::npos) << md;
  EXPECT_NE(md.find("| coarse | none within the target |"), std::string::npos) << md;
  EXPECT_NE(outcome.output.find("speed-up over velocity_verlet"), std::string::npos);
}

// A study whose reference is a CSV of probe values (here the probes.csv of a VERNER_8_5_6 run):
// only probe errors are measured, and they fall with dt at symplectic Euler's order.
TEST(Study, ProbeCsvReferenceGivesProbeErrors) {
  const fs::path dir = test::scratch_dir("study_csv");
  const std::string scene = std::string(FISSURE_SOURCE_DIR) + "/configs/compare/bar_swing.yaml";
  const auto reference = test::run_fissure(
      "run " + scene + " --out " + (dir / "reference").string() +
      " --set time.end=0.01 --set bodies[0].resolution=0.1 --set output.every=0.005 " +
      "--set integrator.type=arkode --set integrator.method=VERNER_8_5_6 " +
      "--set integrator.rtol=1e-12 --set integrator.atol=1e-15");
  ASSERT_EQ(reference.exit_code, 0) << reference.output;
  test::write_file(dir / "csv.yaml",
                   "scene: " + scene +
                       "\nset: [\"time.end=0.01\", \"bodies[0].resolution=0.1\"]\nevery: 0.005\n"
                       "reference: {probes: reference/probes.csv}\nruns:\n"
                       "  - {name: symplectic_euler, integrator: {type: symplectic_euler}, dt: "
                       "[1.0e-5, 5.0e-6]}\noutput: {dir: " +
                       (dir / "out").string() + "}\n");
  const auto outcome = test::run_fissure("study " + (dir / "csv.yaml").string());
  ASSERT_EQ(outcome.exit_code, 0) << outcome.output;
  const auto rows = test::read_records(dir / "out" / "results.csv");
  ASSERT_EQ(rows.size(), 2u);
  for (const auto& row : rows) {
    EXPECT_EQ(row.at("status"), "ok");
    EXPECT_TRUE(row.at("error_max").empty());
  }
  const double coarse = std::stod(rows[0].at("probe_error")),
               fine = std::stod(rows[1].at("probe_error"));
  std::printf("probe errors %.3g, %.3g: order %.2f\n", coarse, fine, std::log2(coarse / fine));
  EXPECT_NEAR(std::log2(coarse / fine), 1.0, 0.3);
}

// --out replaces the study file's output.dir and --set its keys, as on fissure run: here the
// file's two-step sweep becomes one step, and nothing is written where the file points.
TEST(Study, OutAndSetOnTheCommandLine) {
  const fs::path dir = test::scratch_dir("study_cli");
  const std::string scene = std::string(FISSURE_SOURCE_DIR) + "/configs/compare/bar_swing.yaml";
  test::write_file(dir / "cli.yaml",
                   "scene: " + scene +
                       "\nset: [\"time.end=0.01\", \"bodies[0].resolution=0.1\"]\n"
                       "reference: {integrator: {type: velocity_verlet}, dt: 2.5e-6}\nruns:\n"
                       "  - {name: velocity_verlet, integrator: {type: velocity_verlet}, dt: "
                       "[2.0e-5, 1.0e-5]}\noutput: {dir: " +
                       (dir / "from_file").string() + "}\n");
  const auto outcome =
      test::run_fissure("study " + (dir / "cli.yaml").string() + " --out " +
                        (dir / "from_cli").string() + " --set 'runs[0].dt=[1.0e-5]'");
  ASSERT_EQ(outcome.exit_code, 0) << outcome.output;
  EXPECT_NE(outcome.output.find("in " + (dir / "from_cli").string()), std::string::npos)
      << outcome.output;
  EXPECT_FALSE(fs::exists(dir / "from_file"));
  const auto rows = test::read_records(dir / "from_cli" / "results.csv");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].at("status"), "ok");
  EXPECT_EQ(rows[0].at("dt"), "1e-05");
  EXPECT_TRUE(fs::exists(dir / "from_cli" / "reference" / "probes.csv"));
  // A --set naming a key the study file does not have is refused like one in the file.
  const auto bad = test::run_fissure("study " + (dir / "cli.yaml").string() + " --set evry=0.005");
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("evry: unknown key; did you mean 'every'?"), std::string::npos)
      << bad.output;
}

TEST(Study, BadStudyFileNamesFileAndKey) {
  const fs::path dir = test::scratch_dir("study_bad");
  test::write_file(dir / "bad.yaml",
                   "scene: nowhere.yaml\nreference: {integrator: {type: "
                   "velocity_verlet}}\nruns: []\n");
  const auto outcome = test::run_fissure("study " + (dir / "bad.yaml").string());
  EXPECT_EQ(outcome.exit_code, 2);
  EXPECT_NE(outcome.output.find("bad.yaml"), std::string::npos) << outcome.output;
  EXPECT_NE(outcome.output.find("reference.dt"), std::string::npos) << outcome.output;
}

}  // namespace
}  // namespace fissure
