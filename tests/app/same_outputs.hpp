#pragma once
// A resumed run against the same run left alone: every output file bitwise equal, and the
// summary's counts.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>

#include "app/run_fissure.hpp"

namespace fissure::test {

// Every output file of a finished run but the summary (its wall times differ) and the
// checkpoint, with its bytes.
inline std::map<std::string, std::string> outputs(const std::filesystem::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name != "summary.json" && name != "checkpoint.bin") files[name] = slurp(entry.path());
  }
  return files;
}

inline void expect_same_outputs(const std::filesystem::path& resumed,
                                const std::filesystem::path& reference) {
  const auto a = outputs(resumed), b = outputs(reference);
  ASSERT_EQ(a.size(), b.size());
  for (const auto& [name, bytes] : b) {
    ASSERT_TRUE(a.count(name)) << name << " missing after the resume";
    EXPECT_TRUE(a.at(name) == bytes) << name << " differs from the uninterrupted run";
  }
  const auto s = read_summary(resumed / "summary.json");
  const auto r = read_summary(reference / "summary.json");
  for (const char* key :
       {"steps", "post_steps", "force_evaluations", "broken_bonds", "energy_drift"})
    EXPECT_EQ(s.at(key), r.at(key)) << key;
}

}  // namespace fissure::test
