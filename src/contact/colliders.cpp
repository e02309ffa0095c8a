#include "contact/colliders.hpp"

#include <algorithm>
#include <cmath>

#include "contact/contact_particles.hpp"
#include "core/error.hpp"

namespace fissure {

namespace {

// Relative tangential speed below which friction is scaled down linearly (regularised Coulomb),
// so that a resting contact does not chatter.
constexpr double kStickSpeed = 1e-3;

}  // namespace

Colliders::Colliders(const Scene& scene)
    : friction_(scene.config.contact.friction),
      gravity_{scene.config.gravity[0], scene.config.gravity[1], scene.config.gravity[2]} {
  for (const Collider& c : scene.config.colliders) {
    State s{c, {0, 0, 0}, {c.velocity[0], c.velocity[1], c.velocity[2]}, {0, 0, 0}};
    if (c.kind == Collider::Kind::sphere) s.position = {c.center[0], c.center[1], c.center[2]};
    if (c.kind == Collider::Kind::plane) s.position = {c.point[0], c.point[1], c.point[2]};
    state_.push_back(s);
  }
  auto particles = contact_particles(scene);
  radius_ = std::move(particles.radius);
  stiffness_ = std::move(particles.stiffness);
}

double Colliders::penetration(const State& c, const double* y, double radius, double* n) const {
  const auto& x = c.position;
  if (c.shape.kind == Collider::Kind::plane) {
    for (int k = 0; k < 3; ++k) n[k] = c.shape.normal[k];
    const double distance = (y[0] - x[0]) * n[0] + (y[1] - x[1]) * n[1] + (y[2] - x[2]) * n[2];
    return radius - distance;
  }
  double d[3], distance;
  if (c.shape.kind == Collider::Kind::sphere) {
    for (int k = 0; k < 3; ++k) d[k] = y[k] - x[k];
    distance = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) - c.shape.radius;
  } else {
    double inside = -1e300;  // depth of the shallowest face when the point is inside the box
    int axis = 0;
    for (int k = 0; k < 3; ++k) {
      const double lo = c.shape.min[k] + x[k], hi = c.shape.max[k] + x[k];
      d[k] = y[k] - std::clamp(y[k], lo, hi);
      const double face = std::max(lo - y[k], y[k] - hi);
      if (face > inside) inside = face, axis = k;
    }
    if (d[0] == 0 && d[1] == 0 && d[2] == 0) {
      const double mid = 0.5 * (c.shape.min[axis] + c.shape.max[axis]) + x[axis];
      for (int k = 0; k < 3; ++k) n[k] = k == axis ? (y[axis] < mid ? -1.0 : 1.0) : 0.0;
      return radius - inside;
    }
    distance = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  }
  const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (length == 0) {  // at a sphere's centre: as deep as it gets, pushed out along z
    n[0] = n[1] = 0;
    n[2] = 1;
    return radius - distance;
  }
  for (int k = 0; k < 3; ++k) n[k] = d[k] / length;
  return radius - distance;
}

void Colliders::add_forces(const double* y, const double* v, double* f) {
  const int n = static_cast<int>(radius_.size());
  for (State& c : state_) {
    double rx = 0, ry = 0, rz = 0;
#pragma omp parallel for reduction(+ : rx, ry, rz) schedule(static)
    for (int i = 0; i < n; ++i) {
      double normal[3];
      const double depth = penetration(c, y + 3 * i, radius_[i], normal);
      if (depth <= 0) continue;
      // Normal penalty force k p n and friction −μ k p v_t/max(|v_t|, v_stick).
      const double pressing = stiffness_[i] * depth;
      double relative[3], along = 0;
      for (int k = 0; k < 3; ++k) {
        relative[k] = v[3 * i + k] - c.velocity[k];
        along += relative[k] * normal[k];
      }
      double tangential[3], speed2 = 0;
      for (int k = 0; k < 3; ++k) {
        tangential[k] = relative[k] - along * normal[k];
        speed2 += tangential[k] * tangential[k];
      }
      const double drag = friction_ * pressing / std::max(std::sqrt(speed2), kStickSpeed);
      double force[3];
      for (int k = 0; k < 3; ++k) {
        force[k] = pressing * normal[k] - drag * tangential[k];
        f[3 * i + k] += force[k];
      }
      rx -= force[0];
      ry -= force[1];
      rz -= force[2];
    }
    c.reaction = {rx, ry, rz};
  }
}

void Colliders::advance(double h) {
  for (State& c : state_) {
    if (!c.shape.kinematic)
      for (int k = 0; k < 3; ++k) c.velocity[k] += h * (c.reaction[k] / c.shape.mass + gravity_[k]);
    if (c.shape.kind != Collider::Kind::plane)
      for (int k = 0; k < 3; ++k) c.position[k] += h * c.velocity[k];
  }
}

std::array<double, 3> Colliders::momentum() const {
  std::array<double, 3> p{0, 0, 0};
  for (const State& c : state_)
    if (!c.shape.kinematic)
      for (int k = 0; k < 3; ++k) p[k] += c.shape.mass * c.velocity[k];
  return p;
}

std::vector<double> Colliders::saved_state() const {
  std::vector<double> state;
  for (const State& c : state_) {
    state.insert(state.end(), c.position.begin(), c.position.end());
    state.insert(state.end(), c.velocity.begin(), c.velocity.end());
  }
  return state;
}

void Colliders::restore_state(const std::vector<double>& state) {
  if (state.size() != 6 * state_.size())
    throw InputError("", "colliders", "the checkpoint holds another number of colliders");
  for (std::size_t c = 0; c < state_.size(); ++c)
    for (int k = 0; k < 3; ++k) {
      state_[c].position[k] = state[6 * c + k];
      state_[c].velocity[k] = state[6 * c + 3 + k];
    }
}

}  // namespace fissure
