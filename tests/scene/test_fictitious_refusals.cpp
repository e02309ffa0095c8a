// What surface_correction: fictitious (docs/model.md, deviation 8) cannot model is refused when the
// config is read, naming the key (config.cpp, check_fictitious_particles), beside the refusals of
// tests/model/test_second_order_model.cpp: the paper's model, a points body, anisotropy, and bodies
// that differ in model or in surface correction.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "scene/config.hpp"
#include "support/error_message.hpp"

namespace fissure {
namespace {

// A block with `material` appended to its material map, then `bodies` appended to the list.
std::string scene(const std::string& material, const std::string& bodies = "") {
  return fmt::format(
      "time: {{end: 1.0}}\nbodies:\n"
      "  - geometry: {{box: {{min: [0, 0, 0], max: [0.2, 0.05, 0.05]}}}}\n"
      "    resolution: 0.025\n"
      "    material: {{density: 1000, bulk_modulus: 2e6, shear_modulus: 1e6{}}}\n{}",
      material, bodies);
}

const std::string kFictitious = ", surface_correction: fictitious";

TEST(FictitiousRefusals, ThePapersModel) {
  test::expect_input_error([&] { parse_config(scene(kFictitious + ", model: paper"), "a.yaml"); },
                           "a.yaml",
                           "bodies[0].material.surface_correction: fictitious needs model: lps");
}

TEST(FictitiousRefusals, APointsBody) {
  const std::string yaml =
      "time: {end: 1.0}\nbodies:\n"
      "  - geometry: {points: {file: cloud.xyz}}\n"
      "    resolution: 0.025\n"
      "    material: {density: 1000, bulk_modulus: 2e6, shear_modulus: 1e6" +
      kFictitious + "}\n";
  test::expect_input_error([&] { parse_config(yaml, "a.yaml"); }, "a.yaml",
                           "bodies[0].geometry: surface_correction: fictitious needs a tet-sampled "
                           "body");
}

TEST(FictitiousRefusals, Anisotropy) {
  test::expect_input_error(
      [&] {
        parse_config(scene(kFictitious + ", anisotropy: {direction: [1, 0, 0], ratio: 2}"),
                     "a.yaml");
      },
      "a.yaml", "bodies[0].material.anisotropy: surface_correction: fictitious is isotropic only");
}

// The second body's key is named, whichever of the two differs.
TEST(FictitiousRefusals, BodiesThatDifferInModelOrSurfaceCorrection) {
  const std::string second =
      "  - geometry: {{box: {{min: [0, 0, 0.1], max: [0.2, 0.05, 0.15]}}}}\n"
      "    resolution: 0.025\n"
      "    material: {{density: 1000, bulk_modulus: 2e6, shear_modulus: 1e6{}}}\n";
  test::expect_input_error(
      [&] {
        parse_config(scene("", fmt::format(fmt::runtime(second), ", model: paper")), "a.yaml");
      },
      "a.yaml", "bodies[1].material.model: all bodies must use the same model");
  test::expect_input_error(
      [&] { parse_config(scene(kFictitious, fmt::format(fmt::runtime(second), "")), "a.yaml"); },
      "a.yaml",
      "bodies[1].material.surface_correction: all bodies must use the same surface_correction");
}

}  // namespace
}  // namespace fissure
