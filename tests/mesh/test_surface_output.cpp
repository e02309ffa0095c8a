// Surface and tet output of a run: the files docs/output.md names, written per frame
// only when asked for, and removed by the next run.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "app/run_fissure.hpp"

namespace fissure::test {
namespace {

namespace fs = std::filesystem;

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The effects `fissure info` prints on its line "effects: a, b, ...".
std::string effects_of(const std::string& info) {
  const std::string key = "effects: ";
  const std::size_t begin = info.find(key);
  if (begin == std::string::npos) return "";
  const std::size_t end = info.find('\n', begin);
  return info.substr(begin + key.size(), end - begin - key.size());
}

// A small fracturing box pulled apart at both ends, three frames.
std::string scene_yaml(const std::string& output) {
  return "name: pulled\n"
         "time: {end: 0.002, dt: 1e-5}\n"
         "bodies:\n"
         "  - geometry: {box: {min: [0, 0, 0], max: [0.3, 0.1, 0.1]}}\n"
         "    resolution: 0.05\n"
         "    material: {density: 1000, bulk_modulus: 1e6, shear_modulus: 1e6,\n"
         "               fracture: {critical_stretch: 0.001}}\n"
         "constraints:\n"
         "  - {region: {box: {min: [-1, -1, -1], max: [0.05, 1, 1]}}, velocity: [-5, 0, 0]}\n"
         "  - {region: {box: {min: [0.25, -1, -1], max: [1, 1, 1]}}, velocity: [5, 0, 0]}\n"
         "output: {every: 0.001" +
         output + "}\n";
}

TEST(SurfaceOutput, WritesSurfaceAndTetFramesWhenAskedAndNothingOtherwise) {
  const fs::path dir = scratch_dir("surface_output");
  write_file(dir / "scene.yaml", scene_yaml(", surface: true, tets: true"));
  // `fissure info` lists the surface and tet outputs among the scene's effects.
  const Outcome info = run_fissure("info " + (dir / "scene.yaml").string());
  EXPECT_EQ(effects_of(info.output), "elasticity, fracture, surface, tets") << info.output;
  const Outcome run =
      run_fissure("run " + (dir / "scene.yaml").string() + " --out " + (dir / "out").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  for (const char* name : {"surface.pvd", "tets.pvd", "surface_000000.vtu", "surface_000000.obj",
                           "tets_000000.vtu", "surface_000002.vtu", "surface_000002.obj"})
    EXPECT_TRUE(fs::exists(dir / "out" / name)) << name;
  // The OBJ's faces refer to its vertices; the last frame has crack faces in group `crack`.
  const std::string obj = read(dir / "out" / "surface_000002.obj");
  std::istringstream lines(obj);
  std::string line;
  long vertices = 0, faces = 0, crack_faces = 0, largest = 0;
  bool in_crack = false;
  while (std::getline(lines, line)) {
    if (line.rfind("v ", 0) == 0) ++vertices;
    if (line.rfind("g ", 0) == 0) in_crack = line == "g crack";
    if (line.rfind("f ", 0) == 0) {
      ++faces;
      crack_faces += in_crack;
      std::istringstream f(line.substr(2));
      for (long i; f >> i;) largest = std::max(largest, i);
    }
  }
  EXPECT_GT(faces, 0);
  EXPECT_GT(crack_faces, 0);
  EXPECT_LE(largest, vertices);
  const std::string vtu = read(dir / "out" / "surface_000002.vtu");
  for (const char* array : {"Name=\"damage\"", "Name=\"body\"", "Name=\"crack\""})
    EXPECT_NE(vtu.find(array), std::string::npos) << array;
  // A run without surfaces writes none and removes the earlier run's.
  write_file(dir / "scene.yaml", scene_yaml(""));
  EXPECT_EQ(effects_of(run_fissure("info " + (dir / "scene.yaml").string()).output),
            "elasticity, fracture");
  const Outcome plain =
      run_fissure("run " + (dir / "scene.yaml").string() + " --out " + (dir / "out").string());
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  for (const auto& entry : fs::directory_iterator(dir / "out")) {
    const std::string name = entry.path().filename().string();
    EXPECT_TRUE(name.rfind("surface", 0) != 0 && name.rfind("tets", 0) != 0) << name;
  }
}

TEST(SurfaceOutput, RejectsAnUnknownSurfaceMotion) {
  const fs::path dir = scratch_dir("surface_motion");
  write_file(dir / "scene.yaml", scene_yaml(", surface: true, surface_motion: drift"));
  const Outcome info = run_fissure("info " + (dir / "scene.yaml").string());
  EXPECT_EQ(info.exit_code, 2);
  EXPECT_NE(info.output.find("output.surface_motion"), std::string::npos) << info.output;
}

}  // namespace
}  // namespace fissure::test
