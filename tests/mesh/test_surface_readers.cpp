// read_surface: every format reads the unit cube; malformed files give clear InputErrors.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cube_fixtures.hpp"
#include "mesh/geometry.hpp"
#include "mesh_test_util.hpp"

namespace fissure::test {
namespace {

struct CubeFile {
  const char* name;
  std::string (*contents)();
};

void PrintTo(const CubeFile& file, std::ostream* os) { *os << file.name; }

class CubeFormats : public MeshFileTest, public ::testing::WithParamInterface<CubeFile> {};

// STL corners are merged into 8 vertices too.
TEST_P(CubeFormats, ReadsEightCornersAndTwelveTriangles) {
  const std::string file = write(GetParam().name, GetParam().contents());
  const SurfaceMesh s = read_surface(file);
  EXPECT_EQ(s.vertices.size(), 3u * 8u);
  EXPECT_EQ(s.triangles.size(), 3u * 12u);
}

TEST_P(CubeFormats, TetrahedralizesToUnitVolume) {
  const std::string file = write(GetParam().name, GetParam().contents());
  const TetMesh mesh = load_mesh_file(file, 0.5);
  EXPECT_NEAR(total_volume(mesh), 1.0, 1e-9);
  EXPECT_GT(min_volume(mesh), 0.0);
}

INSTANTIATE_TEST_SUITE_P(Surface, CubeFormats,
                         ::testing::Values(CubeFile{"cube.obj", cube_obj},
                                           CubeFile{"cube.off", cube_off},
                                           CubeFile{"cube_ascii.ply", cube_ply_ascii},
                                           CubeFile{"cube_binary.ply", cube_ply_binary},
                                           CubeFile{"cube_ascii.stl", cube_stl_ascii},
                                           CubeFile{"cube_binary.stl", cube_stl_binary}),
                         [](const auto& info) {
                           std::string name = info.param.name;
                           name[name.find('.')] = '_';
                           return name;
                         });

using SurfaceReaders = MeshFileTest;

TEST_F(SurfaceReaders, OffCountsOnHeaderLine) {
  std::string text = cube_off();
  text.replace(0, text.find("0 0 0\n"), "OFF 8 6 0\n");
  EXPECT_EQ(read_surface(write("cube.off", text)).triangles.size(), 3u * 12u);
}

using SurfaceErrors = MeshFileTest;

TEST_F(SurfaceErrors, MissingFile) {
  expect_input_error([&] { read_surface(path("absent.obj")); }, path("absent.obj"),
                     "file not found");
}

TEST_F(SurfaceErrors, DirectoryInsteadOfFile) {
  std::filesystem::create_directory(path("folder.obj"));
  expect_input_error([&] { read_surface(path("folder.obj")); }, path("folder.obj"),
                     "not a regular file");
}

TEST_F(SurfaceErrors, UnknownExtension) {
  const std::string file = write("cube.xyz", cube_obj());
  expect_input_error([&] { read_surface(file); }, file, "unsupported surface extension");
}

TEST_F(SurfaceErrors, ObjWithoutFaces) {
  const std::string file = write("empty.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  expect_input_error([&] { read_surface(file); }, file, "no triangles");
}

TEST_F(SurfaceErrors, ObjIndexOutOfRange) {
  const std::string file = write("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  expect_input_error([&] { read_surface(file); }, file, "line 4: vertex index 9 out of range");
}

TEST_F(SurfaceErrors, ObjNonFiniteCoordinate) {
  const std::string file = write("nan.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  expect_input_error([&] { read_surface(file); }, file, "non-finite coordinate");
}

TEST_F(SurfaceErrors, ObjMalformedNumber) {
  const std::string file = write("text.obj", "v 0 zero 0\n");
  expect_input_error([&] { read_surface(file); }, file, "line 1: invalid number 'zero'");
}

TEST_F(SurfaceErrors, OffCountsBeyondFile) {
  const std::string file = write("huge.off", "OFF\n1000000000 1 0\n0 0 0\n");
  expect_input_error([&] { read_surface(file); }, file, "header claims 1000000000 vertices");
}

TEST_F(SurfaceErrors, OffMissingHeader) {
  const std::string file = write("noheader.off", "8 6 12\n0 0 0\n");
  expect_input_error([&] { read_surface(file); }, file, "missing OFF header");
}

TEST_F(SurfaceErrors, PlyAsciiCountsBeyondFile) {
  std::string text = cube_ply_ascii();
  text.replace(text.find("vertex 8"), 8, "vertex 123456789");
  const std::string file = write("huge.ply", text);
  expect_input_error([&] { read_surface(file); }, file, "header claims 123456789 'vertex'");
}

TEST_F(SurfaceErrors, PlyBinaryTruncated) {
  const std::string text = cube_ply_binary();
  const std::string file = write("short.ply", text.substr(0, text.size() - 20));
  expect_input_error([&] { read_surface(file); }, file, "unexpected end of PLY data");
}

TEST_F(SurfaceErrors, PlyBigEndian) {
  std::string text = cube_ply_binary();
  text.replace(text.find("little"), 6, "big");
  const std::string file = write("big.ply", text);
  expect_input_error([&] { read_surface(file); }, file,
                     "unsupported PLY format 'binary_big_endian'");
}

TEST_F(SurfaceErrors, PlyIndexOutOfRange) {
  std::string text = cube_ply_ascii();
  text.replace(text.find("4 3 0 4 7"), 9, "4 3 0 4 8");
  const std::string file = write("range.ply", text);
  expect_input_error([&] { read_surface(file); }, file, "vertex index 8, out of range");
}

TEST_F(SurfaceErrors, StlBinaryTruncated) {
  const std::string data = cube_stl_binary();
  const std::string file = write("short.stl", data.substr(0, data.size() - 7));
  expect_input_error([&] { read_surface(file); }, file, "header claims 12 triangles");
}

TEST_F(SurfaceErrors, StlAsciiFacetWithTwoVertices) {
  const std::string file = write("two.stl",
                                 "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"
                                 "vertex 1 0 0\nendloop\nendfacet\nendsolid s\n");
  expect_input_error([&] { read_surface(file); }, file, "facet has 2 vertices");
}

TEST_F(SurfaceErrors, StlTooShort) {
  const std::string file = write("tiny.stl", "abc");
  expect_input_error([&] { read_surface(file); }, file, "too short for a binary STL");
}

}  // namespace
}  // namespace fissure::test
