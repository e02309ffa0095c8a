// `fissure render`: a tiny run becomes PNG pictures that show something, and the errors name
// what is wrong (exit code 2 for a bad folder, 3 when the renderer is missing).
#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include "app/run_fissure.hpp"
#include "io/external_program.hpp"
#include "support/png_pixels.hpp"

namespace fissure {
namespace {

const char* kTinyWall =
    "time: {end: 0.002}\n"
    "bodies:\n"
    "  - geometry: {box: {min: [0, 0, 0], max: [0.4, 0.05, 0.4]}}\n"
    "    resolution: 0.05\n"
    "    material: {density: 2200, bulk_modulus: 3.3e8, shear_modulus: 2.0e8,\n"
    "               fracture: {critical_stretch: 0.002}}\n"
    "constraints:\n"
    "  - {region: {box: {min: [-1, -1, -1], max: [2, 2, 0.03]}}, fix: true}\n"
    "colliders:\n"
    "  - {sphere: {center: [0.2, -0.06, 0.2], radius: 0.05}, velocity: [0, 40, 0], mass: 5}\n"
    "output: {every: 0.001}\n";

TEST(Render, PicturesOfATinyRunShowTheParticles) {
  if (find_program("povray").empty()) GTEST_SKIP() << "povray is not installed";
  const auto dir = test::scratch_dir("render");
  test::write_file(dir / "wall.yaml", kTinyWall);
  const auto out = dir / "out";
  const auto run =
      test::run_fissure("run " + (dir / "wall.yaml").string() + " --out " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto render = test::run_fissure("render " + out.string() +
                                        " --set render.width=160 --set render.height=120 "
                                        "--set render.animation=none --field velocity");
  ASSERT_EQ(render.exit_code, 0) << render.output;
  EXPECT_NE(render.output.find("rendered 3 frames"), std::string::npos) << render.output;
  for (const char* name : {"frame_000000.png", "frame_000001.png", "frame_000002.png"}) {
    const test::Image image = test::read_png((out / "render" / name).string());
    ASSERT_EQ(image.width, 160) << name;
    ASSERT_EQ(image.height, 120) << name;
    // Background, floor, shading and the colour map: many colours, and a good share of the
    // picture differs from the background in the corner.
    const std::set<std::uint32_t> colours(image.rgb.begin(), image.rgb.end());
    EXPECT_GT(colours.size(), 50u) << name;
    long differing = 0;
    for (const auto c : image.rgb) differing += c != image.rgb.front();
    EXPECT_GT(differing, static_cast<long>(image.rgb.size() / 20)) << name;
  }
  // --out puts the pictures elsewhere; render.every=2 of 3 frames draws the first and the last.
  const auto elsewhere =
      test::run_fissure("render " + out.string() + " --out " + (dir / "pictures").string() +
                        " --set render.width=80 --set render.height=60 "
                        "--set render.animation=none --set render.every=2");
  ASSERT_EQ(elsewhere.exit_code, 0) << elsewhere.output;
  EXPECT_NE(elsewhere.output.find("rendered 2 frames to " + (dir / "pictures").string()),
            std::string::npos)
      << elsewhere.output;
  for (const char* name : {"frame_000000.png", "frame_000002.png"})
    EXPECT_EQ(test::read_png((dir / "pictures" / name).string()).width, 80) << name;
  // The config's render block is read, and a bad value is named.
  test::write_file(dir / "bad.yaml", std::string(kTinyWall) + "render: {field: stress}\n");
  const auto bad =
      test::run_fissure("render " + out.string() + " --config " + (dir / "bad.yaml").string());
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("render.field"), std::string::npos) << bad.output;
}

TEST(Render, MissingFolderOrFramesIsBadInput) {
  const auto dir = test::scratch_dir("render_bad");
  const auto missing = test::run_fissure("render " + (dir / "nothing").string());
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_NE(missing.output.find("no such output folder"), std::string::npos) << missing.output;
  const auto empty = test::run_fissure("render " + dir.string());
  EXPECT_EQ(empty.exit_code, 2) << empty.output;
  EXPECT_NE(empty.output.find("particles.pvd"), std::string::npos) << empty.output;
}

TEST(Render, MissingRendererNamesThePackage) {
  const auto dir = test::scratch_dir("render_no_povray");
  test::write_file(dir / "wall.yaml", kTinyWall);
  const auto out = dir / "out";
  ASSERT_EQ(
      test::run_fissure("run " + (dir / "wall.yaml").string() + " --out " + out.string()).exit_code,
      0);
  const std::string command = "PATH=" + (dir / "empty").string() + " " + FISSURE_BINARY +
                              " render " + out.string() + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  for (char buffer[512]; std::fgets(buffer, sizeof buffer, pipe);) output += buffer;
  const int status = pclose(pipe);
  EXPECT_EQ(WEXITSTATUS(status), 3) << output;
  EXPECT_NE(output.find("install the Debian package 'povray'"), std::string::npos) << output;
}

}  // namespace
}  // namespace fissure
