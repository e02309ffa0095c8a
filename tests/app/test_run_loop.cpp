// The run loop's observers (src/app/observer.hpp): each restores every array it saves to a
// checkpoint, a checkpoint of the earlier positional layout is refused with the file and the
// reason, and an observer's bad option fails before the output folder is touched.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "app/run_fissure.hpp"
#include "app/run_observers.hpp"
#include "io/checkpoint_file.hpp"

namespace fissure {
namespace {

namespace fs = std::filesystem;

// 30 particles: gravity, damping, a clamped end and a probe, checkpoints every 0.004 s.
const char* kScene = R"(
time: {end: 0.01, dt: auto}
gravity: [0, 0, -9.81]
damping: 5.0
bodies:
  - geometry: {box: {min: [0, 0, 0], max: [0.1, 0.02, 0.02]}}
    resolution: 0.02
    material: {density: 1000, bulk_modulus: 1.0e6, shear_modulus: 5.0e5}
constraints:
  - {region: {box: {min: [-1, -1, -1], max: [0.01, 1, 1]}}, fix: true}
probes:
  - {name: tip, region: {box: {min: [0.09, -1, -1], max: [1, 1, 1]}}}
output: {every: 0.002, probe_every: 0.0005, checkpoint_every: 0.004}
)";

using Sorted = std::map<std::string, std::vector<double>>;

Sorted sorted(const NamedArrays& arrays) { return {arrays.begin(), arrays.end()}; }

// A checkpoint's sections, each taken by one observer of a fresh run with every number lowered
// by 1 (so that no value equals a default), must come back unchanged from its saved_state():
// an observer that forgets to restore a field, or saves one under another observer's prefix,
// fails here.
TEST(RunLoop, EveryObserverRestoresEveryArrayItSaves) {
  const auto dir = test::scratch_dir("round_trip");
  test::write_file(dir / "bar.yaml", kScene);
  const auto run =
      test::run_fissure("run " + (dir / "bar.yaml").string() + " --out " + (dir / "run").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  fs::copy(dir / "run", dir / "restored");
  const CheckpointReader checkpoint((dir / "restored" / "checkpoint.bin").string());

  Config config = parse_config(checkpoint.text("config"), checkpoint.text("config.file"));
  config.output.dir = (dir / "restored").string();
  const Scene scene = build_scene(config);
  auto model = make_model(scene);
  Dynamics dynamics(scene, *model);
  PostStep post_step(scene, *model, true);
  auto integrator = make_integrator(config.integrator, config.file);
  State state{scene.particles.reference, scene.particles.velocity, checkpoint.number("run.time")};
  RunSummary summary;
  summary.dt = 1e-5;
  const RunRanks ranks(scene, MPI_COMM_NULL);
  const RunParts parts{config,      scene, *model,  dynamics, post_step,
                       *integrator, state, summary, ranks};
  RunObservers observers = make_run_observers(scene, dynamics, [] { return NamedArrays{}; });

  std::vector<std::string> prefixes = {"config", "run.",      "state.",     "post_step.",
                                       "model.", "dynamics.", "integrator."};
  for (const auto* list : {&observers.checks, &observers.outputs})
    for (const auto& observer : *list) {
      const std::string prefix = observer->name() + ".";
      prefixes.push_back(prefix);
      NamedArrays lowered = checkpoint.arrays(prefix);
      for (auto& [name, values] : lowered)
        for (double& v : values) v -= 1;
      observer->resume(parts, lowered);
      EXPECT_EQ(sorted(observer->saved_state()), sorted(lowered)) << observer->name();
      std::printf("%s: %zu arrays round-trip\n", observer->name().c_str(), lowered.size());
    }
  for (const std::string& name : checkpoint.names())
    EXPECT_TRUE(std::any_of(prefixes.begin(), prefixes.end(),
                            [&](const std::string& p) { return name.rfind(p, 0) == 0; }))
        << name << " belongs to no part of the run";
}

// The positional sections of the earlier layout (run.schedule, run.ledger, ...) are refused,
// naming the checkpoint and the section, before anything in the folder changes.
TEST(RunLoop, CheckpointWithThePositionalLayoutIsRefused) {
  const auto dir = test::scratch_dir("old_layout");
  CheckpointWriter w;
  w.add("config", std::string(kScene));
  w.add("config.file", (dir / "bar.yaml").string());
  w.add("run.time", std::vector<double>{0.004});
  w.add("run.steps", std::vector<double>{100});
  w.add("run.frames", std::vector<double>{3});
  w.add("run.frame_times", std::vector<double>{0, 0.002, 0.004});
  w.add("run.schedule", std::vector<double>{0.0045, 0.006, 0.008, 0.004, 0.004, 0.1});
  w.add("run.probes_bytes", std::vector<double>{10});
  w.add("run.ledger", std::vector<double>(11, 0.5));
  w.write((dir / "checkpoint.bin").string());
  test::write_file(dir / "probes.csv", "time,kinetic_energy\n0,0\n");
  const auto outcome = test::run_fissure("run --resume " + dir.string());
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
  for (const std::string& part : {(dir / "checkpoint.bin").string(), std::string("run.schedule"),
                                  std::string("earlier version")})
    EXPECT_NE(outcome.output.find(part), std::string::npos) << part << "\n" << outcome.output;
  EXPECT_EQ(test::slurp(dir / "probes.csv"), "time,kinetic_energy\n0,0\n");
}

// A probe region without particles is an input error (exit 2) that leaves an earlier run's
// files where they are.
TEST(RunLoop, BadProbeFailsBeforeTheOutputFolderIsTouched) {
  const auto dir = test::scratch_dir("bad_probe");
  std::string scene = kScene;
  scene.replace(scene.find("min: [0.09, -1, -1], max: [1, 1, 1]"), 35,
                "min: [5.0, 5.0, 5.0], max: [6, 6, 6]");
  test::write_file(dir / "bar.yaml", scene);
  const auto out = dir / "out";
  fs::create_directories(out);
  for (const char* name : {"probes.csv", "particles_000000.vtu", "particles.pvd", "summary.json"})
    test::write_file(out / name, name);
  const auto outcome =
      test::run_fissure("run " + (dir / "bar.yaml").string() + " --out " + out.string());
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
  EXPECT_NE(outcome.output.find("probes[0].region"), std::string::npos) << outcome.output;
  for (const char* name : {"probes.csv", "particles_000000.vtu", "particles.pvd", "summary.json"})
    EXPECT_EQ(test::slurp(out / name), name) << name;
}

}  // namespace
}  // namespace fissure
