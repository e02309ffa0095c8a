#include "contact/colliders.hpp"

#include <algorithm>

#include "contact/collider_registry.hpp"
#include "contact/contact_particles.hpp"
#include "core/error.hpp"
#include "parallel/collective.hpp"
#include "parallel/halo.hpp"

namespace fissure {

Colliders::Colliders(const Scene& scene)
    : friction_(scene.config.contact.friction),
      gravity_{scene.config.gravity[0], scene.config.gravity[1], scene.config.gravity[2]} {
  for (const Collider& c : scene.config.colliders) {
    auto shape = make_collider_shape(c);
    const Point origin = shape->origin();
    state_.push_back({c, std::move(shape), origin, c.velocity, {0, 0, 0}});
  }
  auto particles = contact_particles(scene);
  radius_ = std::move(particles.radius);
  stiffness_ = std::move(particles.stiffness);
  end_ = static_cast<int>(radius_.size());
}

Colliders::~Colliders() = default;

void Colliders::add_forces(const double* y, const double* v, double* f) {
  const ContactLaw law{begin_, end_, radius_.data(), stiffness_.data(), friction_};
  for (State& c : state_) c.reaction = c.shape->add_forces(law, c.position, c.velocity, y, v, f);
}

void Colliders::distribute(const Halo& halo) {
  begin_ = halo.begin();
  end_ = halo.end();
  halo_ = &halo;
}

void Colliders::advance(double h) {
  if (halo_) {
    // each rank pushed on its own rows: the reaction is the sum over the ranks
    std::vector<double> reactions;
    for (const State& c : state_)
      reactions.insert(reactions.end(), c.reaction.begin(), c.reaction.end());
    sum_over_ranks(halo_->comm(), reactions);
    for (std::size_t k = 0; k < state_.size(); ++k)
      std::copy(reactions.begin() + 3 * k, reactions.begin() + 3 * k + 3,
                state_[k].reaction.begin());
  }
  for (State& c : state_) {
    if (!c.settings.kinematic)
      for (int k = 0; k < 3; ++k)
        c.velocity[k] += h * (c.reaction[k] / c.settings.mass + gravity_[k]);
    if (c.settings.options->moves())
      for (int k = 0; k < 3; ++k) c.position[k] += h * c.velocity[k];
  }
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
