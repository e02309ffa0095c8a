#pragma once
// Stops the run (status unstable) when energy that no load put in exceeds
// integrator.energy_growth_limit of the energy put in (|E(0)| + Σ |work|) for 10 steps in a row,
// or for the last two steps or more of the run (a short run is judged at its end): K
// + losses − (E(0) + work) bounds the ledger's balance from below because Π ≥ 0, so it needs no
// energy evaluation. A check of the run loop (app/observer.hpp), after the ledger's booking.
#include "app/energy_ledger.hpp"

namespace fissure {

class Halo;

class EnergyGrowthCheck : public Observer {
 public:
  // Over several ranks `halo` is theirs (null on one). Collective.
  EnergyGrowthCheck(const Scene& scene, const EnergyLedger& ledger, const Halo* halo = nullptr);
  std::string name() const override { return "energy_growth"; }
  void after_step(const RunParts& run, const Step& step) override;
  NamedArrays saved_state() const override;
  void resume(const RunParts& run, const NamedArrays& state) override;

 private:
  const EnergyLedger& ledger_;
  // 1e-12 Σ m|g||x|: below this the work of gravity is lost to the round-off of positions (a
  // first adaptive step of 1e-12 s moves nothing), so energy this small is never "growth".
  double round_off_energy_ = 0;
  int excess_steps_ = 0;  // consecutive steps over integrator.energy_growth_limit
};

}  // namespace fissure
