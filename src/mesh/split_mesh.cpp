#include "mesh/split_mesh.hpp"

#include <cstddef>
#include <numeric>
#include <utility>

#include "mesh/face_adjacency.hpp"
#include "mesh/mesh_util.hpp"

namespace fissure {

int SplitMesh::copy_vertex(int v) {
  const int copy = vertex_count();
  for (int k = 0; k < 3; ++k) {
    mesh.vertices.push_back(mesh.vertices[3 * static_cast<std::size_t>(v) + k]);
    position.push_back(position[3 * static_cast<std::size_t>(v) + k]);
  }
  origin.push_back(origin[v]);
  return copy;
}

SplitMesh make_split_mesh(TetMesh mesh) {
  SplitMesh s;
  for (int t = 0; t < mesh.tet_count(); ++t) {
    int* tet = &mesh.tets[4 * static_cast<std::size_t>(t)];
    if (mesh_detail::tet_signed_volume(mesh.vertices.data(), tet) < 0) std::swap(tet[2], tet[3]);
  }
  s.mesh = std::move(mesh);
  const int n = s.mesh.vertex_count();
  s.position = s.mesh.vertices;
  s.origin.resize(n);
  std::iota(s.origin.begin(), s.origin.end(), 0);
  s.across = face_adjacency(s.mesh);
  s.corner_offsets.assign(n + 1, 0);
  for (int v : s.mesh.tets) ++s.corner_offsets[v + 1];
  std::partial_sum(s.corner_offsets.begin(), s.corner_offsets.end(), s.corner_offsets.begin());
  s.corners.resize(s.mesh.tets.size());
  std::vector<int> next(s.corner_offsets.begin(), s.corner_offsets.end() - 1);
  for (std::size_t c = 0; c < s.mesh.tets.size(); ++c)
    s.corners[next[s.mesh.tets[c]]++] = static_cast<int>(c);
  return s;
}

}  // namespace fissure
