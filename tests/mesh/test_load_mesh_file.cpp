// load_mesh_file: dispatch on the (case-insensitive) extension.
#include <gtest/gtest.h>

#include "cube_fixtures.hpp"
#include "mesh/geometry.hpp"
#include "mesh_test_util.hpp"

namespace fissure::test {
namespace {

using LoadMeshFile = MeshFileTest;

TEST_F(LoadMeshFile, ExtensionIsCaseInsensitive) {
  const std::string file = write("CUBE.OBJ", cube_obj());
  EXPECT_NEAR(total_volume(load_mesh_file(file, 0.5)), 1.0, 1e-9);
}

TEST_F(LoadMeshFile, UnknownExtensionListsSupported) {
  const std::string file = write("cube.vtk", cube_obj());
  expect_input_error([&] { load_mesh_file(file, 0.5); }, file,
                     "(supported: .obj, .stl, .off, .ply, .node, .ele)");
}

TEST_F(LoadMeshFile, OpenSurfaceFileRejected) {
  std::string text = cube_obj();
  text.erase(text.find("f 1 2 6 5\n"), 10);
  const std::string file = write("open.obj", text);
  expect_input_error([&] { load_mesh_file(file, 0.5); }, file, "surface is not closed");
}

}  // namespace
}  // namespace fissure::test
