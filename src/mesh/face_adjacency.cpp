#include "mesh/face_adjacency.hpp"

#include <algorithm>
#include <array>
#include <cstddef>

namespace fissure {

std::vector<int> face_adjacency(const TetMesh& mesh) {
  const int faces = 4 * mesh.tet_count();
  // Each face as its sorted vertex triple, sorted so that matching faces are consecutive.
  struct Key {
    std::array<int, 3> vertices;
    int face;
  };
  std::vector<Key> keys(faces);
  for (int f = 0; f < faces; ++f) {
    const int* tet = &mesh.tets[4 * static_cast<std::size_t>(f / 4)];
    const int* corners = kFaceCorners[f % 4];
    std::array<int, 3> v = {tet[corners[0]], tet[corners[1]], tet[corners[2]]};
    std::sort(v.begin(), v.end());
    keys[f] = {v, f};
  }
  std::sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) {
    return a.vertices != b.vertices ? a.vertices < b.vertices : a.face < b.face;
  });
  std::vector<int> across(faces, -1);
  for (int begin = 0; begin < faces;) {
    int end = begin + 1;
    while (end < faces && keys[end].vertices == keys[begin].vertices) ++end;
    if (end - begin == 2) {
      across[keys[begin].face] = keys[begin + 1].face;
      across[keys[begin + 1].face] = keys[begin].face;
    }
    begin = end;
  }
  return across;
}

}  // namespace fissure
