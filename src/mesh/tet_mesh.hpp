#pragma once
// A tetrahedral mesh as flat arrays (paper §5.2): particles are sampled one per tet.
#include <array>
#include <vector>

namespace fissure {

struct TetMesh {
  std::vector<double> vertices;  // 3 * vertex_count, xyz interleaved
  std::vector<int> tets;         // 4 * tet_count, vertex indices, positive orientation

  int vertex_count() const { return static_cast<int>(vertices.size() / 3); }
  int tet_count() const { return static_cast<int>(tets.size() / 4); }
};

// A closed triangulated surface, input to tetrahedralization.
struct SurfaceMesh {
  std::vector<double> vertices;  // 3 * vertex_count
  std::vector<int> triangles;    // 3 * triangle_count
};

}  // namespace fissure
