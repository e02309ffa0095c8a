#pragma once
// The kinematic constraints (config constraints): regions whose particles move as prescribed, held
// still, translated or turned rigidly, until released. Not a load: a held particle's acceleration
// is set rather than added to, and the reaction that takes, m (a_prescribed − a_free), does work
// the ledger books as constraint_work.
#include <array>
#include <vector>

#include "scene/scene.hpp"

namespace fissure {

class Constraints {
 public:
  explicit Constraints(const Scene& scene);
  // The part of the acceleration `a` holds: all of it, or one half of a split right-hand side
  // (the reaction is their sum).
  enum class Part { whole, implicit, explicit_ };
  // Sets a where a constraint holds the particle at time t to the acceleration of its prescribed
  // motion (ω × (ω × r) for a turning one, r its prescribed offset from the centre; 0 otherwise,
  // and 0 in the explicit part of a split right-hand side) and keeps the reaction −m a_free
  // (the prescribed acceleration, normal to the velocity, does no work). An integrator that
  // integrates a held particle's acceleration (ARKODE) then follows a turning end, not its tangent.
  void hold(double t, double* a, Part part);
  // For integrators that hold particles through their own equations (petsc_newton): the reactions
  // they computed, 3N (read on held particles only).
  void set_reactions(const std::vector<double>& reaction);
  // The reactions' work over a step from `before` to `after`, Σ R·Δy [J].
  double work(const double* before, const double* after) const;
  // Sets the velocity of every particle held by a constraint active at time t.
  void constrain_velocity(double t, double* v) const;
  // The particles a constraint holds at time t and the velocity each one moves at.
  void held(double t, std::vector<int>& particles, std::vector<Vec3>& velocities) const;
  // The particles a constraint holds at time t and how far each moves from its position in y (3N)
  // over the next tau seconds along its prescribed motion, exactly: v τ + (R(ωτ) − I)(y − c − v t)
  // for a turning one (c its centre), v τ otherwise.
  void held_motion(double t, double tau, const double* y, std::vector<int>& particles,
                   std::vector<Vec3>& displacements) const;

 private:
  // The constraint holding particle held_particles_[k] at time t: the last one in config order
  // that contains it and is not yet released, or −1.
  int active_constraint(std::size_t k, double t) const;
  // The rigid motion each constraint prescribes at one time: its velocity and, for a rotating
  // one, ω, the centre and R(ωt) (row-major), computed once per loop over the held particles.
  struct HeldMotion {
    Vec3 velocity, angular_velocity, center;
    std::array<double, 9> rotation;
    bool rotates;
  };
  void set_motions(double t) const;
  // Its offset from the centre, R(ωt)(x0 − c), for held particle held_particles_[k] under
  // motions_[c] (rotating).
  Vec3 held_offset(std::size_t k, int c) const;
  // Velocity motions_[c] gives held particle held_particles_[k]: the constraint's velocity, plus
  // ω × R(ωt)(x0 − centre) for a rotating one (x0 the reference position).
  Vec3 held_velocity(std::size_t k, int c) const;

  const std::vector<double>& mass_;  // the scene's, which outlives the dynamics
  std::vector<Constraint> constraints_;
  std::vector<int> held_particles_;          // particles inside at least one constraint region
  std::vector<double> held_reference_;       // their reference positions, 3 per held particle
  mutable std::vector<HeldMotion> motions_;  // per constraint, at the time of the last loop
  std::vector<int> held_offsets_;            // CSR: constraints holding each of held_particles_
  std::vector<int> held_by_;
  // Reactions (3 per held particle) at the last evaluation, split as the implicit–explicit
  // evaluations split the acceleration (their sum is the reaction).
  std::vector<double> implicit_reaction_, explicit_reaction_;
};

}  // namespace fissure
