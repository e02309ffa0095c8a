// read_tetgen: .node/.ele round trip, numbering, orientation and malformed files.
#include <gtest/gtest.h>

#include <iomanip>
#include <sstream>
#include <string>

#include "mesh/geometry.hpp"
#include "mesh_test_util.hpp"

namespace fissure::test {
namespace {

class TetgenReader : public MeshFileTest {
 protected:
  std::string write_node(const std::string& text) { return write("m.node", text); }
  std::string write_ele(const std::string& text) { return write("m.ele", text); }
  // .node with one attribute and boundary markers; .ele with `corners` nodes per tet.
  void write_tetgen(const std::string& base, const TetMesh& mesh, int first, int corners = 4) {
    std::ostringstream node, ele;
    node << std::setprecision(17) << "# nodes\n" << mesh.vertex_count() << " 3 1 1\n";
    for (int v = 0; v < mesh.vertex_count(); ++v) {
      node << v + first;
      for (int c = 0; c < 3; ++c) node << ' ' << mesh.vertices[3 * v + c];
      node << " 0.5 1\n";
    }
    ele << mesh.tet_count() << ' ' << corners << " 0\n";
    for (int t = 0; t < mesh.tet_count(); ++t) {
      ele << t + first;
      for (int k = 0; k < corners; ++k) ele << ' ' << mesh.tets[4 * t + k % 4] + first;
      ele << '\n';
    }
    write(base + ".node", node.str());
    write(base + ".ele", ele.str());
  }
  // Five nodes, a unit right tet on the first four, and the given .ele text.
  void write_single(const std::string& ele) {
    write_node("5 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 1 1 1\n");
    write_ele(ele);
  }
};

TEST_F(TetgenReader, RoundTripOneBasedByAnyName) {
  const TetMesh mesh = tetrahedralize_box({0, 0, 0}, {1, 0.5, 0.25}, 0.25);
  write_tetgen("box", mesh, 1);
  for (const std::string& name : {path("box"), path("box.node"), path("box.ele")}) {
    const TetMesh read = read_tetgen(name);
    EXPECT_EQ(read.vertices, mesh.vertices);
    EXPECT_EQ(read.tets, mesh.tets);
  }
}

TEST_F(TetgenReader, RoundTripZeroBasedThroughLoadMeshFile) {
  const TetMesh mesh = tetrahedralize_box({0, 0, 0}, {1, 1, 1}, 0.5);
  write_tetgen("cube", mesh, 0);
  const TetMesh read = load_mesh_file(path("cube.node"), 123.0);
  EXPECT_EQ(read.vertices, mesh.vertices);
  EXPECT_EQ(read.tets, mesh.tets);
}

TEST_F(TetgenReader, TenNodeTetsKeepCorners) {
  const TetMesh mesh = tetrahedralize_box({0, 0, 0}, {1, 1, 1}, 0.5);
  write_tetgen("quadratic", mesh, 1, 10);
  EXPECT_EQ(read_tetgen(path("quadratic.ele")).tets, mesh.tets);
}

TEST_F(TetgenReader, AllInvertedAreFlipped) {
  write_single("2 4 0\n1 1 3 2 4\n2 3 2 4 5\n");
  const TetMesh mesh = read_tetgen(path("m"));
  EXPECT_GT(min_volume(mesh), 0.0);
  EXPECT_NEAR(total_volume(mesh), 1.0 / 6.0 + 1.0 / 3.0, 1e-15);
}

TEST_F(TetgenReader, MixedInversionRejected) {
  write_single("2 4 0\n1 1 2 3 4\n2 3 2 4 5\n");
  expect_input_error([&] { read_tetgen(path("m")); }, path("m.ele"),
                     "tet 2 is inverted (negative volume) while 1 of 2");
}

TEST_F(TetgenReader, DegenerateTetRejected) {
  write_single("1 4 0\n1 1 2 3 3\n");
  expect_input_error([&] { read_tetgen(path("m")); }, path("m.ele"), "tet 1 is degenerate");
}

TEST_F(TetgenReader, NodeIndexOutOfRange) {
  write_single("1 4 0\n1 1 2 3 6\n");
  expect_input_error([&] { read_tetgen(path("m")); }, path("m.ele"),
                     "line 2: node index '6' out of range (1 to 5)");
}

TEST_F(TetgenReader, NonFiniteCoordinate) {
  write_node("4 3 0 0\n0 0 0 0\n1 inf 0 0\n2 0 1 0\n3 0 0 1\n");
  write_ele("1 4 0\n0 0 1 2 3\n");
  expect_input_error([&] { read_tetgen(path("m")); }, path("m.node"),
                     "line 3: invalid or non-finite coordinate 'inf'");
}

TEST_F(TetgenReader, NodeCountBeyondFile) {
  write_node("99999999 3 0 0\n0 0 0 0\n");
  write_ele("1 4 0\n0 0 0 0 0\n");
  expect_input_error([&] { read_tetgen(path("m")); }, path("m.node"),
                     "header claims 99999999 nodes");
}

TEST_F(TetgenReader, TetCountBeyondFile) {
  write_single("3 4 0\n1 1 2 3 4\n");
  expect_input_error([&] { read_tetgen(path("m")); }, path("m.ele"), "header claims 3 tets");
}

TEST_F(TetgenReader, NonConsecutiveNodeNumbers) {
  write_node("3 3 0 0\n1 0 0 0\n3 1 0 0\n4 0 1 0\n");
  expect_input_error([&] { read_tetgen(path("m")); }, path("m.node"),
                     "expected node index 2, found 3");
}

TEST_F(TetgenReader, TwoDimensionalNodesRejected) {
  write_node("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n");
  expect_input_error([&] { read_tetgen(path("m")); }, path("m.node"), "dimension must be 3");
}

TEST_F(TetgenReader, MissingEleFile) {
  write_node("4 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n");
  expect_input_error([&] { read_tetgen(path("m.node")); }, path("m.ele"), "file not found");
}

}  // namespace
}  // namespace fissure::test
