#include "integrators/dynamics.hpp"

namespace fissure {

Dynamics::Dynamics(const Scene& scene, Model& model)
    : model_(model), mass_(scene.particles.mass), damping_(scene.config.damping) {
  for (int k = 0; k < 3; ++k) gravity_[k] = scene.config.gravity[k];
  const Particles& p = scene.particles;
  const auto& constraints = scene.config.constraints;
  for (const Constraint& c : constraints)
    held_.push_back({{}, {c.velocity[0], c.velocity[1], c.velocity[2]}, c.release_at});
  // Each particle belongs to the last constraint whose region holds it: later constraints
  // override earlier ones, also after their release.
  for (int i = 0; i < p.count(); ++i)
    for (int c = static_cast<int>(constraints.size()) - 1; c >= 0; --c)
      if (constraints[c].region.contains(&p.reference[3 * i])) {
        held_[c].particles.push_back(i);
        break;
      }
  force_.resize(3 * mass_.size());
}

void Dynamics::acceleration(double t, const double* y, const double* v, double* a) {
  model_.forces(y, force_.data());
  const int n = particle_count();
  const double c = damping_;
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    const double inv_m = 1.0 / mass_[i];
    for (int k = 0; k < 3; ++k)
      a[3 * i + k] = force_[3 * i + k] * inv_m + gravity_[k] - c * v[3 * i + k];
  }
  // A held particle moves at constant velocity: its reaction is −m a_free, its power −m a_free·v.
  constraint_power_ = 0;
  for (const Held& h : held_) {
    if (t >= h.release_at) continue;
    for (int i : h.particles)
      for (int k = 0; k < 3; ++k) {
        constraint_power_ -= mass_[i] * a[3 * i + k] * h.velocity[k];
        a[3 * i + k] = 0;
      }
  }
}

void Dynamics::constrain_velocity(double t, double* v) const {
  for (const Held& h : held_) {
    if (t >= h.release_at) continue;
    for (int i : h.particles)
      for (int k = 0; k < 3; ++k) v[3 * i + k] = h.velocity[k];
  }
}

}  // namespace fissure
