#pragma once
// A rigid collider's shape: where it starts, and the penalty and friction forces it exerts on the
// particles it touches. A shape is one file that registers itself (contact/collider_registry.hpp)
// and gives its penetration depth as a plain inline function, so the force loop over the
// particles (ShapeContact) is compiled per shape without a virtual call per particle.
#include <algorithm>
#include <array>
#include <cmath>

namespace fissure {

using Point = std::array<double, 3>;

// What the particles bring to a contact (contact/contact_particles.hpp), and Coulomb's μ; the
// particles [begin, end) it acts on (a rank's rows, or all).
struct ContactLaw {
  int begin, end;
  const double* radius;     // ½ V^(1/3) per particle
  const double* stiffness;  // penalty stiffness per particle [N/m]
  double friction;
};

class ColliderShape {
 public:
  virtual ~ColliderShape() = default;
  // Where its reference point starts: a sphere's centre, a plane's point, 0 for a box (whose
  // position is its offset from where the config put it).
  virtual Point origin() const = 0;
  // Adds the contact force on the law's particles (positions y, velocities v, 3N) to f, with the
  // collider's reference point at `position` moving at `velocity`; returns the force the
  // particles exert on it (the reaction).
  virtual Point add_forces(const ContactLaw& law, const Point& position, const Point& velocity,
                           const double* y, const double* v, double* f) const = 0;
};

// Relative tangential speed below which friction is scaled down linearly (regularised Coulomb),
// so that a resting contact does not chatter.
constexpr double kStickSpeed = 1e-3;

// The penalty force k p n and friction −μ k p v_t/max(|v_t|, v_stick) of every particle at
// penetration depth p > 0 along the outward normal n that Shape::penetration(x, y, r, n)
// returns for its reference point x.
template <class Shape>
class ShapeContact : public ColliderShape {
 public:
  Point add_forces(const ContactLaw& law, const Point& position, const Point& velocity,
                   const double* y, const double* v, double* f) const override {
    const Shape& shape = static_cast<const Shape&>(*this);
    double rx = 0, ry = 0, rz = 0;
#pragma omp parallel for reduction(+ : rx, ry, rz) schedule(static)
    for (int i = law.begin; i < law.end; ++i) {
      double normal[3];
      const double depth = shape.penetration(position.data(), y + 3 * i, law.radius[i], normal);
      if (depth <= 0) continue;
      const double pressing = law.stiffness[i] * depth;
      double relative[3], along = 0;
      for (int k = 0; k < 3; ++k) {
        relative[k] = v[3 * i + k] - velocity[k];
        along += relative[k] * normal[k];
      }
      double tangential[3], speed2 = 0;
      for (int k = 0; k < 3; ++k) {
        tangential[k] = relative[k] - along * normal[k];
        speed2 += tangential[k] * tangential[k];
      }
      const double drag = law.friction * pressing / std::max(std::sqrt(speed2), kStickSpeed);
      double force[3];
      for (int k = 0; k < 3; ++k) {
        force[k] = pressing * normal[k] - drag * tangential[k];
        f[3 * i + k] += force[k];
      }
      rx -= force[0];
      ry -= force[1];
      rz -= force[2];
    }
    return {rx, ry, rz};
  }
};

// Depth r − distance of a particle of radius r whose offset from the nearest point of a convex
// shape is d, normal d/|d|; at d = 0 (a sphere's centre) it is pushed out along z.
inline double outward(const double* d, double distance, double radius, double* n) {
  const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (length == 0) {
    n[0] = n[1] = 0;
    n[2] = 1;
    return radius - distance;
  }
  for (int k = 0; k < 3; ++k) n[k] = d[k] / length;
  return radius - distance;
}

}  // namespace fissure
