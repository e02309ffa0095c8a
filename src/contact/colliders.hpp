#pragma once
// Rigid colliders (spheres, planes, boxes or any registered shape, contact/collider_registry.hpp)
// pushing on the particles with a penalty force and regularised Coulomb friction. A dynamic
// sphere moves under the particles' reaction and gravity.
//
// A body may start touching a collider as sampled (a box with its bottom face on a plane): each
// particle's contact reach against each collider is its radius ½ V^(1/3) less its overlap at
// load, so that it starts at rest in contact and presses only when it moves further in. A
// particle whose centre starts inside a collider is refused at load (docs/config.md, colliders).
#include <array>
#include <memory>
#include <vector>

#include "contact/contact_law.hpp"
#include "scene/scene.hpp"

namespace fissure {

class ColliderShape;  // contact/collider_shape.hpp
class Halo;           // parallel/halo.hpp

class Colliders {
 public:
  // Throws InputError naming the collider and the body when a particle's centre starts inside a
  // collider.
  explicit Colliders(const Scene& scene);
  ~Colliders();
  // Adds the contact force on every particle (of distribute()'s range) to f (3N) and records
  // each collider's reaction and the friction forces.
  void add_forces(const double* y, const double* v, double* f);
  // The penalty energy Σ ½ k p² stored in the contacts at y, over distribute()'s range [J].
  double energy(const double* y) const;

  // Implicit steps: contact as a potential of the positions z at the end of a stage
  // (docs/integrators.md, "Contact"). begin_stage() places the colliders where they are
  // `elapsed` after the step's start and lags the friction of the contacts at the step's start y,
  // on the stage's velocity (z − anchor)/span (integrators/load.hpp, PotentialStage); potential()
  // returns the penalty and friction energy at z and adds its gradient (3N, or null) and its
  // positive-semidefinite Hessian blocks (9N, or null); with a gradient it records the forces
  // as add_forces does. With `secant` and no friction the penalty is the secant from the
  // depths at y (contact/secant_penalty.hpp), each collider at its place at the step's start.
  void begin_stage(const double* y, const double* anchor, double span, double elapsed,
                   bool secant = false);
  double potential(const double* z, double* gradient, double* blocks);
  // The largest fraction α ≤ 1 of the update dz from z that keeps each particle within its
  // bound (ShapeContact::max_step), over distribute()'s range.
  double max_step(const double* z, const double* dz) const;

  // Over several ranks (docs/mpi.md): add_forces() pushes on the halo's rows only,
  // and advance() sums the reactions over its ranks (in rank order, the same on every rank;
  // collective). The halo must outlive this.
  void distribute(const Halo& halo);
  // Moves the colliders by one step h: kinematic ones at their velocity, dynamic spheres by
  // semi-implicit Euler under the reaction of the last evaluation and gravity.
  void advance(double h);
  // The work the colliders did on the particles over the last step h (after advance()): the
  // normal forces times the colliders' own displacement, plus the friction forces times the
  // particles' displacement from `before` to `after` (3N), this rank's rows [J]. The normal
  // forces' work relative to the colliders is the change of energy().
  double work(const double* before, const double* after, double h) const;
  // Coulomb's μ against the colliders (contact.friction).
  double friction() const { return friction_; }
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
    ContactSums sums;                   // the forces on the particles at the last evaluation
    std::vector<double> reach;          // contact reach per particle
    std::array<double, 3> stage;        // implicit: position at the stage's end
    std::vector<LaggedContact> lagged;  // implicit: the contacts at the stage's start
    std::vector<double> start_depth;    // implicit, secant: the depths at the step's start (N)
  };
  ContactLaw law(const State& c) const;

  std::vector<State> state_;
  std::vector<double> stiffness_;       // penalty stiffness per particle [N/m]
  std::vector<double> friction_force_;  // 3N, at the last evaluation
  double friction_;
  int begin_ = 0, end_ = 0;  // the particles add_forces() pushes on
  const Halo* halo_ = nullptr;
  std::array<double, 3> gravity_;
  double stage_span_ = 0;  // implicit: the stage's span (its velocity (z − anchor)/span)
};

}  // namespace fissure
