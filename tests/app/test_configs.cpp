// Every scene in configs/ (and its subfolders, e.g. compare/) loads, samples and reports its cost
// through `fissure info`.
#include <gtest/gtest.h>

#include <filesystem>

#include "app/run_fissure.hpp"

namespace fissure {
namespace {

TEST(Configs, EveryShippedSceneLoads) {
  int scenes = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(
           std::string(FISSURE_SOURCE_DIR) + "/configs")) {
    if (entry.path().extension() != ".yaml") continue;
    ++scenes;
    const auto outcome = test::run_fissure("info " + entry.path().string());
    EXPECT_EQ(outcome.exit_code, 0) << entry.path() << ": " << outcome.output;
    EXPECT_NE(outcome.output.find("effects: elasticity"), std::string::npos) << entry.path();
  }
  EXPECT_GE(scenes, 3);
}

}  // namespace
}  // namespace fissure
