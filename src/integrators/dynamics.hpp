#pragma once
// The equation of motion the integrators advance: M ÿ = F_int(y) + M g − c M ẏ (Eq 2 with
// gravity and mass-proportional damping), with kinematic constraints on regions.
#include <array>
#include <memory>
#include <vector>

#include "contact/colliders.hpp"
#include "contact/self_contact.hpp"
#include "model/model.hpp"
#include "scene/scene.hpp"

namespace fissure {

class Dynamics {
 public:
  Dynamics(const Scene& scene, Model& model);

  // a = F_int(y)/m + g − c v, zero where a constraint holds the particle at time t.
  // Also records the forces of the constraints and the contacts (load_work()).
  void acceleration(double t, const double* y, const double* v, double* a);
  // The same split in two, for implicit–explicit methods: a = implicit + explicit.
  //   implicit: F_int(y)/m − c v (stiff, elastic);  explicit: g + F_contact(y, v)/m.
  // Both are zero where a constraint holds the particle at time t.
  void implicit_acceleration(double t, const double* y, const double* v, double* a);
  void explicit_acceleration(double t, const double* y, const double* v, double* a);
  // The model's internal forces F_int(y), 3N, overwritten; counted in force_evaluations().
  void internal_forces(const double* y, double* f);
  long force_evaluations() const { return force_evaluations_; }
  // Counts an evaluation of F_int made by the model directly (with its energy, say).
  void count_force_evaluation() { ++force_evaluations_; }
  // External forces M g + F_contact(y, v) (colliders and self-contact), 3N, overwritten.
  void external_forces(const double* y, const double* v, double* f);
  // Sets the velocity of every particle held by a constraint active at time t.
  void constrain_velocity(double t, double* v) const;
  // The particles a constraint holds at time t and the velocity each one moves at.
  void held(double t, std::vector<int>& particles, std::vector<Vec3>& velocities) const;
  Model& model() { return model_; }
  const Model& model() const { return model_; }
  const std::vector<double>& mass() const { return mass_; }
  double damping() const { return damping_; }
  const double* gravity() const { return gravity_; }
  // Ends a completed step of size h: moves the colliders.
  void end_step(double h);
  // The colliders, or nullptr when the scene has none.
  const Colliders* colliders() const { return colliders_.get(); }
  // For checkpoints: the colliders' motion and the force-evaluation counter, and back.
  NamedArrays saved_state() const;
  void restore_state(const NamedArrays& state);
  // Work gravity, the constraints, colliders and self-contact did on the particles over a step
  // from positions `before` to `after`, with the forces of their last evaluation: Σ F·Δy [J]
  // (exact for gravity, and summed per step so that tiny steps lose nothing to cancellation).
  struct Work {
    double gravity = 0, constraints = 0, colliders = 0, self_contact = 0;
  };
  Work load_work(const double* before, const double* after) const;
  // For integrators that hold particles through their own equations (petsc_newton): the
  // constraint reactions they computed, 3N (read on held particles only).
  void set_constraint_reactions(const std::vector<double>& reaction);

 private:
  // The constraint holding particle held_particles_[k] at time t: the last one in config order
  // that contains it and is not yet released, or −1.
  int active_constraint(std::size_t k, double t) const;
  // Zeroes a where a constraint holds the particle at time t; records the reactions −m a_free,
  // 3 per held particle, into `reaction`.
  void hold(double t, double* a, std::vector<double>& reaction) const;
  // Adds the colliders' and self-contact forces to f and records them.
  void add_contact_forces(const double* y, const double* v, double* f);
  // The rigid motion each constraint prescribes at one time: its velocity and, for a rotating
  // one, ω, the centre and R(ωt) (row-major), computed once per loop over the held particles.
  struct HeldMotion {
    Vec3 velocity, angular_velocity, center;
    std::array<double, 9> rotation;
    bool rotates;
  };
  void set_motions(double t) const;
  // Velocity motions_[c] gives held particle held_particles_[k]: the constraint's velocity, plus
  // ω × R(ωt)(x0 − centre) for a rotating one (x0 the reference position).
  Vec3 held_velocity(std::size_t k, int c) const;

  Model& model_;
  std::vector<double> mass_;
  double gravity_[3];
  double damping_;
  std::vector<Constraint> constraints_;
  std::vector<int> held_particles_;          // particles inside at least one constraint region
  std::vector<double> held_reference_;       // their reference positions, 3 per held particle
  mutable std::vector<HeldMotion> motions_;  // per constraint, at the time of the last loop
  std::vector<int> held_offsets_;            // CSR: constraints holding each of held_particles_
  std::vector<int> held_by_;
  std::vector<double> force_;
  std::unique_ptr<Colliders> colliders_;
  std::unique_ptr<SelfContact> self_contact_;
  // Reactions of the constraints (3 per held particle) at the last evaluation, split as the
  // implicit–explicit evaluations split the acceleration (their sum is the reaction).
  std::vector<double> implicit_reaction_, explicit_reaction_;
  std::vector<double> collider_force_, self_contact_force_;  // 3N, at the last evaluation
  long force_evaluations_ = 0;
};

}  // namespace fissure
