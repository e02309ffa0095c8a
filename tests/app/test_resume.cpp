// Checkpoint and restart: a run killed with SIGKILL and resumed with `fissure run --resume` ends
// bitwise equal to the same run left alone (same thread count: OpenMP reductions with a static
// schedule add in a fixed order), losing at most one checkpoint interval when killed.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>

#include "app/run_fissure.hpp"
#include "app/same_outputs.hpp"
#include "io/checkpoint_file.hpp"

extern char** environ;

namespace fissure {
namespace {

namespace fs = std::filesystem;

// A clamped bar, plastic and brittle, hit by a dynamic sphere: fracture, plasticity, a collider
// and the crack surfaces all carry state from step to step.
const char* kScene = R"(
time: {end: 0.01, dt: auto}
gravity: [0, 0, -9.81]
bodies:
  - geometry: {box: {min: [0, 0, 0], max: [0.3, 0.05, 0.05]}}
    resolution: 0.0125
    material:
      density: 1000
      bulk_modulus: 1.0e6
      shear_modulus: 5.0e5
      fracture: {critical_stretch: 0.002}
      plasticity: {yield_stress: 2.0e3, max_plastic_stretch: 0.05}
constraints:
  - {region: {box: {min: [-1, -1, -1], max: [0.02, 1, 1]}}, fix: true}
colliders:
  - {sphere: {center: [0.2, 0.025, 0.12], radius: 0.04}, velocity: [0, 0, -10], mass: 1}
output: {every: 0.002, probe_every: 0.0005, checkpoint_every: 0.002, surface: true}
)";

// Runs `fissure run config --out dir` in the background and kills it with SIGKILL once its first
// checkpoint is on disk and a few more probe rows were written after it.
void run_and_kill(const fs::path& config, const fs::path& dir) {
  const std::string binary = FISSURE_BINARY, config_path = config.string(), out = dir.string();
  std::vector<char*> argv = {const_cast<char*>(binary.c_str()),      const_cast<char*>("run"),
                             const_cast<char*>(config_path.c_str()), const_cast<char*>("--out"),
                             const_cast<char*>(out.c_str()),         nullptr};
  pid_t pid;
  ASSERT_EQ(posix_spawn(&pid, binary.c_str(), nullptr, nullptr, argv.data(), environ), 0);
  const auto checkpoint = dir / "checkpoint.bin";
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  while (!fs::exists(checkpoint) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_TRUE(fs::exists(checkpoint)) << "no checkpoint within 5 minutes";
  const auto rows_at_checkpoint = fs::file_size(dir / "probes.csv");
  while (fs::file_size(dir / "probes.csv") < rows_at_checkpoint + 200 &&
         std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the run ended before it was killed";
}

TEST(Resume, KilledRunResumesToTheSameBitsAsAnUninterruptedOne) {
  setenv("OMP_NUM_THREADS", "2", 1);
  const auto dir = test::scratch_dir("resume_kill");
  const auto config = dir / "bar.yaml";
  test::write_file(config, kScene);
  const auto reference = dir / "reference", killed = dir / "killed";
  const auto whole = test::run_fissure("run " + config.string() + " --out " + reference.string());
  ASSERT_EQ(whole.exit_code, 0) << whole.output;

  run_and_kill(config, killed);
  ASSERT_FALSE(fs::exists(killed / "summary.json"));
  // What the kill lost: the rows after the checkpoint, less than one interval of them.
  const CheckpointReader checkpoint((killed / "checkpoint.bin").string());
  const std::string probes = test::slurp(killed / "probes.csv");
  const std::string last_row = probes.substr(probes.rfind('\n', probes.size() - 2) + 1);
  const double last_time = std::stod(last_row), checkpoint_time = checkpoint.number("run.time");
  std::printf("killed at t = %.5f s, last checkpoint at t = %.5f s (interval 0.002 s)\n", last_time,
              checkpoint_time);
  EXPECT_LE(last_time - checkpoint_time, 0.002 + 1e-4);

  const auto resumed = test::run_fissure("run --resume " + killed.string());
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  test::expect_same_outputs(killed, reference);
}

// The other integrators with state between steps (velocity Verlet's acceleration, Newmark's)
// resume bitwise too, on a coarser bar, from the one checkpoint of a finished run at 0.006 s of
// 0.01 s: the resume takes the last 40% of the steps again and must land on the same bits.
TEST(Resume, VerletAndNewmarkResumeFromAnEarlyCheckpointBitwise) {
  setenv("OMP_NUM_THREADS", "2", 1);
  for (const std::string integrator : {"--set integrator.type=velocity_verlet",
                                       "--set integrator.type=petsc_newton --set "
                                       "integrator.scheme=newmark --set time.dt=0.0005"}) {
    const auto dir = test::scratch_dir("resume_integrators");
    const auto config = dir / "bar.yaml";
    test::write_file(config, kScene);
    const auto reference = dir / "reference", resumed = dir / "resumed";
    const auto whole = test::run_fissure("run " + config.string() + " --out " + reference.string() +
                                         " --set 'bodies[0].resolution=0.025' " +
                                         "--set output.checkpoint_every=0.006 " + integrator);
    ASSERT_EQ(whole.exit_code, 0) << whole.output;
    fs::copy(reference, resumed);
    const CheckpointReader checkpoint((resumed / "checkpoint.bin").string());
    const double checkpoint_time = checkpoint.number("run.time");
    const long checkpoint_steps = std::lround(checkpoint.number("run.steps"));
    const auto again = test::run_fissure("run --resume " + resumed.string());
    ASSERT_EQ(again.exit_code, 0) << again.output;
    const long steps = std::stol(test::read_summary(resumed / "summary.json").at("steps"));
    std::printf("%s: checkpoint at t = %.5f s, step %ld of %ld: the resume took %ld steps\n",
                integrator.c_str(), checkpoint_time, checkpoint_steps, steps,
                steps - checkpoint_steps);
    EXPECT_GE(checkpoint_time, 0.006 - 1e-9);  // the first step at or past 0.006 s
    EXPECT_LT(checkpoint_time, 0.0065);
    EXPECT_GE(steps - checkpoint_steps, steps / 3);
    test::expect_same_outputs(resumed, reference);
  }
}

TEST(Resume, DamagedCheckpointIsAClearError) {
  const auto dir = test::scratch_dir("resume_damaged");
  test::write_file(dir / "checkpoint.bin", "FISSCKPT\x01");
  const auto outcome = test::run_fissure("run --resume " + dir.string());
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
  EXPECT_NE(outcome.output.find((dir / "checkpoint.bin").string()), std::string::npos)
      << outcome.output;
  EXPECT_NE(outcome.output.find("truncated"), std::string::npos) << outcome.output;
  const auto none = test::run_fissure("run --resume " + (dir / "nowhere").string());
  EXPECT_EQ(none.exit_code, 2) << none.output;
  EXPECT_NE(none.output.find("no checkpoint"), std::string::npos) << none.output;
}

}  // namespace
}  // namespace fissure
