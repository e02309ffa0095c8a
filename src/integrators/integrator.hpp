#pragma once
// One small interface for every time integrator: advance the state by one step, nothing else.
#include <memory>
#include <string>
#include <vector>

#include "integrators/dynamics.hpp"

namespace fissure {

struct State {
  std::vector<double> position;  // y, 3N
  std::vector<double> velocity;  // ẏ, 3N
  double time = 0;
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  // Advances `state` from state.time to state.time + dt.
  virtual void step(Dynamics& dynamics, State& state, double dt) = 0;
  // The bond set changed (fracture): drop anything computed from the old bonds.
  virtual void bonds_changed() {}
};

// The integrator registered under `type`; throws InputError naming the valid ones otherwise.
std::unique_ptr<Integrator> make_integrator(const std::string& type, const std::string& file);
std::vector<std::string> integrator_names();

}  // namespace fissure
