#include "mesh/surface_extract.hpp"

#include <cstddef>

#include "mesh/face_adjacency.hpp"

namespace fissure {

namespace {

bool holds(const int* tet, int v) {
  return tet[0] == v || tet[1] == v || tet[2] == v || tet[3] == v;
}

}  // namespace

BoundarySurface extract_boundary(const SplitMesh& mesh) {
  BoundarySurface s;
  const std::vector<int>& tets = mesh.mesh.tets;
  for (int t = 0; t < mesh.tet_count(); ++t) {
    const int* tet = &tets[4 * static_cast<std::size_t>(t)];
    for (int k = 0; k < 4; ++k) {
      const int across = mesh.across[4 * t + k];
      const int a = tet[kFaceCorners[k][0]], b = tet[kFaceCorners[k][1]],
                c = tet[kFaceCorners[k][2]];
      if (across >= 0) {
        const int* other = &tets[4 * static_cast<std::size_t>(across / 4)];
        if (holds(other, a) && holds(other, b) && holds(other, c)) continue;
      }
      s.triangles.insert(s.triangles.end(), {a, b, c});
      s.tet.push_back(t);
      s.crack.push_back(across >= 0);
    }
  }
  return s;
}

}  // namespace fissure
