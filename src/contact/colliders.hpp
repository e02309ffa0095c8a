#pragma once
// Rigid colliders (spheres, planes, boxes or any registered shape, contact/collider_registry.hpp)
// pushing on the particles with a penalty force and regularised Coulomb friction. A dynamic
// sphere moves under the particles' reaction and gravity.
#include <array>
#include <memory>
#include <vector>

#include "scene/scene.hpp"

namespace fissure {

class ColliderShape;  // contact/collider_shape.hpp
class Halo;           // parallel/halo.hpp

class Colliders {
 public:
  explicit Colliders(const Scene& scene);
  ~Colliders();
  // Adds the contact force on every particle (of distribute()'s range) to f (3N) and records
  // each collider's reaction.
  void add_forces(const double* y, const double* v, double* f);
  // Over several ranks (docs/mpi.md): add_forces() pushes on the halo's rows only,
  // and advance() sums the reactions over its ranks (in rank order, the same on every rank;
  // collective). The halo must outlive this.
  void distribute(const Halo& halo);
  // Moves the colliders by one step h: kinematic ones at their velocity, dynamic spheres by
  // semi-implicit Euler under the reaction of the last add_forces and gravity.
  void advance(double h);
  // Momentum of the dynamic colliders, for balances.
  std::array<double, 3> momentum() const;
  // For checkpoints: position and velocity of every collider (6 numbers each), and back.
  std::vector<double> saved_state() const;
  void restore_state(const std::vector<double>& state);

 private:
  struct State {
    Collider settings;
    std::unique_ptr<ColliderShape> shape;
    std::array<double, 3> position;  // sphere centre, plane point, or box offset from its min
    std::array<double, 3> velocity;
    std::array<double, 3> reaction;  // force the particles exert on it, last add_forces
  };

  std::vector<State> state_;
  std::vector<double> radius_;     // contact radius per particle: ½ V^(1/3)
  std::vector<double> stiffness_;  // penalty stiffness per particle [N/m]
  double friction_;
  int begin_ = 0, end_ = 0;  // the particles add_forces() pushes on
  const Halo* halo_ = nullptr;
  std::array<double, 3> gravity_;
};

}  // namespace fissure
