#pragma once
// The run's energy ledger: the energy stored in the particles, the work the loads put in, and
// what the effects took out, so that E = K + Π balances: K + Π + losses = E(0) + work. What is
// left over, relative to the run's energy scale, is the integrator's own energy error.
#include <string>
#include <utility>
#include <vector>

namespace fissure {

struct EnergyLedger {
  double kinetic = 0, elastic = 0;  // K = ½ Σ m|v|², Π = Σ V W (Eq 10) at the last sample
  // Work put into the particles since t = 0 [J]: by gravity (exact: −ΔU), by the constraints,
  // and by the colliders (penalty and friction forces, Σ ∫ F·v dt).
  double gravity_work = 0, constraint_work = 0, collider_work = 0;
  // Energy taken out since t = 0 [J]: by mass-proportional damping (∫ 2cK dt), by self-contact
  // (−∫ F·v dt: stored in the penalty while particles press together), by the plastic return
  // map and by broken bonds (stored energy released at fixed positions).
  double damping_loss = 0, contact_loss = 0, plastic_dissipation = 0, fracture_release = 0;
  double initial = 0;  // K + Π at t = 0
  double scale = 0;    // the largest K + |Π| and |work| seen at a sample: the unit of the error

  // K + Π + losses − (E(0) + work) [J].
  double balance() const;
  // balance() / scale (0 before anything moves).
  double balance_error() const;
  // (name, value) of every entry, in the order of probes.csv's ledger columns.
  std::vector<std::pair<std::string, double>> entries() const;
  // The names alone.
  static std::vector<std::string> names();
  // Every field as numbers, and back (checkpoints).
  std::vector<double> numbers() const;
  static EnergyLedger from_numbers(const std::vector<double>& numbers);
};

}  // namespace fissure
