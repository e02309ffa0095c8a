// Conforming midpoint refinement of a triangulated surface, so that TetGen can keep it as is.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "mesh/mesh_util.hpp"

namespace fissure::mesh_detail {

namespace {

double distance(const std::vector<double>& v, int a, int b) {
  return std::hypot(v[3 * a] - v[3 * b], v[3 * a + 1] - v[3 * b + 1], v[3 * a + 2] - v[3 * b + 2]);
}

// One pass: every edge longer than `max_edge` gets a midpoint, shared by both its triangles;
// each triangle is split by the pattern of its split edges. Returns false if nothing was split.
bool split_long_edges(SurfaceMesh& s, double max_edge) {
  std::unordered_map<uint64_t, int> midpoints;
  const auto midpoint = [&](int a, int b) {
    if (distance(s.vertices, a, b) <= max_edge) return -1;
    const uint64_t key = (uint64_t(std::min(a, b)) << 32) | uint32_t(std::max(a, b));
    const auto [it, inserted] = midpoints.emplace(key, int(s.vertices.size() / 3));
    if (inserted) {
      for (int c = 0; c < 3; ++c) {
        s.vertices.push_back(0.5 * (s.vertices[3 * a + c] + s.vertices[3 * b + c]));
      }
    }
    return it->second;
  };
  std::vector<int> out;
  out.reserve(s.triangles.size());
  for (size_t t = 0; t < s.triangles.size(); t += 3) {
    std::array<int, 3> v = {s.triangles[t], s.triangles[t + 1], s.triangles[t + 2]};
    std::array<int, 3> m = {midpoint(v[0], v[1]), midpoint(v[1], v[2]), midpoint(v[2], v[0])};
    const int split = (m[0] >= 0) + (m[1] >= 0) + (m[2] >= 0);
    // Rotate (keeping orientation) so that edge 0 is split and, with two splits, edge 2 is not.
    for (int r = 0; r < 3 && split > 0 && (m[0] < 0 || (split == 2 && m[2] >= 0)); ++r) {
      std::rotate(v.begin(), v.begin() + 1, v.end());
      std::rotate(m.begin(), m.begin() + 1, m.end());
    }
    const auto add = [&](int a, int b, int c) { out.insert(out.end(), {a, b, c}); };
    if (split == 0) {
      add(v[0], v[1], v[2]);
    } else if (split == 1) {
      add(v[0], m[0], v[2]);
      add(m[0], v[1], v[2]);
    } else if (split == 2) {
      add(m[0], v[1], m[1]);
      // Quad v0, m0, m1, v2: cut along its shorter diagonal.
      if (distance(s.vertices, v[0], m[1]) < distance(s.vertices, m[0], v[2])) {
        add(v[0], m[0], m[1]);
        add(v[0], m[1], v[2]);
      } else {
        add(v[0], m[0], v[2]);
        add(m[0], m[1], v[2]);
      }
    } else {
      add(v[0], m[0], m[2]);
      add(m[0], v[1], m[1]);
      add(m[2], m[1], v[2]);
      add(m[0], m[1], m[2]);
    }
  }
  s.triangles = std::move(out);
  return !midpoints.empty();
}

}  // namespace

void refine_surface(SurfaceMesh& surface, double max_edge) {
  while (split_long_edges(surface, max_edge)) {
  }
}

}  // namespace fissure::mesh_detail
