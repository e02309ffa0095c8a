#include "integrators/constraints.hpp"

#include <algorithm>
#include <cmath>

namespace fissure {

Constraints::Constraints(const Scene& scene)
    : mass_(scene.particles.mass), constraints_(scene.config.constraints) {
  const Particles& p = scene.particles;
  held_offsets_.push_back(0);
  for (int i = 0; i < p.count(); ++i) {
    const std::size_t before = held_by_.size();
    for (std::size_t c = 0; c < constraints_.size(); ++c)  // a clamped face holds no particle
      if (!constraints_[c].clamp && constraints_[c].region.contains(&p.reference[3 * i]))
        held_by_.push_back(static_cast<int>(c));
    if (held_by_.size() == before) continue;
    held_particles_.push_back(i);
    held_reference_.insert(held_reference_.end(), &p.reference[3 * i], &p.reference[3 * i] + 3);
    held_offsets_.push_back(static_cast<int>(held_by_.size()));
  }
  implicit_reaction_.assign(3 * held_particles_.size(), 0.0);
  explicit_reaction_.assign(3 * held_particles_.size(), 0.0);
}

int Constraints::active_constraint(std::size_t k, double t) const {
  for (int c = held_offsets_[k + 1] - 1; c >= held_offsets_[k]; --c)
    if (t < constraints_[held_by_[c]].release_at) return held_by_[c];
  return -1;
}

namespace {

// R(θ) about the unit axis a, row-major (Rodrigues: cos θ I + sin θ [a]× + (1 − cos θ) a aᵀ).
std::array<double, 9> rotation(const Vec3& a, double theta) {
  const double cos_t = std::cos(theta), sin_t = std::sin(theta), u = 1 - cos_t;
  return {cos_t + u * a[0] * a[0],        u * a[0] * a[1] - sin_t * a[2],
          u * a[0] * a[2] + sin_t * a[1], u * a[1] * a[0] + sin_t * a[2],
          cos_t + u * a[1] * a[1],        u * a[1] * a[2] - sin_t * a[0],
          u * a[2] * a[0] - sin_t * a[1], u * a[2] * a[1] + sin_t * a[0],
          cos_t + u * a[2] * a[2]};
}

Vec3 times(const std::array<double, 9>& m, const Vec3& r) {
  Vec3 out;
  for (int d = 0; d < 3; ++d) out[d] = m[3 * d] * r[0] + m[3 * d + 1] * r[1] + m[3 * d + 2] * r[2];
  return out;
}

Vec3 cross(const Vec3& w, const Vec3& r) {
  return {w[1] * r[2] - w[2] * r[1], w[2] * r[0] - w[0] * r[2], w[0] * r[1] - w[1] * r[0]};
}

double length(const Vec3& w) { return std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]); }

}  // namespace

void Constraints::hold(double t, double* a, Part part) {
  // A held particle's reaction is m (a_prescribed − a_free); a_prescribed ⟂ v (uniform
  // translation and rotation) does no work, so the ledger books −m a_free.
  std::vector<double>& reaction = part == Part::explicit_ ? explicit_reaction_ : implicit_reaction_;
  set_motions(t);
  for (std::size_t k = 0; k < held_particles_.size(); ++k) {
    const int i = held_particles_[k];
    const int c = active_constraint(k, t);
    Vec3 prescribed{};
    if (c >= 0 && motions_[c].rotates && part != Part::explicit_) {
      const Vec3& w = motions_[c].angular_velocity;
      prescribed = cross(w, cross(w, held_offset(k, c)));
    }
    for (int d = 0; d < 3; ++d) {
      reaction[3 * k + d] = c >= 0 ? -mass_[i] * a[3 * i + d] : 0.0;
      if (c >= 0) a[3 * i + d] = prescribed[d];
    }
  }
  if (part == Part::whole) std::fill(explicit_reaction_.begin(), explicit_reaction_.end(), 0.0);
}

void Constraints::set_reactions(const std::vector<double>& reaction) {
  for (std::size_t k = 0; k < held_particles_.size(); ++k)
    for (int d = 0; d < 3; ++d) {
      implicit_reaction_[3 * k + d] = reaction[3 * held_particles_[k] + d];
      explicit_reaction_[3 * k + d] = 0;
    }
}

double Constraints::work(const double* before, const double* after) const {
  double w = 0;
  for (std::size_t k = 0; k < held_particles_.size(); ++k)
    for (int d = 0; d < 3; ++d) {
      const int u = 3 * held_particles_[k] + d;
      const double reaction = implicit_reaction_[3 * k + d] + explicit_reaction_[3 * k + d];
      w += reaction * (after[u] - before[u]);
    }
  return w;
}

void Constraints::set_motions(double t) const {
  motions_.resize(constraints_.size());
  for (std::size_t c = 0; c < constraints_.size(); ++c) {
    const Constraint& s = constraints_[c];
    HeldMotion& m = motions_[c];
    m = {s.velocity, s.angular_velocity, s.center, {}, s.rotates()};
    if (!m.rotates) continue;
    const Vec3& w = s.angular_velocity;
    const double rate = length(w);
    m.rotation = rotation({w[0] / rate, w[1] / rate, w[2] / rate}, rate * t);
  }
}

Vec3 Constraints::held_offset(std::size_t k, int c) const {
  const HeldMotion& m = motions_[c];
  const double* x0 = &held_reference_[3 * k];
  return times(m.rotation, {x0[0] - m.center[0], x0[1] - m.center[1], x0[2] - m.center[2]});
}

Vec3 Constraints::held_velocity(std::size_t k, int c) const {
  const HeldMotion& m = motions_[c];
  Vec3 v = m.velocity;
  if (!m.rotates) return v;
  const Vec3 turning = cross(m.angular_velocity, held_offset(k, c));
  for (int d = 0; d < 3; ++d) v[d] += turning[d];
  return v;
}

void Constraints::held_motion(double t, double tau, const double* y, std::vector<int>& particles,
                              std::vector<Vec3>& displacements) const {
  particles.clear();
  displacements.clear();
  // each constraint's turn over tau, R(ωτ) − I
  std::vector<std::array<double, 9>> turn(constraints_.size());
  for (std::size_t c = 0; c < constraints_.size(); ++c) {
    const Vec3& w = constraints_[c].angular_velocity;
    if (!constraints_[c].rotates()) continue;
    const double rate = length(w);
    turn[c] = rotation({w[0] / rate, w[1] / rate, w[2] / rate}, rate * tau);
    for (int d = 0; d < 3; ++d) turn[c][4 * d] -= 1;
  }
  for (std::size_t k = 0; k < held_particles_.size(); ++k) {
    const int c = active_constraint(k, t);
    if (c < 0) continue;
    const Constraint& s = constraints_[c];
    const int i = held_particles_[k];
    Vec3 moved;
    for (int d = 0; d < 3; ++d) moved[d] = s.velocity[d] * tau;
    if (s.rotates()) {
      Vec3 offset;
      for (int d = 0; d < 3; ++d) offset[d] = y[3 * i + d] - s.center[d] - s.velocity[d] * t;
      const Vec3 turned = times(turn[c], offset);
      for (int d = 0; d < 3; ++d) moved[d] += turned[d];
    }
    particles.push_back(i);
    displacements.push_back(moved);
  }
}

void Constraints::held(double t, std::vector<int>& particles, std::vector<Vec3>& velocities) const {
  particles.clear();
  velocities.clear();
  set_motions(t);
  for (std::size_t k = 0; k < held_particles_.size(); ++k) {
    const int c = active_constraint(k, t);
    if (c < 0) continue;
    particles.push_back(held_particles_[k]);
    velocities.push_back(held_velocity(k, c));
  }
}

void Constraints::constrain_velocity(double t, double* v) const {
  set_motions(t);
  for (std::size_t k = 0; k < held_particles_.size(); ++k) {
    const int c = active_constraint(k, t);
    if (c < 0) continue;
    const Vec3 velocity = held_velocity(k, c);
    for (int d = 0; d < 3; ++d) v[3 * held_particles_[k] + d] = velocity[d];
  }
}

}  // namespace fissure
