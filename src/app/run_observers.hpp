#pragma once
// The run loop's observers (app/observer.hpp) in the order the loop calls them: the checks, the
// registered outputs (app/output_registry.hpp), the checkpoints. A new output is one file that
// registers itself; a new check is one file and one line in run_observers.cpp.
#include <functional>
#include <memory>
#include <vector>

#include "app/checkpoint_output.hpp"

namespace fissure {

struct RunObservers {
  // After the post-step of every step: the checks, then the outputs.
  std::vector<std::unique_ptr<Observer>> checks, outputs;
  CheckpointOutput* checkpoints = nullptr;  // one of outputs
  // Every observer's saved state, checks first.
  NamedArrays saved_state() const;
};

// Makes them for `scene` and its loads (`dynamics`); each checks its options and none touches a
// file. `observers_state` gives the checkpoint the observers' saved state
// (RunObservers::saved_state of the result).
RunObservers make_run_observers(const Scene& scene, const Dynamics& dynamics,
                                std::function<NamedArrays()> observers_state);

}  // namespace fissure
