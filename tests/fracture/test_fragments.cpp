// Fragments (connected components of intact bonds), and the α of Eq 19: a threshold that grows
// with damage leaves fewer, larger pieces than α = 0 on the same shattering wall.
#include <gtest/gtest.h>

#include <filesystem>

#include "app/simulation.hpp"
#include "fracture/bond_breaking.hpp"
#include "fracture/fragments.hpp"
#include "model/model.hpp"
#include "support/scenes.hpp"

namespace fissure {
namespace {

long fragments_of_block(const std::string& cracks) {
  const Scene scene = test::block_scene({.size = {0.2, 0.1, 0.1},
                                         .resolution = 0.025,
                                         .bulk = 1.0e6,
                                         .shear = 1.0e6,
                                         .material = ", fracture: {critical_stretch: 1}",
                                         .scene = cracks});
  auto model = make_model(scene);
  const BondBreaking breaking(scene, *model);  // removes the bonds crossing the cracks
  return count_fragments(scene.families, *model);
}

TEST(Fragments, CracksThroughTheBlockSplitIt) {
  EXPECT_EQ(fragments_of_block(""), 1);
  EXPECT_EQ(
      fragments_of_block("initial_cracks:\n  - {plane: {point: [0.1, 0, 0], normal: [1, 0, 0]}}\n"),
      2);
  EXPECT_EQ(
      fragments_of_block("initial_cracks:\n  - {plane: {point: [0.1, 0, 0], normal: [1, 0, 0]}}\n"
                         "  - {plane: {point: [0, 0.05, 0], normal: [0, 1, 0]}}\n"),
      4);
}

long fragments_of_shot_wall(double alpha) {
  const auto out = std::filesystem::temp_directory_path() /
                   ("fissure_test_fragments_alpha_" + std::to_string(alpha));
  const std::string yaml = fmt::format(
      "time: {{end: 0.002}}\n"
      "bodies:\n"
      "  - geometry: {{box: {{min: [0, 0, 0], max: [0.4, 0.05, 0.4]}}}}\n"
      "    resolution: 0.035\n"
      "    material: {{density: 2200, bulk_modulus: 3.3e8, shear_modulus: 2.0e8,\n"
      "               fracture: {{critical_stretch: 0.002, alpha: {}}}}}\n"
      "constraints:\n"
      "  - {{region: {{box: {{min: [-1, -1, -1], max: [2, 2, 0.03]}}}}, fix: true}}\n"
      "colliders:\n"
      "  - {{sphere: {{center: [0.2, -0.06, 0.2], radius: 0.05}}, velocity: [0, 40, 0], mass: "
      "5}}\n"
      "output: {{dir: {}, every: 0.002}}\n",
      alpha, out.string());
  return run_simulation(parse_config(yaml, "wall.yaml"), {}).fragments;
}

TEST(Fragments, AlphaAboveZeroLeavesFewerFragments) {
  const long plain = fragments_of_shot_wall(0);
  const long mitigated = fragments_of_shot_wall(5);
  EXPECT_GT(plain, 20) << "the wall must shatter for the comparison to mean something";
  EXPECT_LT(mitigated, plain);
  EXPECT_GT(mitigated, 1);
}

}  // namespace
}  // namespace fissure
