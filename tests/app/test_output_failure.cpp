// Output that cannot be written stops the run with exit code 3 and a message naming the file and
// the reason; the last checkpoint stays intact and the run resumes from it to the same bits as a
// run that was never stopped. The file-size limit (ulimit -f) also binds root, which a read-only
// folder does not.
#include <gtest/gtest.h>

#include <cstdio>

#include "app/run_fissure.hpp"
#include "app/same_outputs.hpp"
#include "io/checkpoint_file.hpp"

namespace fissure {
namespace {

namespace fs = std::filesystem;

// 30 particles, 2,873 steps with a probes row at each: probes.csv grows to 245 kB while a
// frame is 4.3 kB and the checkpoint 2.7 kB.
const char* kScene = R"(
time: {end: 0.05, dt: auto}
gravity: [0, 0, -9.81]
bodies:
  - geometry: {box: {min: [0, 0, 0], max: [0.1, 0.02, 0.02]}}
    resolution: 0.02
    material: {density: 1000, bulk_modulus: 1.0e6, shear_modulus: 5.0e5}
constraints:
  - {region: {box: {min: [-1, -1, -1], max: [0.01, 1, 1]}}, fix: true}
output: {every: 0.01, probe_every: 1.0e-5, checkpoint_every: 0.01}
)";

// `fissure run config --out dir` with files limited to `kib` KiB (bash's ulimit -f counts KiB).
// The binary itself must turn the SIGXFSZ the limit raises into a failed write.
test::Outcome run_limited(int kib, const fs::path& config, const fs::path& dir) {
  return test::run_shell("bash -c 'ulimit -f " + std::to_string(kib) + " && exec " +
                         FISSURE_BINARY + " run " + config.string() + " --out " + dir.string() +
                         "'");
}

std::vector<std::string> temporary_files(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".tmp") names.push_back(entry.path().filename().string());
  return names;
}

// probes.csv reaches the 128 KiB limit at about t = 0.027 s, after the checkpoints at 0.01 and
// 0.02 s.
TEST(OutputFailure, FileSizeLimitStopsTheRunWhichResumesFromItsCheckpoint) {
  const auto dir = test::scratch_dir("fsize");
  const auto config = dir / "tiny.yaml";
  test::write_file(config, kScene);
  const auto reference = dir / "reference", limited = dir / "limited";
  const auto whole = test::run_fissure("run " + config.string() + " --out " + reference.string());
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  ASSERT_GT(fs::file_size(reference / "probes.csv"), 131072u);  // the limit falls mid-run

  const auto stopped = run_limited(128, config, limited);
  std::printf("%s", stopped.output.c_str());
  EXPECT_EQ(stopped.exit_code, 3) << stopped.output;
  EXPECT_NE(stopped.output.find("cannot write " + (limited / "probes.csv").string() +
                                ": write failed: File too large"),
            std::string::npos)
      << stopped.output;
  EXPECT_NE(stopped.output.find("fissure run --resume " + limited.string()), std::string::npos)
      << stopped.output;
  EXPECT_LE(fs::file_size(limited / "probes.csv"), 131072u);
  EXPECT_TRUE(temporary_files(limited).empty());
  EXPECT_EQ(test::read_summary(limited / "summary.json").at("status"), "\"failed\"");
  const CheckpointReader checkpoint((limited / "checkpoint.bin").string());
  std::printf("last checkpoint at t = %.5f s\n", checkpoint.number("run.time"));
  EXPECT_NEAR(checkpoint.number("run.time"), 0.02, 1e-4);

  const auto resumed = test::run_fissure("run --resume " + limited.string());
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  test::expect_same_outputs(limited, reference);
}

// Under 4 KiB not even the first frame (4.3 kB) fits: the message names it, says there is no
// checkpoint, and no temporary file is left behind.
TEST(OutputFailure, FrameOverTheLimitIsNamedAndLeavesNoTemporaryFile) {
  const auto dir = test::scratch_dir("fsize_frame");
  const auto config = dir / "tiny.yaml";
  test::write_file(config, kScene);
  const auto stopped = run_limited(4, config, dir / "out");
  EXPECT_EQ(stopped.exit_code, 3) << stopped.output;
  EXPECT_NE(stopped.output.find("cannot write " + (dir / "out" / "particles_000000.vtu").string()),
            std::string::npos)
      << stopped.output;
  EXPECT_NE(stopped.output.find("File too large"), std::string::npos) << stopped.output;
  EXPECT_NE(stopped.output.find("no checkpoint was written"), std::string::npos) << stopped.output;
  EXPECT_FALSE(fs::exists(dir / "out" / "particles_000000.vtu"));
  EXPECT_TRUE(temporary_files(dir / "out").empty());
}

}  // namespace
}  // namespace fissure
