#pragma once
// Where the camera stands: the bounds of a run's particles over its frames, and a camera that
// frames them from the front, slightly from the right and above (z is up).
#include <array>
#include <vector>

namespace fissure {

using Point3 = std::array<double, 3>;

struct Bounds {
  Point3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  bool empty() const { return lo[0] > hi[0]; }
  void include(const Bounds& other);
};

// Per axis the 1st to 99th percentile of the points (all of them below 200 points), so that a
// few particles flung far away do not shrink the picture.
Bounds robust_bounds(const std::vector<double>& points);

struct Camera {
  Point3 position{}, look_at{};
  double angle = 35;  // horizontal field of view, degrees
};

// A camera looking at the centre of `b` from a fixed direction, far enough that the sphere
// around `b` fits the narrower of the horizontal and vertical fields of view.
Camera frame_bounds(const Bounds& b, double angle_degrees, double aspect);

}  // namespace fissure
