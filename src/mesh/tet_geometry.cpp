#include "mesh/tet_geometry.hpp"

#include <cmath>

#include "mesh/face_adjacency.hpp"
#include "mesh/mesh_util.hpp"

namespace fissure {

std::vector<std::array<double, 9>> boundary_triangles(const TetMesh& mesh) {
  const std::vector<int> across = face_adjacency(mesh);
  std::vector<std::array<double, 9>> triangles;
  for (int t = 0; t < mesh.tet_count(); ++t)
    for (int k = 0; k < 4; ++k) {
      if (across[4 * t + k] >= 0) continue;
      std::array<double, 9> triangle;
      for (int c = 0; c < 3; ++c) {
        const int v = mesh.tets[4 * t + kFaceCorners[k][c]];
        for (int a = 0; a < 3; ++a) triangle[3 * c + a] = mesh.vertices[3 * v + a];
      }
      triangles.push_back(triangle);
    }
  return triangles;
}

std::array<double, 6> tet_second_moment(const TetMesh& mesh, int t) {
  const int* tet = &mesh.tets[4 * t];
  double centre[3] = {0, 0, 0};
  for (int c = 0; c < 4; ++c)
    for (int a = 0; a < 3; ++a) centre[a] += 0.25 * mesh.vertices[3 * tet[c] + a];
  std::array<double, 6> m{};
  for (int c = 0; c < 4; ++c) {
    double d[3];
    for (int a = 0; a < 3; ++a) d[a] = mesh.vertices[3 * tet[c] + a] - centre[a];
    m[0] += d[0] * d[0], m[1] += d[1] * d[1], m[2] += d[2] * d[2];
    m[3] += d[0] * d[1], m[4] += d[0] * d[2], m[5] += d[1] * d[2];
  }
  const double volume = std::abs(mesh_detail::tet_signed_volume(mesh.vertices.data(), tet));
  for (double& v : m) v *= volume / 20;
  return m;
}

}  // namespace fissure
