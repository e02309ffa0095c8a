// Vertex splitting along crack faces (paper §5.2): exact copy counts on structured
// cuts, and the validity of the mesh after any split.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "mesh/geometry.hpp"
#include "mesh/vertex_split.hpp"
#include "split_fixtures.hpp"

namespace fissure::test {
namespace {

// Copies of original vertex o after splitting.
int copies_of(const SplitMesh& s, int o) {
  return static_cast<int>(std::count(s.origin.begin(), s.origin.end(), o));
}

int vertex_id(int n, int i, int j, int k) { return i + (n + 1) * (j + (n + 1) * k); }

TEST(VertexSplit, UncrackedMeshKeepsItsVerticesAndSurface) {
  SplitMesh s = make_split_mesh(kuhn_cube(2));
  VertexSplitter splitter(s.tet_count());
  EXPECT_EQ(splitter.split_all(s, nullptr), 0);
  EXPECT_EQ(s.vertex_count(), 27);
  const BoundarySurface surface = extract_boundary(s);
  EXPECT_EQ(surface.triangle_count(), 6 * 2 * 2 * 2);  // 6 sides × 4 squares × 2 triangles
  EXPECT_EQ(std::count(surface.crack.begin(), surface.crack.end(), 1), 0);
  CrackFaces none(s.tet_count());
  expect_valid(s, none, true);
}

TEST(VertexSplit, PlaneCutSplitsCubeIntoTwoPieces) {
  const int n = 4;
  SplitMesh s = make_split_mesh(kuhn_cube(n));
  CrackFaces cracks(s.tet_count());
  VertexSplitter splitter(s.tet_count());
  const int faces = crack_faces(s, cracks, [&](int f) { return face_on_plane(s, f, 0, 2.0); });
  EXPECT_EQ(faces, n * n * 2);
  const int plane_vertices = (n + 1) * (n + 1);
  EXPECT_EQ(splitter.split_cracked(s, cracks), plane_vertices);
  EXPECT_EQ(s.vertex_count(), (n + 1) * (n + 1) * (n + 1) + plane_vertices);
  EXPECT_EQ(count_labels(pieces_by_vertices(s)), 2);
  // No vertex is used by tets on both sides of the plane.
  std::vector<int> side(s.vertex_count(), -1);
  for (int t = 0; t < s.tet_count(); ++t) {
    const int here = barycentre(s, t)[0] > 2.0;
    for (int q = 0; q < 4; ++q) {
      int& v = side[s.mesh.tets[4 * t + q]];
      EXPECT_TRUE(v < 0 || v == here) << "vertex " << s.mesh.tets[4 * t + q];
      v = here;
    }
  }
  // Every crack face has opened: both sides are on the surface, and none is left in the set.
  const BoundarySurface surface = extract_boundary(s);
  EXPECT_EQ(std::count(surface.crack.begin(), surface.crack.end(), 1), 2 * faces);
  EXPECT_TRUE(cracks.set().empty());
  expect_valid(s, cracks, true);
}

TEST(VertexSplit, PlaneCutFaceByFaceEndsLikeAllAtOnce) {
  const int n = 3;
  SplitMesh s = make_split_mesh(kuhn_cube(n));
  CrackFaces cracks(s.tet_count());
  VertexSplitter splitter(s.tet_count());
  for (int f = 0; f < 4 * s.tet_count(); ++f)
    if (s.across[f] > f && face_on_plane(s, f, 1, 1.0)) {
      cracks.add(f, s.across[f]);
      splitter.split_cracked(s, cracks);
      expect_valid(s, cracks, false);
    }
  EXPECT_EQ(s.vertex_count(), (n + 1) * (n + 1) * (n + 1) + (n + 1) * (n + 1));
  EXPECT_EQ(count_labels(pieces_by_vertices(s)), 2);
  EXPECT_TRUE(cracks.set().empty());
  expect_valid(s, cracks, true);
}

TEST(VertexSplit, RetiresOnlyTheCrackFacesThatCausedASplit) {
  const int n = 4;
  SplitMesh s = make_split_mesh(kuhn_cube(n));
  CrackFaces cracks(s.tet_count());
  VertexSplitter splitter(s.tet_count());
  // A face on the x < 2 side that touches the plane x = 2 only at the centre vertex, whose
  // tets on that side stay joined around it through their other faces.
  const int centre = vertex_id(n, 2, 2, 2);
  int extra = -1;
  for (int f = 0; f < 4 * s.tet_count() && extra < 0; ++f) {
    if (s.across[f] < f || barycentre(s, f / 4)[0] > 2.0) continue;
    int on_plane = 0, at_centre = 0;
    for (int c : kFaceCorners[f % 4]) {
      const int v = s.mesh.tets[4 * (f / 4) + c];
      on_plane += rest(s, v)[0] == 2.0;
      at_centre += v == centre;
    }
    if (on_plane == 1 && at_centre == 1) extra = f;
  }
  ASSERT_GE(extra, 0);
  cracks.add(extra, s.across[extra]);
  EXPECT_EQ(splitter.split_cracked(s, cracks), 0);  // alone it separates nothing
  ASSERT_EQ(cracks.set().size(), 1u);
  crack_faces(s, cracks, [&](int f) { return face_on_plane(s, f, 0, 2.0); });
  splitter.split_cracked(s, cracks);
  ASSERT_EQ(cracks.set().size(), 1u);  // the plane's faces caused splits; the extra one did not
  EXPECT_EQ(cracks.set()[0], extra);
  EXPECT_EQ(cracks.total(), 1u + n * n * 2);
  expect_valid(s, cracks, false);
}

// The three faces of one tet at one of its corners crack: that corner alone splits off.
void isolate_corner(int n, int tet, int corner) {
  SplitMesh s = make_split_mesh(kuhn_cube(n));
  CrackFaces cracks(s.tet_count());
  VertexSplitter splitter(s.tet_count());
  const int v = s.mesh.tets[4 * tet + corner];
  for (int k = 0; k < 4; ++k)
    if (k != corner && s.across[4 * tet + k] >= 0) cracks.add(4 * tet + k, s.across[4 * tet + k]);
  const int before = s.vertex_count();
  EXPECT_EQ(splitter.split_cracked(s, cracks), 1);
  EXPECT_EQ(s.vertex_count(), before + 1);
  EXPECT_EQ(copies_of(s, v), 2);
  const int copy = s.mesh.tets[4 * tet + corner];
  int users = 0;
  for (int c : s.mesh.tets) users += c == copy;
  EXPECT_EQ(users, 1);                                // the tet's corner has a vertex of its own
  EXPECT_EQ(count_labels(pieces_by_vertices(s)), 1);  // held by the face opposite the corner
  expect_valid(s, cracks, false);
}

TEST(VertexSplit, CrackIsolatingOneTetCornerSplitsThatVertexOnce) {
  const int n = 3;
  // A tet of the centre cell at an interior vertex, and one at the cube's corner vertex.
  const int centre_cell = 1 + n * (1 + n * 1);
  isolate_corner(n, 6 * centre_cell, 0);
  isolate_corner(n, 0, 0);
}

TEST(VertexSplit, ThreePlanesMeetingAtAVertexSplitItIntoEight) {
  const int n = 4;
  SplitMesh s = make_split_mesh(kuhn_cube(n));
  CrackFaces cracks(s.tet_count());
  VertexSplitter splitter(s.tet_count());
  crack_faces(s, cracks, [&](int f) {
    return face_on_plane(s, f, 0, 2.0) || face_on_plane(s, f, 1, 2.0) ||
           face_on_plane(s, f, 2, 2.0);
  });
  splitter.split_cracked(s, cracks);
  EXPECT_EQ(copies_of(s, vertex_id(n, 2, 2, 2)), 8);  // where the three cracks meet
  EXPECT_EQ(copies_of(s, vertex_id(n, 2, 2, 1)), 4);  // where two meet
  EXPECT_EQ(copies_of(s, vertex_id(n, 2, 1, 1)), 2);  // on one
  EXPECT_EQ(copies_of(s, vertex_id(n, 1, 1, 1)), 1);
  EXPECT_EQ(s.vertex_count(), 8 * 3 * 3 * 3);  // eight cubes of 3³ vertices
  EXPECT_EQ(count_labels(pieces_by_vertices(s)), 8);
  expect_valid(s, cracks, true);
}

TEST(VertexSplit, TJunctionSplitsTheJunctionLineIntoThree) {
  const int n = 4;
  SplitMesh s = make_split_mesh(kuhn_cube(n));
  CrackFaces cracks(s.tet_count());
  VertexSplitter splitter(s.tet_count());
  crack_faces(s, cracks, [&](int f) {
    return face_on_plane(s, f, 1, 2.0) ||
           (face_on_plane(s, f, 0, 2.0) && barycentre(s, f / 4)[1] > 2.0);
  });
  splitter.split_cracked(s, cracks);
  for (int k = 0; k <= n; ++k) EXPECT_EQ(copies_of(s, vertex_id(n, 2, 2, k)), 3) << "z = " << k;
  EXPECT_EQ(count_labels(pieces_by_vertices(s)), 3);
  expect_valid(s, cracks, true);
}

TEST(VertexSplit, ThreeQuarterPlanesMeetingOnlyAtAVertexCutOffAnOctant) {
  const int n = 4;
  SplitMesh s = make_split_mesh(kuhn_cube(n));
  CrackFaces cracks(s.tet_count());
  VertexSplitter splitter(s.tet_count());
  // The three faces of the octant [2, 4]³ inside the cube.
  auto in_octant_face = [&](int f, int axis) {
    if (!face_on_plane(s, f, axis, 2.0)) return false;
    const auto c = barycentre(s, f / 4);
    for (int d = 0; d < 3; ++d)
      if (d != axis && c[d] < 2.0) return false;
    return true;
  };
  crack_faces(s, cracks, [&](int f) {
    return in_octant_face(f, 0) || in_octant_face(f, 1) || in_octant_face(f, 2);
  });
  splitter.split_cracked(s, cracks);
  EXPECT_EQ(copies_of(s, vertex_id(n, 2, 2, 2)), 2);
  EXPECT_EQ(copies_of(s, vertex_id(n, 2, 3, 3)), 2);
  EXPECT_EQ(copies_of(s, vertex_id(n, 2, 1, 3)), 1);
  EXPECT_EQ(count_labels(pieces_by_vertices(s)), 2);
  expect_valid(s, cracks, true);
}

TEST(VertexSplit, ZigZagCutOfAnUnstructuredMeshGivesTwoValidPieces) {
  SplitMesh s = make_split_mesh(tetrahedralize_box({0, 0, 0}, {1, 1, 1}, 0.2));
  CrackFaces cracks(s.tet_count());
  VertexSplitter splitter(s.tet_count());
  EXPECT_EQ(splitter.split_all(s, &cracks), 0);
  crack_faces(s, cracks, [&](int f) {
    return (barycentre(s, f / 4)[0] < 0.5) != (barycentre(s, s.across[f] / 4)[0] < 0.5);
  });
  EXPECT_GT(splitter.split_cracked(s, cracks), 0);
  EXPECT_EQ(count_labels(pieces_by_vertices(s)), 2);
  expect_valid(s, cracks, false);
}

TEST(VertexSplit, RandomCracksKeepTheMeshValidAndMatchASplitFromScratch) {
  std::mt19937 rng(7);
  std::bernoulli_distribution crack(0.08);
  const TetMesh box = tetrahedralize_box({0, 0, 0}, {1, 1, 1}, 0.25);
  SplitMesh s = make_split_mesh(box);
  CrackFaces cracks(s.tet_count());
  VertexSplitter splitter(s.tet_count());
  for (int round = 0; round < 6; ++round) {
    crack_faces(s, cracks, [&](int f) { return !cracks.cracked(f) && crack(rng); });
    splitter.split_cracked(s, cracks);
    expect_valid(s, cracks, false);
  }
  // Splitting the original mesh once with the final crack set gives the same split: the same
  // vertex count, each corner's vertex a copy of the same original vertex, and the same
  // corners sharing a vertex (vertex ids may be numbered differently, so each mesh's ids are
  // renumbered in order of first use by the corners before comparing).
  SplitMesh fresh = make_split_mesh(box);
  CrackFaces same(fresh.tet_count());
  crack_faces(fresh, same, [&](int f) { return cracks.cracked(f); });
  VertexSplitter other(fresh.tet_count());
  other.split_all(fresh, &same);
  EXPECT_EQ(fresh.vertex_count(), s.vertex_count());
  EXPECT_GT(s.vertex_count(), box.vertex_count());
  const auto first_use_ids = [](const SplitMesh& m) {
    std::vector<int> renumbered(m.vertex_count(), -1), ids;
    int next = 0;
    for (int v : m.mesh.tets) {
      if (renumbered[v] < 0) renumbered[v] = next++;
      ids.push_back(renumbered[v]);
    }
    return ids;
  };
  EXPECT_EQ(first_use_ids(fresh), first_use_ids(s));
  for (std::size_t c = 0; c < s.mesh.tets.size(); ++c)
    ASSERT_EQ(fresh.origin[fresh.mesh.tets[c]], s.origin[s.mesh.tets[c]]) << "corner " << c;
}

}  // namespace
}  // namespace fissure::test
