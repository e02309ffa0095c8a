#pragma once
// Fixtures and checks for the vertex-splitting tests: a structured cube mesh, cracking faces by
// a predicate, and the validity checks of a split mesh (distinct corners, positive rest volume,
// closed boundary per piece, pieces by shared vertices equal to pieces by uncracked faces).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <functional>
#include <utility>
#include <vector>

#include "mesh/crack_faces.hpp"
#include "mesh/face_adjacency.hpp"
#include "mesh/mesh_util.hpp"
#include "mesh/split_mesh.hpp"
#include "mesh/surface_extract.hpp"
#include "support/union_find.hpp"

namespace fissure::test {

// The cube [0, n]³ cut into n³ unit cells of six tets each (Kuhn's subdivision, conforming
// between cells): every grid plane x, y or z = const is a union of tet faces.
inline TetMesh kuhn_cube(int n) {
  TetMesh m;
  auto id = [n](int i, int j, int k) { return i + (n + 1) * (j + (n + 1) * k); };
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) m.vertices.insert(m.vertices.end(), {1.0 * i, 1.0 * j, 1.0 * k});
  const int axes[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (const auto& order : axes) {
          int p[3] = {i, j, k};
          m.tets.push_back(id(p[0], p[1], p[2]));
          for (int a : order) {
            ++p[a];
            m.tets.push_back(id(p[0], p[1], p[2]));
          }
        }
  return m;
}

// The rest position of vertex v.
inline std::array<double, 3> rest(const SplitMesh& s, int v) {
  return {s.mesh.vertices[3 * v], s.mesh.vertices[3 * v + 1], s.mesh.vertices[3 * v + 2]};
}

// Rest barycentre of tet t.
inline std::array<double, 3> barycentre(const SplitMesh& s, int t) {
  std::array<double, 3> c{};
  for (int q = 0; q < 4; ++q)
    for (int d = 0; d < 3; ++d) c[d] += 0.25 * s.mesh.vertices[3 * s.mesh.tets[4 * t + q] + d];
  return c;
}

// Cracks every interior face for which `crack(face id)` holds; returns how many.
inline int crack_faces(const SplitMesh& s, CrackFaces& cracks,
                       const std::function<bool(int)>& crack) {
  int count = 0;
  for (int f = 0; f < 4 * s.tet_count(); ++f)
    if (s.across[f] > f && crack(f)) {
      cracks.add(f, s.across[f]);
      ++count;
    }
  return count;
}

// True if all three vertices of face f lie on the plane x[axis] = value (rest positions).
inline bool face_on_plane(const SplitMesh& s, int f, int axis, double value) {
  const int t = f / 4;
  for (int c : kFaceCorners[f % 4])
    if (s.mesh.vertices[3 * s.mesh.tets[4 * t + c] + axis] != value) return false;
  return true;
}

// Piece label per tet: tets sharing a vertex id are in one piece.
inline std::vector<int> pieces_by_vertices(const SplitMesh& s) {
  UnionFind pieces(s.tet_count() + s.vertex_count());
  for (int t = 0; t < s.tet_count(); ++t)
    for (int q = 0; q < 4; ++q) pieces.join(t, s.tet_count() + s.mesh.tets[4 * t + q]);
  return pieces.roots(s.tet_count());
}

// Piece label per tet: tets joined through uncracked faces are in one piece.
inline std::vector<int> pieces_by_faces(const SplitMesh& s, const CrackFaces& cracks) {
  UnionFind pieces(s.tet_count());
  for (int f = 0; f < 4 * s.tet_count(); ++f)
    if (s.across[f] >= 0 && !cracks.cracked(f)) pieces.join(f / 4, s.across[f] / 4);
  return pieces.roots(s.tet_count());
}

inline int count_labels(std::vector<int> label) {
  std::sort(label.begin(), label.end());
  return static_cast<int>(std::unique(label.begin(), label.end()) - label.begin());
}

// True if the two labellings are the same partition of the tets.
inline bool same_partition(const std::vector<int>& a, const std::vector<int>& b) {
  std::vector<std::pair<int, int>> pairs(a.size());
  for (std::size_t t = 0; t < a.size(); ++t) pairs[t] = {a[t], b[t]};
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return static_cast<int>(pairs.size()) == count_labels(a) &&
         static_cast<int>(pairs.size()) == count_labels(b);
}

// Boundary edges: for each undirected edge, how many boundary triangles hold it, and whether
// every directed edge is matched by its reverse (the boundary is an oriented closed surface).
struct EdgeCounts {
  int edges = 0;
  int edges_not_in_two = 0;  // undirected edges held by other than exactly two triangles
  int unmatched = 0;         // directed edges (a, b) whose count differs from (b, a)'s
};

inline EdgeCounts boundary_edges(const SplitMesh& s) {
  const BoundarySurface surface = extract_boundary(s);
  std::vector<std::pair<int, int>> directed;
  for (int f = 0; f < surface.triangle_count(); ++f)
    for (int e = 0; e < 3; ++e)
      directed.emplace_back(surface.triangles[3 * f + e], surface.triangles[3 * f + (e + 1) % 3]);
  std::vector<std::pair<int, int>> undirected = directed;
  for (auto& [a, b] : undirected)
    if (a > b) std::swap(a, b);
  std::sort(directed.begin(), directed.end());
  std::sort(undirected.begin(), undirected.end());
  EdgeCounts counts;
  for (std::size_t i = 0; i < undirected.size();) {
    std::size_t j = i;
    while (j < undirected.size() && undirected[j] == undirected[i]) ++j;
    ++counts.edges;
    counts.edges_not_in_two += j - i != 2;
    const auto [a, b] = undirected[i];
    const auto forward = std::equal_range(directed.begin(), directed.end(), std::pair{a, b});
    const auto backward = std::equal_range(directed.begin(), directed.end(), std::pair{b, a});
    counts.unmatched += (forward.second - forward.first) != (backward.second - backward.first);
    i = j;
  }
  return counts;
}

// The validity of the mesh after any split. `manifold`: also require every boundary edge to be
// held by exactly two triangles (true for the structured cuts; an unstructured crack surface can
// pinch an edge between two wedges of one piece, which then holds four).
inline void expect_valid(const SplitMesh& s, const CrackFaces& cracks, bool manifold) {
  for (int t = 0; t < s.tet_count(); ++t) {
    const int* q = &s.mesh.tets[4 * t];
    for (int a = 0; a < 4; ++a) {
      for (int b = a + 1; b < 4; ++b) {
        ASSERT_NE(q[a], q[b]) << "tet " << t;
      }
    }
    EXPECT_GT(mesh_detail::tet_signed_volume(s.mesh.vertices.data(), q), 0) << "tet " << t;
  }
  const EdgeCounts edges = boundary_edges(s);
  EXPECT_GT(edges.edges, 0);
  EXPECT_EQ(edges.unmatched, 0);
  if (manifold) {
    EXPECT_EQ(edges.edges_not_in_two, 0);
  }
  EXPECT_TRUE(same_partition(pieces_by_vertices(s), pieces_by_faces(s, cracks)));
}

}  // namespace fissure::test
