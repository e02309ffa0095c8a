#pragma once
// A load: one term of the equation of motion besides the internal forces, M ÿ = F_int(y) +
// Σ F_load(t, y, ẏ) (Eq 2 with its loads), that also books its energy in the run's ledger. Gravity,
// damping, the colliders and self-contact are loads (one file each); a new load is one file that
// registers itself (integrators/load_registry.hpp). The kinematic constraints are not a load: they
// prescribe motion rather than add a force (integrators/constraints.hpp), and book the work of
// their reaction alike.
#include <functional>

#include "core/named_arrays.hpp"

namespace fissure {

class Halo;

// A completed step as the ledger books it: positions at its start and end, its size, and
// K = ½ Σ m|v|² at its end (computed once, when a term asks for it).
struct BookedStep {
  const double* before;
  const double* after;
  double h;
  std::function<double()> kinetic;
};

// How a ledger entry counts: as work put into the particles, or as energy taken out of them.
enum class Booking { work, loss };

class Load {
 public:
  // A force [N] per particle, or an acceleration [m/s²] uniform per unit mass (gravity, damping),
  // which the dynamics adds after dividing the forces by the mass (a = F/m + g − c v).
  enum class Form { force, acceleration };

  virtual ~Load() = default;
  virtual Form form() const { return Form::force; }
  // A stiff load goes with the internal forces into the implicit half of a split right-hand side
  // (damping); the others are explicit, and implicit integrators that minimise a potential take
  // them at the step's start (Dynamics::external_forces).
  virtual bool stiff() const { return false; }
  // Adds its force (or acceleration, by form()) at time t and state (y, v) to `out`, 3N, and
  // keeps what booked() needs.
  virtual void add(double t, const double* y, const double* v, double* out) = 0;
  // What it books over a completed step, with the force of its last add() [J]: work put in, or
  // energy taken out (by its entry's Booking).
  virtual double booked(const BookedStep& step) const = 0;
  // Ends a completed step of size h (a moving collider advances).
  virtual void end_step(double) {}
  // Where the scene runs over several ranks (Dynamics::distribute): the config key that asks
  // for this load if its force on a particle reads other particles' state (self-contact), which
  // cannot be distributed yet; empty where each particle's force is its own.
  virtual std::string not_distributable() const { return {}; }
  // The scene runs over several ranks (Dynamics::distribute): add() need only push on the
  // halo's rows, and whatever the load sums over the particles (a dynamic collider's reaction)
  // is summed over the ranks, collectively, in end_step().
  virtual void distribute(const Halo&) {}
  // For checkpoints: its state, named "dynamics.<name>", and back.
  virtual NamedArrays saved_state() const { return {}; }
  virtual void restore_state(const NamedArrays&) {}
};

}  // namespace fissure
