#include "app/run_observers.hpp"

#include "app/energy_growth_check.hpp"
#include "app/energy_ledger.hpp"
#include "app/finite_state_check.hpp"
#include "app/output_registry.hpp"

namespace fissure {

NamedArrays RunObservers::saved_state() const {
  NamedArrays state;
  for (const auto* list : {&checks, &outputs})
    for (const auto& observer : *list)
      for (auto& array : observer->saved_state()) state.push_back(std::move(array));
  return state;
}

RunObservers make_run_observers(const Scene& scene, const Dynamics& dynamics,
                                std::function<NamedArrays()> observers_state) {
  RunObservers o;
  auto ledger = std::make_unique<EnergyLedger>(dynamics);
  EnergyLedger& books = *ledger;
  o.checks.push_back(std::make_unique<FiniteStateCheck>());
  o.checks.push_back(std::move(ledger));
  o.checks.push_back(std::make_unique<EnergyGrowthCheck>(scene, books, dynamics.halo()));
  for (const OutputKind& kind : output_kinds()) {
    const OutputOptions* options = nullptr;
    for (const auto& [name, parsed] : scene.config.output.options)
      if (name == kind.name) options = parsed.get();
    o.outputs.push_back(kind.make({scene, books, options, dynamics.halo()}));
  }
  auto checkpoints = std::make_unique<CheckpointOutput>(scene.config, std::move(observers_state));
  o.checkpoints = checkpoints.get();
  o.outputs.push_back(std::move(checkpoints));
  return o;
}

}  // namespace fissure
