// A sphere collider: colliders[i].sphere {center, radius}; it may move and, given a mass, is
// dynamic (contact/colliders.hpp).
#include <cmath>

#include "contact/collider_registry.hpp"

namespace fissure {

namespace {

struct SphereOptions : ColliderOptions {
  Point center{};
  double radius = 0;
  bool can_be_dynamic() const override { return true; }
};

class Sphere : public ShapeContact<Sphere> {
 public:
  explicit Sphere(const SphereOptions& o) : o_(o) {}
  Point origin() const override { return o_.center; }
  // Depth r − (|y − x| − R) of a particle at y against the sphere centred at x.
  double penetration(const double* x, const double* y, double radius, double* n) const {
    const double d[3] = {y[0] - x[0], y[1] - x[1], y[2] - x[2]};
    const double distance = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) - o_.radius;
    return outward(d, distance, radius, n);
  }

 private:
  SphereOptions o_;
};

}  // namespace

ColliderKind sphere_collider_kind() {
  return {"sphere",
          {"center", "radius"},
          [](const OptionReader& r) {
            auto o = std::make_shared<SphereOptions>();
            o->center = r.vec3("center");
            o->radius = r.positive("radius");
            return o;
          },
          [](const ColliderOptions& o) {
            return std::make_unique<Sphere>(shape_options<SphereOptions>(o));
          }};
}

}  // namespace fissure
