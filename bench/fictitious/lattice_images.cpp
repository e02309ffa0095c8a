#include "fictitious/lattice_images.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "scene/point_cloud.hpp"

namespace fissure::bench {

namespace {

double squared_distance_to_box(const double* x, const BoxFaces& box) {
  double d2 = 0;
  for (int a = 0; a < 3; ++a) {
    const double e = std::max({box.min[a] - x[a], 0.0, x[a] - box.max[a]});
    d2 += e * e;
  }
  return d2;
}

bool is_free(const BoxFaces& box, int axis, int side) {
  return std::any_of(box.free.begin(), box.free.end(),
                     [&](const auto& f) { return f[0] == axis && f[1] == side; });
}

}  // namespace

std::vector<Triangle> free_face_triangles(const BoxFaces& box) {
  std::vector<Triangle> triangles;
  for (const auto& [axis, side] : box.free) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    auto point = [&](int a, int b) {
      std::array<double, 3> p;
      p[axis] = side ? box.max[axis] : box.min[axis];
      p[u] = a ? box.max[u] : box.min[u];
      p[v] = b ? box.max[v] : box.min[v];
      return p;
    };
    const auto p00 = point(0, 0), p10 = point(1, 0), p11 = point(1, 1), p01 = point(0, 1);
    triangles.push_back({p00[0], p00[1], p00[2], p10[0], p10[1], p10[2], p11[0], p11[1], p11[2]});
    triangles.push_back({p00[0], p00[1], p00[2], p11[0], p11[1], p11[2], p01[0], p01[1], p01[2]});
  }
  return triangles;
}

FictitiousParticles lattice_images(const Particles& particles, const BoxFaces& box,
                                   double horizon) {
  double mean_volume = 0;
  for (double v : particles.volume) mean_volume += v / particles.count();
  const double spacing = std::cbrt(mean_volume);
  // outside across a free face, and not across a held one
  auto beyond = [&](const double* x, bool free) {
    for (int axis = 0; axis < 3; ++axis)
      for (int side = 0; side < 2; ++side)
        if (is_free(box, axis, side) == free &&
            (side ? x[axis] > box.max[axis] : x[axis] < box.min[axis]))
          return true;
    return false;
  };
  const PointCloud cloud{particles.reference};
  KdTree points(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  points.buildIndex();
  FictitiousParticles lattice;
  int steps[3];
  for (int a = 0; a < 3; ++a)
    steps[a] = static_cast<int>(std::ceil((box.max[a] - box.min[a] + 2 * horizon) / spacing)) + 1;
  for (int i = 0; i < steps[0]; ++i)
    for (int j = 0; j < steps[1]; ++j)
      for (int k = 0; k < steps[2]; ++k) {
        const int index[3] = {i, j, k};
        double x[3];
        for (int a = 0; a < 3; ++a) x[a] = box.min[a] - horizon + (index[a] + 0.5) * spacing;
        const double d2 = squared_distance_to_box(x, box);
        if (d2 == 0 || d2 >= horizon * horizon || !beyond(x, true) || beyond(x, false)) continue;
        std::uint32_t nearest;
        double squared;
        points.knnSearch(x, 1, &nearest, &squared);
        if (squared < 0.25 * spacing * spacing) continue;
        lattice.position.insert(lattice.position.end(), x, x + 3);
        lattice.volume.push_back(mean_volume);
        lattice.body.push_back(0);
      }
  return lattice;
}

}  // namespace fissure::bench
