#include "integrators/dynamics.hpp"

#include <cmath>

#include "core/error.hpp"

namespace fissure {

Dynamics::Dynamics(const Scene& scene, Model& model)
    : model_(model),
      mass_(scene.particles.mass),
      damping_(scene.config.damping),
      constraints_(scene.config.constraints) {
  for (int k = 0; k < 3; ++k) gravity_[k] = scene.config.gravity[k];
  const Particles& p = scene.particles;
  held_offsets_.push_back(0);
  for (int i = 0; i < p.count(); ++i) {
    const std::size_t before = held_by_.size();
    for (std::size_t c = 0; c < constraints_.size(); ++c)
      if (constraints_[c].region.contains(&p.reference[3 * i]))
        held_by_.push_back(static_cast<int>(c));
    if (held_by_.size() == before) continue;
    held_particles_.push_back(i);
    held_reference_.insert(held_reference_.end(), &p.reference[3 * i], &p.reference[3 * i] + 3);
    held_offsets_.push_back(static_cast<int>(held_by_.size()));
  }
  force_.resize(3 * mass_.size());
  implicit_reaction_.assign(3 * held_particles_.size(), 0.0);
  explicit_reaction_.assign(3 * held_particles_.size(), 0.0);
  if (!scene.config.colliders.empty()) {
    colliders_ = std::make_unique<Colliders>(scene);
    collider_force_.resize(3 * mass_.size());
  }
  if (scene.config.contact.self) {
    self_contact_ = std::make_unique<SelfContact>(scene, model);
    self_contact_force_.resize(3 * mass_.size());
  }
}

void Dynamics::end_step(double h) {
  if (colliders_) colliders_->advance(h);
}

int Dynamics::active_constraint(std::size_t k, double t) const {
  for (int c = held_offsets_[k + 1] - 1; c >= held_offsets_[k]; --c)
    if (t < constraints_[held_by_[c]].release_at) return held_by_[c];
  return -1;
}

void Dynamics::internal_forces(const double* y, double* f) {
  model_.forces(y, f);
  ++force_evaluations_;
}

void Dynamics::acceleration(double t, const double* y, const double* v, double* a) {
  internal_forces(y, force_.data());
  add_contact_forces(y, v, force_.data());
  const int n = static_cast<int>(mass_.size());
  const double c = damping_;
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    const double inv_m = 1.0 / mass_[i];
    for (int k = 0; k < 3; ++k)
      a[3 * i + k] = force_[3 * i + k] * inv_m + gravity_[k] - c * v[3 * i + k];
  }
  hold(t, a, implicit_reaction_);
  std::fill(explicit_reaction_.begin(), explicit_reaction_.end(), 0.0);
}

// Adds `source` to `f` in parallel.
static void add_to(const std::vector<double>& source, double* f) {
  const std::size_t n = source.size();
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < n; ++k) f[k] += source[k];
}

void Dynamics::add_contact_forces(const double* y, const double* v, double* f) {
  if (colliders_) {
    std::fill(collider_force_.begin(), collider_force_.end(), 0.0);
    colliders_->add_forces(y, v, collider_force_.data());
    add_to(collider_force_, f);
  }
  if (self_contact_) {
    std::fill(self_contact_force_.begin(), self_contact_force_.end(), 0.0);
    self_contact_->add_forces(y, self_contact_force_.data());
    add_to(self_contact_force_, f);
  }
}

Dynamics::Work Dynamics::load_work(const double* before, const double* after) const {
  Work w;
  for (std::size_t k = 0; k < held_particles_.size(); ++k)
    for (int d = 0; d < 3; ++d) {
      const int u = 3 * held_particles_[k] + d;
      const double reaction = implicit_reaction_[3 * k + d] + explicit_reaction_[3 * k + d];
      w.constraints += reaction * (after[u] - before[u]);
    }
  auto work_of = [&](const std::vector<double>& force) {
    double sum = 0;
    const std::size_t n = force.size();
#pragma omp parallel for reduction(+ : sum) schedule(static)
    for (std::size_t k = 0; k < n; ++k) sum += force[k] * (after[k] - before[k]);
    return sum;
  };
  w.colliders = work_of(collider_force_);
  w.self_contact = work_of(self_contact_force_);
  if (gravity_[0] != 0 || gravity_[1] != 0 || gravity_[2] != 0) {
    const int n = static_cast<int>(mass_.size());
    double sum = 0;
#pragma omp parallel for reduction(+ : sum) schedule(static)
    for (int i = 0; i < n; ++i)
      for (int d = 0; d < 3; ++d)
        sum += mass_[i] * gravity_[d] * (after[3 * i + d] - before[3 * i + d]);
    w.gravity = sum;
  }
  return w;
}

void Dynamics::set_constraint_reactions(const std::vector<double>& reaction) {
  for (std::size_t k = 0; k < held_particles_.size(); ++k)
    for (int d = 0; d < 3; ++d) {
      implicit_reaction_[3 * k + d] = reaction[3 * held_particles_[k] + d];
      explicit_reaction_[3 * k + d] = 0;
    }
}

void Dynamics::set_motions(double t) const {
  motions_.resize(constraints_.size());
  for (std::size_t c = 0; c < constraints_.size(); ++c) {
    const Constraint& s = constraints_[c];
    HeldMotion& m = motions_[c];
    m = {s.velocity, s.angular_velocity, s.center, {}, s.rotates()};
    if (!m.rotates) continue;
    const Vec3& w = s.angular_velocity;
    const double rate = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    const Vec3 a = {w[0] / rate, w[1] / rate, w[2] / rate};
    // Rodrigues: R = cos θ I + sin θ [a]× + (1 − cos θ) a aᵀ, θ = |ω| t
    const double cos_t = std::cos(rate * t), sin_t = std::sin(rate * t), u = 1 - cos_t;
    m.rotation = {cos_t + u * a[0] * a[0],        u * a[0] * a[1] - sin_t * a[2],
                  u * a[0] * a[2] + sin_t * a[1], u * a[1] * a[0] + sin_t * a[2],
                  cos_t + u * a[1] * a[1],        u * a[1] * a[2] - sin_t * a[0],
                  u * a[2] * a[0] - sin_t * a[1], u * a[2] * a[1] + sin_t * a[0],
                  cos_t + u * a[2] * a[2]};
  }
}

Vec3 Dynamics::held_velocity(std::size_t k, int c) const {
  const HeldMotion& m = motions_[c];
  Vec3 v = m.velocity;
  if (!m.rotates) return v;
  const double* x0 = &held_reference_[3 * k];
  const Vec3 r0 = {x0[0] - m.center[0], x0[1] - m.center[1], x0[2] - m.center[2]};
  Vec3 r;
  for (int d = 0; d < 3; ++d)
    r[d] =
        m.rotation[3 * d] * r0[0] + m.rotation[3 * d + 1] * r0[1] + m.rotation[3 * d + 2] * r0[2];
  const Vec3& w = m.angular_velocity;
  v[0] += w[1] * r[2] - w[2] * r[1];
  v[1] += w[2] * r[0] - w[0] * r[2];
  v[2] += w[0] * r[1] - w[1] * r[0];
  return v;
}

void Dynamics::hold(double t, double* a, std::vector<double>& reaction) const {
  // A held particle's reaction is m (a_prescribed − a_free); a_prescribed ⟂ v (uniform
  // translation and rotation) does no work, so the ledger books −m a_free.
  for (std::size_t k = 0; k < held_particles_.size(); ++k) {
    const int i = held_particles_[k];
    const bool active = active_constraint(k, t) >= 0;
    for (int d = 0; d < 3; ++d) {
      reaction[3 * k + d] = active ? -mass_[i] * a[3 * i + d] : 0.0;
      if (active) a[3 * i + d] = 0;
    }
  }
}

void Dynamics::implicit_acceleration(double t, const double* y, const double* v, double* a) {
  internal_forces(y, force_.data());
  const int n = static_cast<int>(mass_.size());
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k)
      a[3 * i + k] = force_[3 * i + k] / mass_[i] - damping_ * v[3 * i + k];
  hold(t, a, implicit_reaction_);
}

void Dynamics::explicit_acceleration(double t, const double* y, const double* v, double* a) {
  external_forces(y, v, a);
  const int n = static_cast<int>(mass_.size());
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) a[3 * i + k] /= mass_[i];
  hold(t, a, explicit_reaction_);
}

void Dynamics::external_forces(const double* y, const double* v, double* f) {
  const int n = static_cast<int>(mass_.size());
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) f[3 * i + k] = mass_[i] * gravity_[k];
  add_contact_forces(y, v, f);
}

void Dynamics::held(double t, std::vector<int>& particles, std::vector<Vec3>& velocities) const {
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

void Dynamics::constrain_velocity(double t, double* v) const {
  set_motions(t);
  for (std::size_t k = 0; k < held_particles_.size(); ++k) {
    const int c = active_constraint(k, t);
    if (c < 0) continue;
    const Vec3 velocity = held_velocity(k, c);
    for (int d = 0; d < 3; ++d) v[3 * held_particles_[k] + d] = velocity[d];
  }
}

NamedArrays Dynamics::saved_state() const {
  NamedArrays state = {{"dynamics.force_evaluations", {double(force_evaluations_)}}};
  if (colliders_) state.emplace_back("dynamics.colliders", colliders_->saved_state());
  return state;
}

void Dynamics::restore_state(const NamedArrays& state) {
  if (const std::vector<double>* n = find_array(state, "dynamics.force_evaluations"))
    force_evaluations_ = static_cast<long>(n->at(0));
  if (colliders_) {
    const std::vector<double>* c = find_array(state, "dynamics.colliders");
    if (!c) throw InputError("", "dynamics.colliders", "missing from the checkpoint");
    colliders_->restore_state(*c);
  }
}

}  // namespace fissure
