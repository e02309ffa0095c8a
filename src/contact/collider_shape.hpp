#pragma once
// A rigid collider's shape: where it starts, and the penalty and friction forces it exerts on the
// particles it touches. A shape is one file that registers itself (contact/collider_registry.hpp)
// and gives its penetration depth as a plain inline function, so the loops over the particles
// (ShapeContact) are compiled per shape without a virtual call per particle.
//
// A particle at penetration depth p > 0 (its contact reach minus its distance from the shape)
// stores the penalty energy ½ k p² and feels its force k p n along the outward normal n
// (docs/integrators.md, "Contact"). Explicit integrators take the force with regularised Coulomb
// friction, −μ k p v_t / max(|v_t|, v_stick); implicit ones take the energy into the step's
// potential at each iterate, with its gradient and the positive-semidefinite part of its Hessian,
// k n nᵀ (exact for a plane and a box's faces; a sphere's or an edge's curvature term is negative
// and is left out, IPC's per-contact projection).
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "contact/contact_law.hpp"
#include "contact/secant_penalty.hpp"

namespace fissure {

class ColliderShape {
 public:
  virtual ~ColliderShape() = default;
  // Where its reference point starts: a sphere's centre, a plane's point, 0 for a box (whose
  // position is its offset from where the config put it).
  virtual Point origin() const = 0;
  // Depth of one particle at y of contact radius r with the reference point at `position`, and
  // the outward normal n (not for loops over the particles).
  virtual double depth(const Point& position, const double* y, double radius, double* n) const = 0;
  // Explicit: adds the penalty and friction forces on the law's particles (positions y,
  // velocities v, 3N) to f and the friction forces alone to `friction` (3N), with the collider's
  // reference point at `position` moving at `velocity`.
  virtual ContactSums add_forces(const ContactLaw& law, const Point& position,
                                 const Point& velocity, const double* y, const double* v, double* f,
                                 double* friction) const = 0;
  // Σ ½ k p² over the law's particles at y [J].
  virtual double energy(const ContactLaw& law, const Point& position, const double* y) const = 0;
  // Implicit: the penalty energy at z; adds its gradient −k p n to `gradient` (3N, or null) and
  // k n nᵀ to each particle's 3×3 block in `blocks` (9N, or null); the normal forces' sum into
  // `sums`. With `start_depth` (the depths p0 at the step's start, N, or null) it takes the
  // secant from p0 instead (contact/secant_penalty.hpp): energy G, gradient −G' n, block G'' n nᵀ.
  virtual double penalty(const ContactLaw& law, const Point& position, const double* z,
                         const double* start_depth, double* gradient, double* blocks,
                         ContactSums& sums) const = 0;
  // The depth of each of the law's particles at y into `out` (N).
  virtual void depths(const ContactLaw& law, const Point& position, const double* y,
                      double* out) const = 0;
  // The contacts at y, for the step's lagged friction, each anchored at `anchor` (3N).
  virtual void lag(const ContactLaw& law, const Point& position, const double* y,
                   const double* anchor, std::vector<LaggedContact>& out) const = 0;
  // The largest fraction α ≤ 1 of the update dz from z that keeps every particle's depth within
  // its bound: its contact reach (its centre never crosses the shape's surface), or its depth at
  // z where that is deeper already.
  virtual double max_step(const ContactLaw& law, const Point& position, const double* z,
                          const double* dz) const = 0;
};

// Relative tangential speed below which friction is scaled down linearly (regularised Coulomb),
// so that a resting contact does not chatter: ε_v of the friction potential.
constexpr double kStickSpeed = 1e-3;

template <class Shape>
class ShapeContact : public ColliderShape {
 public:
  double depth(const Point& position, const double* y, double radius, double* n) const override {
    return self().penetration(position.data(), y, radius, n);
  }

  ContactSums add_forces(const ContactLaw& law, const Point& position, const Point& velocity,
                         const double* y, const double* v, double* f,
                         double* friction) const override {
    double nx = 0, ny = 0, nz = 0, tx = 0, ty = 0, tz = 0;
#pragma omp parallel for reduction(+ : nx, ny, nz, tx, ty, tz) schedule(static)
    for (int i = law.begin; i < law.end; ++i) {
      double normal[3];
      const double p = self().penetration(position.data(), y + 3 * i, law.reach[i], normal);
      if (p <= 0) continue;
      const double pressing = law.stiffness[i] * p;
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
      double push[3], rub[3];
      for (int k = 0; k < 3; ++k) {
        push[k] = pressing * normal[k];
        rub[k] = -drag * tangential[k];
        f[3 * i + k] += push[k] + rub[k];
        friction[3 * i + k] += rub[k];
      }
      nx += push[0], ny += push[1], nz += push[2];
      tx += rub[0], ty += rub[1], tz += rub[2];
    }
    return {{nx, ny, nz}, {tx, ty, tz}};
  }

  double energy(const ContactLaw& law, const Point& position, const double* y) const override {
    double sum = 0;
#pragma omp parallel for reduction(+ : sum) schedule(static)
    for (int i = law.begin; i < law.end; ++i) {
      double normal[3];
      const double p = self().penetration(position.data(), y + 3 * i, law.reach[i], normal);
      if (p > 0) sum += 0.5 * law.stiffness[i] * p * p;
    }
    return sum;
  }

  double penalty(const ContactLaw& law, const Point& position, const double* z,
                 const double* start_depth, double* gradient, double* blocks,
                 ContactSums& sums) const override {
    double sum = 0, nx = 0, ny = 0, nz = 0;
#pragma omp parallel for reduction(+ : sum, nx, ny, nz) schedule(static)
    for (int i = law.begin; i < law.end; ++i) {
      double n[3];
      const double p = self().penetration(position.data(), z + 3 * i, law.reach[i], n);
      const double k = law.stiffness[i];
      // ½ k p², or the secant G from the step's start; force, and the block's coefficient
      SecantPenalty e{0.5 * k * p * p, k * p, k};
      if (start_depth)
        e = secant_penalty(k, start_depth[i], p);
      else if (p <= 0)
        continue;
      if (e.slope == 0 && e.curvature == 0) continue;
      sum += e.energy;
      nx += e.slope * n[0], ny += e.slope * n[1], nz += e.slope * n[2];
      if (gradient)
        for (int a = 0; a < 3; ++a) gradient[3 * i + a] -= e.slope * n[a];  // ∂p/∂z = −n
      if (blocks)
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) blocks[9 * i + 3 * a + b] += e.curvature * n[a] * n[b];
    }
    sums.normal[0] += nx, sums.normal[1] += ny, sums.normal[2] += nz;
    return sum;
  }

  void depths(const ContactLaw& law, const Point& position, const double* y,
              double* out) const override {
#pragma omp parallel for schedule(static)
    for (int i = law.begin; i < law.end; ++i) {
      double n[3];
      out[i] = self().penetration(position.data(), y + 3 * i, law.reach[i], n);
    }
  }

  void lag(const ContactLaw& law, const Point& position, const double* y, const double* anchor,
           std::vector<LaggedContact>& out) const override {
    for (int i = law.begin; i < law.end; ++i) {
      LaggedContact c{i, 0, {0, 0, 0}, {anchor[3 * i], anchor[3 * i + 1], anchor[3 * i + 2]}};
      const double p = self().penetration(position.data(), y + 3 * i, law.reach[i], c.normal);
      if (p <= 0 || law.friction <= 0) continue;
      c.limit = law.friction * law.stiffness[i] * p;  // μλ, λ = k p
      out.push_back(c);
    }
  }

  double max_step(const ContactLaw& law, const Point& position, const double* z,
                  const double* dz) const override {
    double alpha = 1;
#pragma omp parallel for reduction(min : alpha) schedule(static)
    for (int i = law.begin; i < law.end; ++i) {
      double n[3], w[3];
      for (int k = 0; k < 3; ++k) w[k] = z[3 * i + k] + dz[3 * i + k];
      const double* x = position.data();
      // the full update is admitted where it ends within the reach (at most as deep as at z)
      const double end = self().penetration(x, w, law.reach[i], n);
      if (end <= law.reach[i]) continue;
      const double bound =
          std::max(law.reach[i], self().penetration(x, z + 3 * i, law.reach[i], n));
      if (end <= bound) continue;
      // the depth along the update is continuous: bisect for where it reaches the bound
      double lo = 0, hi = 1;
      for (int it = 0; it < 40; ++it) {
        const double mid = 0.5 * (lo + hi);
        for (int k = 0; k < 3; ++k) w[k] = z[3 * i + k] + mid * dz[3 * i + k];
        (self().penetration(x, w, law.reach[i], n) <= bound ? lo : hi) = mid;
      }
      alpha = std::min(alpha, lo);
    }
    return alpha;
  }

 private:
  const Shape& self() const { return static_cast<const Shape&>(*this); }
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
