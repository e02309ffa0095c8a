#include "render/view.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace fissure {

void Bounds::include(const Bounds& other) {
  for (int k = 0; k < 3; ++k) {
    lo[k] = std::min(lo[k], other.lo[k]);
    hi[k] = std::max(hi[k], other.hi[k]);
  }
}

Bounds robust_bounds(const std::vector<double>& points) {
  Bounds b;
  const std::size_t n = points.size() / 3;
  if (n == 0) return b;
  const std::size_t cut = n < 200 ? 0 : n / 100;
  std::vector<double> axis(n);
  for (int k = 0; k < 3; ++k) {
    for (std::size_t i = 0; i < n; ++i) axis[i] = points[3 * i + k];
    std::nth_element(axis.begin(), axis.begin() + cut, axis.end());
    b.lo[k] = axis[cut];
    std::nth_element(axis.begin(), axis.end() - 1 - cut, axis.end());
    b.hi[k] = axis[n - 1 - cut];
  }
  return b;
}

Camera frame_bounds(const Bounds& b, double angle_degrees, double aspect) {
  Camera c;
  c.angle = angle_degrees;
  double radius = 0;
  for (int k = 0; k < 3; ++k) {
    c.look_at[k] = 0.5 * (b.lo[k] + b.hi[k]);
    radius += 0.25 * (b.hi[k] - b.lo[k]) * (b.hi[k] - b.lo[k]);
  }
  radius = std::max(std::sqrt(radius), 1e-9);
  const double horizontal = angle_degrees * std::numbers::pi / 180;
  const double vertical = 2 * std::atan(std::tan(horizontal / 2) / aspect);
  const double distance = 1.05 * radius / std::sin(std::min(horizontal, vertical) / 2);
  const Point3 direction{0.45, -1.0, 0.5};
  const double norm = std::sqrt(direction[0] * direction[0] + direction[1] * direction[1] +
                                direction[2] * direction[2]);
  for (int k = 0; k < 3; ++k) c.position[k] = c.look_at[k] + distance * direction[k] / norm;
  return c;
}

}  // namespace fissure
