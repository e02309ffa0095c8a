#pragma once
// The run's energy ledger: the energy stored in the particles and in the colliders' contacts,
// the work the loads put in, and what the effects took out, so that E = K + Π + U balances:
// K + Π + U + losses = E(0) + work, U the penalty energy of the contacts with the colliders. What
// is left over, relative to the run's energy scale, is the integrator's own energy error. A check
// of the run loop (app/observer.hpp): it books every step; the probes sample it.
//
// Entries, in this order: one per load kind and the constraints (Dynamics::ledger_entries():
// gravity_work, constraint_work, collider_work, damping_loss, contact_loss, then registered
// loads), then the post-step's plastic_dissipation and fracture_release, then balance_error,
// then stored_energy (U at the sample).
#include <string>
#include <utility>
#include <vector>

#include "app/observer.hpp"

namespace fissure {

class EnergyLedger : public Observer {
 public:
  explicit EnergyLedger(const Dynamics& dynamics);
  std::string name() const override { return "ledger"; }
  void before_step(const RunParts& run) override;
  // Adds the step's work and losses.
  void after_step(const RunParts& run, const Step& step) override;
  void summarize(RunSummary& summary) const override;
  NamedArrays saved_state() const override;
  void resume(const RunParts& run, const NamedArrays& state) override;

  // Takes K, Π and U of the state (the first sample sets E(0)) and widens the scale.
  void sample(const RunParts& run);
  double kinetic() const { return kinetic_; }
  double elastic() const { return elastic_; }
  double stored() const { return stored_; }
  double initial() const { return initial_; }
  double scale() const { return scale_; }
  // Σ of the work entries since t = 0, `from` + Σ of their absolute values, and Σ of the losses
  // [J], each added in the order of entries().
  double work() const;
  double absolute_work(double from = 0) const;
  double losses() const;
  // K + Π + U + losses − (E(0) + work) [J].
  double balance() const;
  // balance() / scale (0 before anything moves).
  double balance_error() const;
  // (name, value) of every entry, in the order of probes.csv's ledger columns.
  std::vector<std::pair<std::string, double>> entries() const;
  // The names alone.
  std::vector<std::string> names() const;

 private:
  struct Entry {
    std::string name;
    Booking booking;
    double value = 0;  // since t = 0 [J]
  };
  // Σ of the values booked as `booking`, from −0 (the exact additive identity).
  double sum(Booking booking) const;

  double kinetic_ = 0, elastic_ = 0;  // K = ½ Σ m|v|², Π = Σ V W (Eq 10) at the last sample
  double stored_ = 0;                 // U = Σ ½ k p² of the loads (Dynamics::stored_energy)
  // The loads' and constraints' entries (Dynamics::ledger_entries()), then the stored energy the
  // post-step released at fixed positions: by the plastic return map and by broken bonds.
  std::vector<Entry> entries_;
  std::size_t loads_;   // the first loads_ of entries_ are the loads'
  double initial_ = 0;  // K + Π + U at t = 0
  double scale_ = 0;    // the largest K + |Π| and |work| seen at a sample: the unit of the error
  bool sampled_ = false;
  std::vector<double> before_;  // y at the start of the step, for the load work
};

}  // namespace fissure
