#pragma once
// The outputs of a run (observers of the run loop, app/observer.hpp), each registered in one
// place next to its code: its name, its own keys in output: and their parser
// (scene/option_parsers.hpp) and its constructor. The run makes every registered output, in the
// order of registration, then the checkpoints (app/run_observers.cpp). The built-in ones,
// probes.csv and the frames, are registered on first use of the registry and, through
// builtin_registration.cpp, at start-up of every program linked to this layer; their keys
// (output.every, probe_every, surface, tets, surface_motion) are OutputSettings' own, since
// other layers read them too. A test registers its own with register_output.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "app/energy_ledger.hpp"
#include "app/observer.hpp"

namespace fissure {

class Halo;

// What an output's constructor gets: the scene, the energy ledger it may sample, its own
// options (null where it has none or the config was made in code), and over several ranks
// their halo (null on one).
struct OutputContext {
  const Scene& scene;
  EnergyLedger& ledger;
  const OutputOptions* options;
  const Halo* halo = nullptr;
};

struct OutputKind {
  std::string name;               // its name (also its checkpoint prefix, Observer::name)
  std::vector<std::string> keys;  // its own keys in output:
  // Reads them from the output: map (null: it has none); the result is in OutputSettings::options.
  std::function<std::shared_ptr<const OutputOptions>(const OptionReader&)> parse;
  // Makes it; checks its options and touches no file.
  std::function<std::unique_ptr<Observer>(const OutputContext&)> make;
};

// Adds `kind` and its option parser; throws std::logic_error if the name is taken.
void register_output(OutputKind kind);
const std::vector<OutputKind>& output_kinds();

// An output's options of type T: its parser's, or T's defaults where none were parsed.
template <class Options>
Options output_options(const OutputContext& context) {
  if (!context.options) return Options{};
  return dynamic_cast<const Options&>(*context.options);
}

}  // namespace fissure
