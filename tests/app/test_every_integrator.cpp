// One fracture scene of the gallery (glass_wall.yaml, coarsened) runs with every integrator, and
// every completed step went through the one shared post-step (bond breaking, damage, mesh
// splitting): summary.json's post_steps, counted inside PostStep, equals the steps taken.
#include <gtest/gtest.h>

#include <regex>
#include <string>

#include "app/run_fissure.hpp"

namespace fissure {
namespace {

struct IntegratorChoice {
  const char* label;
  const char* settings;  // --set arguments
};

class EveryIntegrator : public ::testing::TestWithParam<IntegratorChoice> {};

TEST_P(EveryIntegrator, GlassWallBreaksThroughTheSharedPostStep) {
  const auto dir = test::scratch_dir(std::string("every_integrator_") + GetParam().label);
  const std::string scene = std::string(FISSURE_SOURCE_DIR) + "/configs/glass_wall.yaml";
  const auto outcome = test::run_fissure(
      "run " + scene + " --out " + dir.string() +
      " --set bodies[0].resolution=0.1 --set time.end=0.002 --set output.every=0.0005 " +
      GetParam().settings);
  ASSERT_EQ(outcome.exit_code, 0) << outcome.output;
  const auto summary = test::read_summary(dir / "summary.json");
  const long steps = std::stol(summary.at("steps"));
  const long post_steps = std::stol(summary.at("post_steps"));
  const long broken = std::stol(summary.at("broken_bonds"));
  std::printf("%s: %ld steps, %ld post-steps, %ld broken bonds, %s s\n", GetParam().label, steps,
              post_steps, broken, summary.at("wall_seconds").c_str());
  EXPECT_GT(steps, 0);
  EXPECT_EQ(post_steps, steps);
  EXPECT_GT(broken, 0);
  EXPECT_TRUE(std::filesystem::exists(dir / "surface_000004.obj"));
  // petsc_newton reuses its factor across steps: broken bonds must have refreshed it.
  if (std::string(GetParam().label) == "petsc_newton") {
    const std::string text = test::slurp(dir / "summary.json");
    std::smatch m;
    ASSERT_TRUE(
        std::regex_search(text, m, std::regex(R"("refreshes_bonds_broken"\s*:\s*([0-9]+))")))
        << text;
    std::printf("petsc_newton: %s refreshes after bonds broke\n", m[1].str().c_str());
    EXPECT_GT(std::stol(m[1].str()), 0);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Integrators, EveryIntegrator,
    ::testing::Values(
        IntegratorChoice{"symplectic_euler", "--set integrator.type=symplectic_euler"},
        IntegratorChoice{"velocity_verlet", "--set integrator.type=velocity_verlet"},
        IntegratorChoice{"petsc_newton", "--set integrator.type=petsc_newton --set time.dt=2e-5"},
        IntegratorChoice{"arkode",
                         "--set integrator.type=arkode "
                         "--set integrator.method=DORMAND_PRINCE_7_4_5"}),
    [](const auto& info) { return std::string(info.param.label); });

}  // namespace
}  // namespace fissure
