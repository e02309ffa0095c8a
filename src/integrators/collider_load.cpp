#include "integrators/collider_load.hpp"

#include "core/error.hpp"
#include "integrators/load_registry.hpp"

namespace fissure {

ColliderLoad::ColliderLoad(const Scene& scene) : colliders_(scene) {}

void ColliderLoad::add(double, const double* y, const double* v, double* f) {
  colliders_.add_forces(y, v, f);
}

void ColliderLoad::distribute(const Halo& halo) { colliders_.distribute(halo); }

double ColliderLoad::booked(const BookedStep& step) const {
  return colliders_.work(step.before, step.after, step.h);
}

NamedArrays ColliderLoad::saved_state() const {
  return {{"dynamics.colliders", colliders_.saved_state()}};
}

void ColliderLoad::restore_state(const NamedArrays& state) {
  const std::vector<double>* c = find_array(state, "dynamics.colliders");
  if (!c) throw InputError("", "dynamics.colliders", "missing from the checkpoint");
  colliders_.restore_state(*c);
}

std::unique_ptr<Load> make_collider_load(const Scene& scene) {
  if (scene.config.colliders.empty()) return nullptr;
  return std::make_unique<ColliderLoad>(scene);
}

}  // namespace fissure
