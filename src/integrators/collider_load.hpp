#pragma once
// The rigid colliders (contact/colliders.hpp) as a load: their penalty and friction forces, the
// work of those forces over a step, Σ F·Δy, and the colliders' motion at the end of each step.
#include <memory>

#include "contact/colliders.hpp"
#include "integrators/load.hpp"

namespace fissure {

class ColliderLoad : public Load {
 public:
  explicit ColliderLoad(const Scene& scene);
  void add(double t, const double* y, const double* v, double* f) override;
  double booked(const BookedStep& step) const override;
  void end_step(double h) override { colliders_.advance(h); }
  void distribute(const Halo& halo) override;
  // "dynamics.colliders": position and velocity of every collider.
  NamedArrays saved_state() const override;
  void restore_state(const NamedArrays& state) override;
  const Colliders& colliders() const { return colliders_; }

 private:
  Colliders colliders_;
  std::vector<double> force_;  // 3N, at the last add()
};

}  // namespace fissure
