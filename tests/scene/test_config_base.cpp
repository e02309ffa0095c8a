// `base:` in scene files: a file starts from another one and overrides it key by key.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "app/run_fissure.hpp"
#include "integrators/petsc_newton_settings.hpp"
#include "integrators/registry.hpp"
#include "scene/config.hpp"
#include "support/error_message.hpp"

namespace fissure {
namespace {

namespace fs = std::filesystem;

// A folder of this test's own (test::scratch_dir names it after the test) with a sub-folder.
fs::path scratch() {
  const fs::path dir = test::scratch_dir("config_base");
  fs::create_directories(dir / "sub");
  return dir;
}

void write(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

const char* kBase =
    "time: {end: 1.0, dt: auto}\n"
    "integrator: {type: symplectic_euler}\n"
    "gravity: [0, 0, -9.81]\n"
    "bodies:\n"
    "  - geometry: {box: {min: [0, 0, 0], max: [1, 0.1, 0.1]}}\n"
    "    resolution: 0.025\n"
    "    material: {density: 1000, bulk_modulus: 5.0e6, shear_modulus: 5.0e6}\n";

std::string error_of(const fs::path& path) {
  return test::input_error_message([&] { load_config(path.string()); });
}

// Maps merge key by key (time.end survives a time.dt override), lists and values replace, the
// base path is relative to the including file, and the name comes from the including file.
TEST(ConfigBase, IncludingFileOverridesKeyByKey) {
  const fs::path dir = scratch();
  write(dir / "scene.yaml", kBase);
  write(dir / "sub" / "newmark.yaml",
        "base: ../scene.yaml\ntime: {dt: 0.001}\ngravity: [0, 0, -1]\n"
        "integrator: {type: petsc_newton, scheme: newmark}\n");
  const Config c = load_config((dir / "sub" / "newmark.yaml").string());
  EXPECT_EQ(c.name, "newmark");
  EXPECT_DOUBLE_EQ(c.time.end, 1.0);
  EXPECT_FALSE(c.time.dt_auto);
  EXPECT_DOUBLE_EQ(c.time.dt, 0.001);
  EXPECT_DOUBLE_EQ(c.gravity[2], -1.0);
  EXPECT_EQ(c.integrator.type, "petsc_newton");
  EXPECT_EQ(options_of<PetscNewtonSettings>(c.integrator).scheme,
            PetscNewtonSettings::Scheme::newmark);
  ASSERT_EQ(c.bodies.size(), 1u);
  EXPECT_DOUBLE_EQ(c.bodies[0].resolution, 0.025);
}

TEST(ConfigBase, MissingBaseFileNamesTheIncludingFile) {
  const fs::path dir = scratch();
  write(dir / "a.yaml", "base: nowhere.yaml\n");
  const std::string e = error_of(dir / "a.yaml");
  EXPECT_NE(e.find("a.yaml"), std::string::npos) << e;
  EXPECT_NE(e.find("base"), std::string::npos) << e;
  EXPECT_NE(e.find("nowhere.yaml"), std::string::npos) << e;
}

TEST(ConfigBase, FilesIncludingEachOtherAreRefused) {
  const fs::path dir = scratch();
  write(dir / "a.yaml", "base: b.yaml\n");
  write(dir / "b.yaml", "base: a.yaml\n");
  EXPECT_NE(error_of(dir / "a.yaml").find("include each other"), std::string::npos);
}

TEST(ConfigBase, BaseMustBeAPath) {
  const fs::path dir = scratch();
  write(dir / "a.yaml", "base: [x.yaml]\n");
  EXPECT_NE(error_of(dir / "a.yaml").find("expected the path of a scene file"), std::string::npos);
}

}  // namespace
}  // namespace fissure
