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

// An implicit stage as a load's potential sees it: the positions at the step's start (3N), the
// stage's velocity as the scheme makes it of the stage's positions z, (z − anchor)/span (3N and
// seconds; span 0 for a static step), the time from the step's start to the stage's end, and
// whether contact takes its secant from the step's start (Newmark: ImplicitScheme::contact_secant).
struct PotentialStage {
  const double* start;
  const double* anchor;
  double span;
  double elapsed;
  bool secant = false;
};

// A load that implicit integrators take into the potential each step minimises
// (docs/integrators.md, "Contact"), evaluated at every iterate z instead of once at the step's
// start: its energy, its gradient and the positive-semidefinite part of its Hessian, as 3×3
// blocks per particle (what the factor takes) and, for a pair potential, the product of the blocks
// that couple particles (what the Newton matrix adds).
class LoadPotential {
 public:
  virtual ~LoadPotential() = default;
  // Fixes what the potential holds through a stage: a moving load's place, lagged friction.
  virtual void begin_stage(const PotentialStage& stage) = 0;
  // Its energy at z [J], this rank's rows; adds its gradient to `gradient` (3N, or null) and its
  // Hessian blocks to `blocks` (9 per particle, row-major, or null).
  virtual double evaluate(const double* z, double* gradient, double* blocks) = 0;
  // Adds the product of its Hessian's blocks between particles (a pair potential's) with v to
  // out (3N), at z, the point evaluate() last took its blocks at; nothing for a potential whose
  // particles act each on their own (the blocks hold its whole Hessian; couples() false).
  virtual void add_coupling(const double*, const double*, double*) const {}
  virtual bool couples() const { return false; }
  // The largest fraction α ≤ 1 of the update dz from z the load admits (1: any); this rank's
  // rows.
  virtual double max_step(const double*, const double*) const { return 1; }
  // True for contact, whose force switches on and off within a step: the schemes take it at the
  // step's end and never carry it to the next step or stage (implicit_scheme.hpp). False for a
  // smooth potential, integrated as the elastic forces are, at the scheme's own order.
  virtual bool contact() const { return false; }
};

class Load {
 public:
  // A force [N] per particle, or an acceleration [m/s²] uniform per unit mass (gravity, damping),
  // which the dynamics adds after dividing the forces by the mass (a = F/m + g − c v).
  enum class Form { force, acceleration };

  virtual ~Load() = default;
  virtual Form form() const { return Form::force; }
  // A stiff load goes with the internal forces into the implicit half of a split right-hand side
  // (damping); the others are explicit, and implicit integrators that minimise a potential take
  // them at the step's start (Dynamics::external_forces) unless they give a potential().
  virtual bool stiff() const { return false; }
  // The load as a potential of the positions, or nullptr. Implicit integrators that minimise a
  // potential take it there; they refuse a stiff load that gives none (Dynamics::
  // implicit_refusal) unless the schemes take it as a coefficient of their own equations.
  virtual LoadPotential* potential() { return nullptr; }
  // A stiff load the implicit schemes take into their equations through a coefficient
  // (damping's c, Dynamics::damping()).
  virtual bool scheme_coefficient() const { return false; }
  // The energy it stores at positions y (3N), this rank's rows [J]: a penalty's. The ledger
  // counts it with the kinetic and elastic energy (stored_energy).
  virtual double stored_energy(const double*) const { return 0; }
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
