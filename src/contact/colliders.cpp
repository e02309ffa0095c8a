#include "contact/colliders.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "contact/collider_registry.hpp"
#include "contact/contact_particles.hpp"
#include "contact/lagged_friction.hpp"
#include "core/error.hpp"
#include "parallel/collective.hpp"
#include "parallel/halo.hpp"

namespace fissure {

namespace {

// Each particle's reach against the collider at `origin`: its radius less its overlap at load.
// Throws InputError for a particle whose centre starts inside the collider.
std::vector<double> reach_at_load(const Scene& scene, const ColliderShape& shape,
                                  const Point& origin, const std::vector<double>& radius,
                                  std::size_t index) {
  const Particles& p = scene.particles;
  std::vector<double> reach = radius;
  for (int i = 0; i < p.count(); ++i) {
    double n[3];
    const double overlap = shape.depth(origin, &p.reference[3 * i], radius[i], n);
    if (overlap <= 0) continue;
    if (overlap > radius[i]) {
      const double* x = &p.reference[3 * i];
      throw InputError(
          scene.config.file, fmt::format("colliders[{}]", index),
          fmt::format("body '{}' starts inside this {}: its particle at ({:.4g}, {:.4g}, {:.4g}) "
                      "is {:.3g} m inside (a body may touch a collider, its particles' centres "
                      "outside it, but not overlap it); move the body or the collider",
                      scene.config.bodies[p.body[i]].name, scene.config.colliders[index].shape,
                      x[0], x[1], x[2], overlap - radius[i]));
    }
    reach[i] = radius[i] - overlap;  // touching as sampled: at rest in contact
  }
  return reach;
}

}  // namespace

Colliders::Colliders(const Scene& scene)
    : friction_(scene.config.contact.friction),
      gravity_{scene.config.gravity[0], scene.config.gravity[1], scene.config.gravity[2]} {
  auto particles = contact_particles(scene);
  stiffness_ = std::move(particles.stiffness);
  for (const Collider& c : scene.config.colliders) {
    auto shape = make_collider_shape(c);
    const Point origin = shape->origin();
    auto reach = reach_at_load(scene, *shape, origin, particles.radius, state_.size());
    state_.push_back(
        {c, std::move(shape), origin, c.velocity, {}, std::move(reach), origin, {}, {}});
  }
  end_ = static_cast<int>(stiffness_.size());
  friction_force_.assign(3 * stiffness_.size(), 0.0);
}

Colliders::~Colliders() = default;

ContactLaw Colliders::law(const State& c) const {
  return {begin_, end_, c.reach.data(), stiffness_.data(), friction_};
}

void Colliders::add_forces(const double* y, const double* v, double* f) {
  std::fill(friction_force_.begin(), friction_force_.end(), 0.0);
  for (State& c : state_)
    c.sums = c.shape->add_forces(law(c), c.position, c.velocity, y, v, f, friction_force_.data());
}

double Colliders::energy(const double* y) const {
  double sum = 0;
  for (const State& c : state_) sum += c.shape->energy(law(c), c.position, y);
  return sum;
}

void Colliders::begin_stage(const double* y, const double* anchor, double span, double elapsed,
                            bool secant) {
  stage_span_ = span;
  for (State& c : state_) {
    for (int k = 0; k < 3; ++k) c.stage[k] = c.position[k] + elapsed * c.velocity[k];
    c.lagged.clear();
    if (span > 0) c.shape->lag(law(c), c.position, y, anchor, c.lagged);
    c.start_depth.clear();
    // Not with friction: the secant keeps a contact's normal oscillation, so that its depth at a
    // step's start, which sets the lagged Coulomb limit, swings between 0 and twice the resting
    // one (Newmark's block on the incline slid 82% too far)
    if (secant && friction_ == 0) {
      c.start_depth.resize(stiffness_.size());
      c.shape->depths(law(c), c.position, y, c.start_depth.data());
    }
  }
}

double Colliders::potential(const double* z, double* gradient, double* blocks) {
  // an evaluation of the forces (a gradient) is what the books and a dynamic collider take
  const bool record = gradient != nullptr;
  if (record) std::fill(friction_force_.begin(), friction_force_.end(), 0.0);
  double energy = 0;
  for (State& c : state_) {
    ContactSums sums;
    energy +=
        c.shape->penalty(law(c), c.stage, z, c.start_depth.empty() ? nullptr : c.start_depth.data(),
                         gradient, blocks, sums);
    // the slip u = span × the tangential velocity relative to the collider
    const Point shift = {stage_span_ * c.velocity[0], stage_span_ * c.velocity[1],
                         stage_span_ * c.velocity[2]};
    for (const LaggedContact& contact : c.lagged) {
      const int i = contact.particle;
      double u[3], g[3] = {0, 0, 0};
      slip(contact, z, shift, u);
      energy += lagged_friction(contact, u, stage_span_, g, blocks ? blocks + 9 * i : nullptr);
      if (record)
        for (int k = 0; k < 3; ++k) {
          gradient[3 * i + k] += g[k];
          friction_force_[3 * i + k] -= g[k];
          sums.friction[k] -= g[k];
        }
    }
    if (record) c.sums = sums;
  }
  return energy;
}

double Colliders::max_step(const double* z, const double* dz) const {
  double alpha = 1;
  for (const State& c : state_) alpha = std::min(alpha, c.shape->max_step(law(c), c.stage, z, dz));
  return alpha;
}

void Colliders::distribute(const Halo& halo) {
  begin_ = halo.begin();
  end_ = halo.end();
  halo_ = &halo;
}

void Colliders::advance(double h) {
  std::vector<double> reactions;
  for (const State& c : state_)
    for (int k = 0; k < 3; ++k) reactions.push_back(-(c.sums.normal[k] + c.sums.friction[k]));
  // each rank pushed on its own rows: the reaction is the sum over the ranks
  if (halo_) sum_over_ranks(halo_->comm(), reactions);
  for (std::size_t n = 0; n < state_.size(); ++n) {
    State& c = state_[n];
    if (!c.settings.kinematic)
      for (int k = 0; k < 3; ++k)
        c.velocity[k] += h * (reactions[3 * n + k] / c.settings.mass + gravity_[k]);
    if (c.settings.options->moves())
      for (int k = 0; k < 3; ++k) c.position[k] += h * c.velocity[k];
  }
}

double Colliders::work(const double* before, const double* after, double h) const {
  double sum = 0;
  for (const State& c : state_)
    if (c.settings.options->moves())
      for (int k = 0; k < 3; ++k) sum += c.sums.normal[k] * h * c.velocity[k];
  const std::size_t first = 3 * std::size_t(begin_), end = 3 * std::size_t(end_);
  for (std::size_t k = first; k < end; ++k) sum += friction_force_[k] * (after[k] - before[k]);
  return sum;
}

std::array<double, 3> Colliders::momentum() const {
  std::array<double, 3> p{0, 0, 0};
  for (const State& c : state_)
    if (!c.settings.kinematic)
      for (int k = 0; k < 3; ++k) p[k] += c.settings.mass * c.velocity[k];
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
