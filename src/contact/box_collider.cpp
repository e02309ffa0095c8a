// A box collider: colliders[i].box {min, max}, axis-aligned; it may move (kinematic only).
#include <algorithm>
#include <cmath>

#include "contact/collider_registry.hpp"

namespace fissure {

namespace {

struct BoxOptions : ColliderOptions {
  Point min{}, max{};
};

class Box : public ShapeContact<Box> {
 public:
  explicit Box(const BoxOptions& o) : o_(o) {}
  Point origin() const override { return {0, 0, 0}; }
  // Depth of a particle at y against the box offset by x: r − distance to the nearest point
  // outside it; inside, r plus the depth below the nearest face, pushed out through that face.
  double penetration(const double* x, const double* y, double radius, double* n) const {
    double d[3];
    double inside = -1e300;  // depth of the shallowest face when the point is inside the box
    int axis = 0;
    for (int k = 0; k < 3; ++k) {
      const double lo = o_.min[k] + x[k], hi = o_.max[k] + x[k];
      d[k] = y[k] - std::clamp(y[k], lo, hi);
      const double face = std::max(lo - y[k], y[k] - hi);
      if (face > inside) inside = face, axis = k;
    }
    if (d[0] == 0 && d[1] == 0 && d[2] == 0) {
      const double mid = 0.5 * (o_.min[axis] + o_.max[axis]) + x[axis];
      for (int k = 0; k < 3; ++k) n[k] = k == axis ? (y[axis] < mid ? -1.0 : 1.0) : 0.0;
      return radius - inside;
    }
    return outward(d, std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]), radius, n);
  }

 private:
  BoxOptions o_;
};

}  // namespace

ColliderKind box_collider_kind() {
  return {
      "box",
      {"min", "max"},
      [](const OptionReader& r) {
        auto o = std::make_shared<BoxOptions>();
        o->min = r.vec3("min");
        o->max = r.vec3("max");
        for (int k = 0; k < 3; ++k)
          if (o->max[k] <= o->min[k]) r.fail("max", "each component of max must exceed min");
        return o;
      },
      [](const ColliderOptions& o) { return std::make_unique<Box>(shape_options<BoxOptions>(o)); }};
}

}  // namespace fissure
