// The checkpoint file format: what is written is read back exactly, and a damaged file is
// refused with a message that names it and says what is wrong.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "app/run_fissure.hpp"
#include "io/checkpoint_file.hpp"
#include "support/error_message.hpp"

namespace fissure {
namespace {

std::filesystem::path written_checkpoint(const std::string& name) {
  const auto path = test::scratch_dir("checkpoint_" + name) / "checkpoint.bin";
  CheckpointWriter w;
  w.add("config", std::string("time: {end: 1}\n"));
  w.add("state.position", std::vector<double>{1.0, -2.5, 1e-300, 3.0});
  w.add("state.broken", std::vector<std::uint8_t>{0, 1, 1, 0});
  w.add("model.weighted_volume", std::vector<double>{0.125});
  w.write(path.string());
  return path;
}

// The message of the InputError reading `path` throws, or "" if it reads.
std::string read_error(const std::filesystem::path& path) {
  return test::input_error_message([&] { CheckpointReader reader(path.string()); });
}

TEST(CheckpointFile, WhatIsWrittenIsReadBackExactly) {
  const auto path = written_checkpoint("round_trip");
  const CheckpointReader r(path.string());
  EXPECT_EQ(r.text("config"), "time: {end: 1}\n");
  EXPECT_EQ(r.doubles("state.position"), (std::vector<double>{1.0, -2.5, 1e-300, 3.0}));
  EXPECT_EQ(r.bytes("state.broken"), (std::vector<std::uint8_t>{0, 1, 1, 0}));
  EXPECT_EQ(r.number("model.weighted_volume"), 0.125);
  const NamedArrays model = r.arrays("model.");
  ASSERT_EQ(model.size(), 1u);
  EXPECT_EQ(model[0].first, "model.weighted_volume");
  const std::string missing = test::input_error_message([&] { r.doubles("state.velocity"); });
  ASSERT_NE(missing, "") << "a missing section was read";
  EXPECT_NE(missing.find("state.velocity"), std::string::npos) << missing;
  EXPECT_FALSE(std::filesystem::exists(path.string() + ".tmp"));
}

TEST(CheckpointFile, EveryTruncationIsRefused) {
  const auto path = written_checkpoint("truncated");
  const auto size = std::filesystem::file_size(path);
  const std::string whole = test::slurp(path);
  for (std::uintmax_t keep = 0; keep < size; ++keep) {
    test::write_file(path, whole.substr(0, keep));
    const std::string error = read_error(path);
    EXPECT_NE(error, "") << "truncated to " << keep << " of " << size << " bytes was accepted";
    EXPECT_NE(error.find(path.string()), std::string::npos) << error;
  }
}

TEST(CheckpointFile, EveryFlippedByteIsRefused) {
  const auto path = written_checkpoint("flipped");
  const std::string whole = test::slurp(path);
  for (std::size_t at = 0; at < whole.size(); ++at) {
    std::string damaged = whole;
    damaged[at] = static_cast<char>(damaged[at] ^ 0x10);
    test::write_file(path, damaged);
    EXPECT_NE(read_error(path), "") << "a flipped byte at " << at << " was accepted";
  }
  std::string damaged = whole;
  damaged[whole.size() / 2] ^= 1;
  test::write_file(path, damaged);
  EXPECT_NE(read_error(path).find("checksum"), std::string::npos) << read_error(path);
}

TEST(CheckpointFile, OtherFilesAndVersionsAreNamed) {
  const auto path = written_checkpoint("other");
  std::string text = test::slurp(path);
  text[8] = static_cast<char>(kCheckpointVersion + 1);  // the version follows the 8 magic bytes
  test::write_file(path, text);
  EXPECT_NE(read_error(path).find("format version"), std::string::npos) << read_error(path);
  test::write_file(path, "time: {end: 1}\n");
  EXPECT_NE(read_error(path).find("not a Fissure checkpoint"), std::string::npos);
  std::filesystem::remove(path);
  EXPECT_NE(read_error(path).find("no checkpoint"), std::string::npos) << read_error(path);
}

}  // namespace
}  // namespace fissure
