// A plane collider: colliders[i].plane {point, normal}, the normal pointing to the free side; it
// does not move.
#include <cmath>

#include "contact/collider_registry.hpp"

namespace fissure {

namespace {

struct PlaneOptions : ColliderOptions {
  Point point{};
  Point normal{};  // unit
  bool moves() const override { return false; }
};

class Plane : public ShapeContact<Plane> {
 public:
  explicit Plane(const PlaneOptions& o) : o_(o) {}
  Point origin() const override { return o_.point; }
  // Depth r − (y − x)·n of a particle at y against the plane through x.
  double penetration(const double* x, const double* y, double radius, double* n) const {
    for (int k = 0; k < 3; ++k) n[k] = o_.normal[k];
    const double distance = (y[0] - x[0]) * n[0] + (y[1] - x[1]) * n[1] + (y[2] - x[2]) * n[2];
    return radius - distance;
  }

 private:
  PlaneOptions o_;
};

}  // namespace

ColliderKind plane_collider_kind() {
  return {"plane",
          {"point", "normal"},
          [](const OptionReader& r) {
            auto o = std::make_shared<PlaneOptions>();
            o->point = r.vec3("point");
            o->normal = r.vec3("normal");
            const double length =
                std::sqrt(o->normal[0] * o->normal[0] + o->normal[1] * o->normal[1] +
                          o->normal[2] * o->normal[2]);
            if (length == 0) r.fail("normal", "must not be zero");
            for (double& v : o->normal) v /= length;
            return o;
          },
          [](const ColliderOptions& o) {
            return std::make_unique<Plane>(shape_options<PlaneOptions>(o));
          }};
}

}  // namespace fissure
