#pragma once
// The equation of motion the integrators advance: M ÿ = F_int(y) + Σ F_load(t, y, ẏ) (Eq 2 with
// its loads: gravity M g, damping −c M ẏ, colliders, self-contact and any registered load;
// integrators/load_registry.hpp), with the kinematic constraints holding their regions.
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "contact/colliders.hpp"
#include "integrators/constraints.hpp"
#include "integrators/load.hpp"
#include "model/model.hpp"
#include "scene/scene.hpp"

namespace fissure {

class Halo;

class Dynamics {
 public:
  // Its loads and constraints refer to the scene's masses, so the scene must outlive it.
  Dynamics(const Scene& scene, Model& model);
  Dynamics(const Scene&& scene, Model& model) = delete;

  // a = (F_int(y) + Σ forces)/m + Σ accelerations (g − c v), zero where a constraint holds the
  // particle at time t. The loads keep their forces and the constraints their reactions for the
  // ledger (booked()).
  void acceleration(double t, const double* y, const double* v, double* a) {
    acceleration(t, y, v, a, false);
  }
  // The same without contact, the loads whose potential is contact's (LoadPotential::contact),
  // which implicit schemes take at their stages' end points (implicit_scheme.hpp).
  void acceleration_without_contact(double t, const double* y, const double* v, double* a) {
    acceleration(t, y, v, a, true);
  }
  // The same split in two, for implicit–explicit methods: a = implicit + explicit.
  //   implicit: F_int(y)/m + the stiff loads (− c v);  explicit: the other loads, F/m.
  // Both are zero where a constraint holds the particle at time t.
  void implicit_acceleration(double t, const double* y, const double* v, double* a);
  void explicit_acceleration(double t, const double* y, const double* v, double* a);
  // The model's internal forces F_int(y), 3N, overwritten; counted in force_evaluations().
  void internal_forces(const double* y, double* f);
  long force_evaluations() const { return force_evaluations_; }
  // Counts an evaluation of F_int made by the model directly (with its energy, say).
  void count_force_evaluation() { ++force_evaluations_; }
  // The forces of the loads that are not stiff, M g + F_contact(y, v) + ..., 3N, overwritten;
  // with `without_potentials`, only those of the loads that give no potential (Load::potential:
  // an implicit step takes those at its iterates instead).
  void external_forces(double t, const double* y, const double* v, double* f,
                       bool without_potentials = false);
  // The loads that give a potential of the positions, in load order.
  std::vector<LoadPotential*> potentials() const;
  // The energy the loads store at positions y (3N), this rank's rows [J] (Load::stored_energy).
  double stored_energy(const double* y) const;
  // For implicit integrators that minimise a potential: the ledger entry of a stiff load that
  // gives no potential and that the schemes do not take as a coefficient, which they cannot
  // integrate; empty when there is none.
  std::string implicit_refusal() const;
  // Sets the velocity of every particle held by a constraint active at time t.
  void constrain_velocity(double t, double* v) const { constraints_.constrain_velocity(t, v); }
  // The particles a constraint holds at time t and the velocity each one moves at.
  void held(double t, std::vector<int>& particles, std::vector<Vec3>& velocities) const {
    constraints_.held(t, particles, velocities);
  }
  // Constraints::held_motion.
  void held_motion(double t, double tau, const double* y, std::vector<int>& particles,
                   std::vector<Vec3>& displacements) const {
    constraints_.held_motion(t, tau, y, particles, displacements);
  }
  const Constraints& constraints() const { return constraints_; }
  Model& model() { return model_; }
  const Model& model() const { return model_; }
  const std::vector<double>& mass() const { return mass_; }
  // c of the damping load, which implicit integrators take into their own equations.
  double damping() const { return damping_; }
  // Ends a completed step of size h: the loads' end_step (the colliders move).
  void end_step(double h);
  // The colliders, or nullptr when the scene has none.
  const Colliders* colliders() const;
  // The energy-ledger entries of the loads and constraints, in order (load_kinds()), and what
  // each books over a completed step with the forces of the last evaluation (0 for a load the
  // scene does not have).
  const std::vector<std::pair<std::string, Booking>>& ledger_entries() const { return entries_; }
  std::vector<double> booked(const BookedStep& step) const;
  // For checkpoints: the loads' state and the force-evaluation counter, and back.
  NamedArrays saved_state() const;
  void restore_state(const NamedArrays& state);
  // Over several ranks (docs/mpi.md): the model evaluates only this rank's rows
  // (Model::distribute), and an integrator that supports it (Integrator::distributable())
  // advances rows [first_row(), end_row()) only and calls share() on its positions before each
  // acceleration. Throws std::invalid_argument naming the key of a load or model that cannot
  // be distributed. The halo must outlive this.
  void distribute(const Halo& halo);
  int first_row() const;
  int end_row() const;
  // The halo of distribute(), or nullptr on one rank.
  const Halo* halo() const { return halo_; }
  // Fills the ghosts' entries of y (3N) from the ranks that own them; nothing on one rank.
  // Collective.
  void share(double* y) const;
  // The same for a per-particle array of `width` values per particle.
  void share(double* values, int width) const;
  // For integrators that hold particles through their own equations (petsc_newton): the
  // constraint reactions they computed, 3N (read on held particles only).
  void set_constraint_reactions(const std::vector<double>& reaction) {
    constraints_.set_reactions(reaction);
  }

 private:
  void acceleration(double t, const double* y, const double* v, double* a, bool without_contact);
  // Adds the loads of `form` (only the stiff ones with `stiff_only`, and without contact with
  // `without_contact`) to out.
  void add_loads(Load::Form form, bool stiff_only, double t, const double* y, const double* v,
                 double* out, bool without_contact = false);

  Model& model_;
  std::vector<double> mass_;
  double damping_;
  Constraints constraints_;
  std::vector<std::unique_ptr<Load>> loads_;  // those the scene has, in ledger order
  std::vector<std::pair<std::string, Booking>> entries_;
  // Per entry: its load in loads_, or −1 for the constraints' entry, or −2 for an absent load.
  std::vector<int> entry_load_;
  std::vector<double> force_, scratch_;  // 3N
  long force_evaluations_ = 0;
  const Halo* halo_ = nullptr;
};

}  // namespace fissure
