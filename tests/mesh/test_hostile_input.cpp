// Hostile mesh input: absurd header counts, NaN/inf coordinates, out-of-range indices
// and the inputs the fuzz targets (tests/fuzz) found, each rejected with a clear InputError.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "cube_fixtures.hpp"
#include "mesh/geometry.hpp"
#include "mesh/tetgen_format.hpp"
#include "mesh_test_util.hpp"

namespace fissure::test {
namespace {

using HostileInput = MeshFileTest;

constexpr const char* kTrillion = "1000000000000";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  text.replace(text.find(from), from.size(), to);
  return text;
}

TEST_F(HostileInput, OffTrillionVertices) {
  const std::string file =
      write("huge.off", replaced(cube_off(), "8 6 12", std::string(kTrillion) + " 6 12"));
  expect_input_error([&] { read_surface(file); }, file,
                     "header claims 1000000000000 vertices and 6 faces but the file has only 14");
}

TEST_F(HostileInput, PlyTrillionFaces) {
  const std::string file =
      write("huge.ply", replaced(cube_ply_binary(), "face 12", std::string("face ") + kTrillion));
  expect_input_error([&] { read_surface(file); }, file,
                     "header claims 1000000000000 'face' elements");
}

TEST_F(HostileInput, StlBinaryMaximalCount) {
  std::string data = cube_stl_binary();
  const uint32_t count = std::numeric_limits<uint32_t>::max();
  data.replace(80, 4, reinterpret_cast<const char*>(&count), 4);
  const std::string file = write("huge.stl", data);
  expect_input_error([&] { read_surface(file); }, file,
                     "binary STL header claims 4294967295 triangles");
}

TEST_F(HostileInput, TetgenTrillionNodes) {
  const std::string node = std::string(kTrillion) + " 3 0 0\n1 0 0 0\n";
  expect_input_error([&] { mesh_detail::parse_tetgen(node, "", "m.node", "m.ele"); }, "m.node",
                     "header claims 1000000000000 nodes but the file has only 1 more lines");
}

TEST_F(HostileInput, TetgenTrillionTets) {
  const std::string node = "4 3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n";
  const std::string ele = std::string(kTrillion) + " 4 0\n1 1 2 3 4\n";
  expect_input_error([&] { mesh_detail::parse_tetgen(node, ele, "m.node", "m.ele"); }, "m.ele",
                     "header claims 1000000000000 tets");
}

TEST_F(HostileInput, OffIndexOutOfRange) {
  const std::string file = write("range.off", replaced(cube_off(), "4 3 0 4 7", "4 3 0 4 8"));
  expect_input_error([&] { read_surface(file); }, file,
                     "line 17: vertex index '8' out of range (0 to 7)");
}

TEST_F(HostileInput, OffInfiniteCoordinate) {
  const std::string file = write("inf.off", replaced(cube_off(), "1 1 1\n", "1 inf 1\n"));
  expect_input_error([&] { read_surface(file); }, file,
                     "vertex 6 (0-based) has a non-finite coordinate");
}

TEST_F(HostileInput, PlyNanCoordinate) {
  const std::string file = write("nan.ply", replaced(cube_ply_ascii(), "0 1 1 1\n", "0 nan 1 1\n"));
  expect_input_error([&] { read_surface(file); }, file,
                     "vertex 7 (0-based) has a non-finite coordinate");
}

TEST_F(HostileInput, StlBinaryNanCoordinate) {
  std::string data = cube_stl_binary();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  data.replace(84 + 12, 4, reinterpret_cast<const char*>(&nan), 4);
  const std::string file = write("nan.stl", data);
  expect_input_error([&] { read_surface(file); }, file, "has a non-finite coordinate");
}

TEST_F(HostileInput, TetgenNanCoordinate) {
  const std::string node = "4 3\n1 0 0 0\n2 1 nan 0\n3 0 1 0\n4 0 0 1\n";
  expect_input_error(
      [&] { mesh_detail::parse_tetgen(node, "1 4\n1 1 2 3 4\n", "m.node", "m.ele"); }, "m.node",
      "line 3: invalid or non-finite coordinate 'nan'");
}

TEST_F(HostileInput, TetgenFromMemoryMatchesFile) {
  const std::string node = "4 3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n";
  const std::string ele = "1 4\n1 1 3 2 4\n";
  const TetMesh mesh = mesh_detail::parse_tetgen(node, ele, "m.node", "m.ele");
  ASSERT_EQ(mesh.tet_count(), 1);
  EXPECT_NEAR(tet_volume(mesh, 0), 1.0 / 6.0, 1e-15);  // the inverted tet is flipped
  write("m.ele", ele);
  const TetMesh from_file = read_tetgen(write("m.node", node));
  EXPECT_EQ(from_file.vertices, mesh.vertices);
  EXPECT_EQ(from_file.tets, mesh.tets);
}

// Found by fuzz_ply: a `property` line without type and name read past its tokens.
TEST_F(HostileInput, PlyPropertyWithoutTypeAndName) {
  const std::string file =
      write("bare.ply", replaced(cube_ply_ascii(), "property double y\n", "property\n"));
  expect_input_error([&] { read_surface(file); }, file, "line 6: property needs a type and a name");
}

TEST_F(HostileInput, PlyUnknownPropertyType) {
  const std::string file =
      write("type.ply", replaced(cube_ply_ascii(), "property double y", "property real y"));
  expect_input_error([&] { read_surface(file); }, file, "line 6: unknown property type 'real'");
}

}  // namespace
}  // namespace fissure::test
