// Every bad-input class gets one clear error naming file, key path and reason, and exit code 2;
// a run that turns non-finite stops with step, time and particle, and keeps its output.
#include <gtest/gtest.h>

#include "app/run_fissure.hpp"

namespace fissure {
namespace {

std::string scene(const std::string& geometry, const std::string& material_extra = "",
                  const std::string& body_extra = "") {
  return "time: {end: 0.001}\nbodies:\n  - geometry: " + geometry + "\n    resolution: 0.02\n" +
         body_extra + "    material: {density: 1000, bulk_modulus: 1.0e6, shear_modulus: 1.0e6" +
         material_extra + "}\n";
}

const std::string kBox = "{box: {min: [0, 0, 0], max: [0.1, 0.1, 0.1]}}";

struct BadCase {
  std::string name;
  std::string yaml;
  std::string args;      // extra CLI arguments
  std::string expected;  // substring of the message after the file name
};

class BadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadInput, ClearMessageAndExitCodeTwo) {
  const BadCase& c = GetParam();
  const auto dir = test::scratch_dir("bad_" + c.name);
  const auto config = dir / "scene.yaml";
  test::write_file(config, c.yaml);
  test::write_file(dir / "broken.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  test::write_file(dir / "empty.txt", "# no particles here\n");
  test::write_file(dir / "twins.txt", "0 0 0 1e-6\n0 0 0 1e-6\n0.01 0 0 1e-6\n");
  test::write_file(dir / "twins.txt", "0 0 0 1e-6\n0 0 0 1e-6\n0.01 0 0 1e-6\n");
  const auto outcome = test::run_fissure("info " + config.string() + " " + c.args);
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
  EXPECT_NE(outcome.output.find("error: "), std::string::npos) << outcome.output;
  EXPECT_NE(outcome.output.find(c.expected), std::string::npos)
      << "expected '" << c.expected << "' in: " << outcome.output;
  EXPECT_EQ(outcome.output.find('\n'), outcome.output.size() - 1) << "one line: " << outcome.output;
}

INSTANTIATE_TEST_SUITE_P(
    Classes, BadInput,
    ::testing::Values(
        BadCase{"unknown_key", scene(kBox, ", densty: 3"), "",
                "bodies[0].material.densty: unknown key; did you mean 'density'?"},
        BadCase{"wrong_type", scene(kBox), "--set bodies[0].horizon=wide",
                "bodies[0].horizon: expected a number, got 'wide'"},
        BadCase{"missing_mesh", scene("{mesh: {file: nowhere.obj}}"), "",
                "nowhere.obj: bodies[0].geometry:"},
        BadCase{"malformed_mesh", scene("{mesh: {file: broken.obj}}"), "",
                "broken.obj: bodies[0].geometry:"},
        BadCase{"density", scene(kBox), "--set bodies[0].material.density=-1",
                "bodies[0].material.density: must be positive"},
        BadCase{"bulk_modulus", scene(kBox), "--set bodies[0].material.bulk_modulus=0",
                "bodies[0].material.bulk_modulus: must be positive"},
        BadCase{"shear_modulus", scene(kBox), "--set bodies[0].material.shear_modulus=-5",
                "bodies[0].material.shear_modulus: must be positive"},
        BadCase{"resolution", scene(kBox), "--set bodies[0].resolution=0",
                "bodies[0].resolution: must be positive"},
        BadCase{"horizon", scene(kBox), "--set bodies[0].horizon=0",
                "bodies[0].horizon: must be positive"},
        BadCase{"no_particles", scene("{points: {file: empty.txt}}"), "",
                "empty.txt: bodies[0].geometry: the points file holds no particles"},
        BadCase{"integrator", scene(kBox), "--set integrator.type=verlet",
                "integrator.type: unknown integrator 'verlet'"},
        BadCase{"duplicate_key", scene(kBox, ", density: 5"), "",
                "bodies[0].material.density: duplicate key"},
        BadCase{"list_as_key", scene(kBox) + "[1, 2]: 3\n", "",
                "a key must be a plain name, not a list or map"},
        BadCase{"empty_family", scene(kBox), "--set bodies[0].horizon=0.05",
                "bodies[0].horizon: the particle at"},
        BadCase{"coincident_points", scene("{points: {file: twins.txt}}"), "",
                "bodies[0].geometry: two particles at"},
        BadCase{"huge_mesh", scene(kBox), "--set bodies[0].resolution=1e-5",
                "scene.yaml: bodies[0].resolution: edge length"},
        BadCase{"probe_name",
                scene(kBox) + "probes:\n  - {name: 'a,b', region: {sphere: {center: [0, 0, 0], "
                              "radius: 1}}}\n",
                "", "probes[0].name: use letters, digits"},
        BadCase{"empty_output_dir", scene(kBox), "--set \"output.dir=''\"",
                "output.dir: must not be empty"},
        BadCase{"static_load_ramp", scene(kBox),
                "--set integrator.type=petsc_newton --set integrator.scheme=static "
                "--set integrator.steps=4 --set time.dt=0.001",
                "scene.yaml: time.dt: 0.001 s reaches time.end = 0.001 s in 1 load increment(s), "
                "but integrator.steps = 4 ramps the loads over 4 increments: the run would end at "
                "0.25 of the load"},
        BadCase{"index_overflow", scene(kBox), "--set bodies[99999999999999999999].x=1",
                "index 99999999999999999999 out of range"}),
    [](const auto& info) { return info.param.name; });

TEST(BadInput, MissingConfigFile) {
  const auto outcome = test::run_fissure("run /nonexistent/scene.yaml");
  EXPECT_EQ(outcome.exit_code, 2);
  EXPECT_NE(outcome.output.find("/nonexistent/scene.yaml: cannot open the config file"),
            std::string::npos)
      << outcome.output;
}

// `mpirun -np 2 fissure run`: an explicit integrator runs over both ranks (rank 0 speaks,
// summary.json records the ranks, frames are .pvtu, which fissure render reads); an integrator that cannot be spread over
// ranks yet is refused before the output folder is touched, with exit code 2, the key, and one
// message, not one per rank; `fissure study` runs on one rank only (docs/mpi.md).
TEST(BadInput, WhatCannotRunOnSeveralRanksIsRefusedBeforeAnythingIsWritten) {
  const auto dir = test::scratch_dir("ranks");
  test::write_file(dir / "scene.yaml", scene(kBox));
  const auto out = dir / "out";
  auto on_two_ranks = [](const std::string& args) {
    return test::run_shell(
        "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1 mpirun -np 2 "
        "--oversubscribe " +
        std::string(FISSURE_BINARY) + " " + args);
  };
  const auto refused = on_two_ranks("run " + (dir / "scene.yaml").string() + " --out " +
                                    out.string() + " --set integrator.type=arkode --set integrator.method=SDIRK_2_1_2 " +
                                    "--set integrator.preconditioner=tangent");
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  const std::string expected =
      "scene.yaml: integrator.preconditioner: 'arkode' cannot run over several ranks yet";
  const auto first = refused.output.find(expected);
  EXPECT_NE(first, std::string::npos) << refused.output;
  EXPECT_EQ(refused.output.find(expected, first + 1), std::string::npos) << refused.output;
  EXPECT_FALSE(std::filesystem::exists(out));
  const auto study = on_two_ranks("study " + (dir / "study.yaml").string());
  EXPECT_EQ(study.exit_code, 2) << study.output;
  EXPECT_NE(study.output.find("fissure study was started on 2 MPI ranks"), std::string::npos)
      << study.output;

  const auto spread = on_two_ranks("run " + (dir / "scene.yaml").string() + " --out " +
                                   out.string() + " --set integrator.type=velocity_verlet");
  EXPECT_EQ(spread.exit_code, 0) << spread.output;
  const auto line = spread.output.find(" particles, ");  // the run's line, from rank 0 only
  EXPECT_NE(line, std::string::npos) << spread.output;
  EXPECT_EQ(spread.output.find(" particles, ", line + 1), std::string::npos) << spread.output;
  EXPECT_NE(test::slurp(out / "summary.json").find("\"ranks\": 2"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(out / "particles_000000.pvtu"));
  EXPECT_TRUE(std::filesystem::exists(out / "particles_000000_p1.vtu"));
  // fissure render reads the .pvtu frames particles.pvd lists (the first and the last here)
  const auto render = test::run_fissure("render " + out.string() +
                                        " --set render.every=100 --set render.width=160 "
                                        "--set render.height=120");
  EXPECT_EQ(render.exit_code, 0) << render.output;
  EXPECT_TRUE(std::filesystem::exists(out / "render" / "frame_000000.png")) << render.output;
}

// An integrator option the scene cannot use fails before the output folder is touched: exit 2,
// the key path, and an earlier run's output still in place (clear_previous_output would have
// removed it; before Integrator::check it failed in the first step, after the first frame).
TEST(BadInput, IntegratorOptionsFailBeforeAnythingIsWritten) {
  const auto dir = test::scratch_dir("integrator_check");
  const auto config = dir / "scene.yaml";
  test::write_file(config, scene(kBox, ", model: paper"));
  const std::pair<std::string, std::string> cases[] = {
      {"--set integrator.type=petsc_newton",
       "scene.yaml: integrator.type: material.model 'paper' provides no stiffness"},
      {"--set integrator.type=arkode --set integrator.method=SDIRK_2_1_2",
       "scene.yaml: integrator.method: 'SDIRK_2_1_2' is implicit, and material.model 'paper'"}};
  for (const auto& [args, expected] : cases) {
    const auto out = dir / "out";
    std::filesystem::create_directories(out);
    test::write_file(out / "probes.csv", "an earlier run's probes\n");
    const auto outcome =
        test::run_fissure("run " + config.string() + " --out " + out.string() + " " + args);
    EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
    EXPECT_NE(outcome.output.find(expected), std::string::npos) << outcome.output;
    EXPECT_EQ(test::slurp(out / "probes.csv"), "an earlier run's probes\n");
    EXPECT_FALSE(std::filesystem::exists(out / "particles.pvd")) << args;
    EXPECT_FALSE(std::filesystem::exists(out / "summary.json")) << args;
  }
}

// dt far above the stable step with the energy-growth check off: the run stops at the first
// non-finite state with step, time and particle, exit code 3, and the probes and frames written
// so far stay on disk (the safety net behind the energy check, tests/stability/).
TEST(BadInput, NonFiniteStateStopsWithStepTimeAndParticle) {
  const auto dir = test::scratch_dir("nonfinite");
  const auto config = dir / "scene.yaml";
  test::write_file(config,
                   scene(kBox) + "gravity: [0, 0, -9.81]\n" +
                       "constraints:\n  - {region: {box: {min: [-1, -1, -1], max: [0.02, 1, 1]}}, "
                       "fix: true}\n" +
                       "probes:\n  - {name: all, region: {box: {min: [-1, -1, -1], "
                       "max: [1, 1, 1]}}}\n" +
                       "output: {every: 1.0e-6, probe_every: 1.0e-6}\n");
  const auto out = dir / "out";
  const auto outcome = test::run_fissure("run " + config.string() + " --out " + out.string() +
                                         " --set time.dt=1e-2 --set time.end=1.0" +
                                         " --set integrator.allow_unstable_dt=true" +
                                         " --set integrator.energy_growth_limit=0");
  EXPECT_EQ(outcome.exit_code, 3) << outcome.output;
  EXPECT_NE(outcome.output.find("warning: "), std::string::npos) << outcome.output;
  EXPECT_NE(outcome.output.find("state became non-finite at step"), std::string::npos)
      << outcome.output;
  EXPECT_NE(outcome.output.find("first at particle"), std::string::npos) << outcome.output;
  EXPECT_TRUE(std::filesystem::exists(out / "probes.csv"));
  EXPECT_TRUE(std::filesystem::exists(out / "particles.pvd"));
  EXPECT_TRUE(std::filesystem::exists(out / "particles_000000.vtu"));
  std::ifstream summary(out / "summary.json");
  const std::string text((std::istreambuf_iterator<char>(summary)), {});
  EXPECT_NE(text.find("\"status\": \"nonfinite\""), std::string::npos) << text;
}

}  // namespace
}  // namespace fissure
