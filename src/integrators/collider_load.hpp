#pragma once
// The rigid colliders (contact/colliders.hpp) as a load: their penalty and friction forces, the
// penalty energy they store, the work the moving colliders and friction do over a step, and the
// colliders' motion at the end of each step. Implicit integrators take them as a potential of
// the positions (LoadPotential).
#include <memory>

#include "contact/colliders.hpp"
#include "integrators/load.hpp"

namespace fissure {

class ColliderLoad : public Load, public LoadPotential {
 public:
  explicit ColliderLoad(const Scene& scene);
  void add(double t, const double* y, const double* v, double* f) override;
  // The colliders' work (Colliders::work): moving colliders' normal forces and friction.
  double booked(const BookedStep& step) const override;
  double stored_energy(const double* y) const override { return colliders_.energy(y); }
  void end_step(double h) override { colliders_.advance(h); }
  void distribute(const Halo& halo) override;
  LoadPotential* potential() override { return this; }
  void begin_stage(const PotentialStage& s) override {
    colliders_.begin_stage(s.start, s.anchor, s.span, s.elapsed, s.secant);
  }
  double evaluate(const double* z, double* gradient, double* blocks) override {
    return colliders_.potential(z, gradient, blocks);
  }
  bool contact() const override { return true; }
  double max_step(const double* z, const double* dz) const override {
    return colliders_.max_step(z, dz);
  }
  // "dynamics.colliders": position and velocity of every collider.
  NamedArrays saved_state() const override;
  void restore_state(const NamedArrays& state) override;
  const Colliders& colliders() const { return colliders_; }

 private:
  Colliders colliders_;
};

}  // namespace fissure
