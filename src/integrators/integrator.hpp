#pragma once
// One small interface for every time integrator: advance the state by one step, nothing else.
// The run loop calls step(), then the shared post-step (plasticity, fracture), then output.
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/named_arrays.hpp"
#include "integrators/dynamics.hpp"
#include "scene/config.hpp"

namespace fissure {

struct State {
  std::vector<double> position;  // y, 3N
  std::vector<double> velocity;  // ẏ, 3N
  double time = 0;
};

// Named counters an integrator reports (summary.json "integrator" block).
using Statistics = std::vector<std::pair<std::string, double>>;

class Integrator {
 public:
  virtual ~Integrator() = default;
  // Advances `state` by one step of dt, or of at most dt for an adaptive integrator, and
  // returns the step taken.
  virtual double step(Dynamics& dynamics, State& state, double dt) = 0;
  // Checks the options against the scene before the run writes anything (and before the first
  // step): throws InputError naming the key, e.g. an implicit method with a model that gives no
  // stiffness.
  virtual void check(const Dynamics&) const {}
  // The bond set changed (fracture): drop anything computed from the old bonds.
  virtual void bonds_changed() {}
  // True when dt is bounded by the explicit stability limit (notes §4).
  virtual bool explicit_step() const { return false; }
  // True when the integrator chooses its own steps; time.dt is then the largest.
  virtual bool adaptive() const { return false; }
  // True when it can run over several ranks (Dynamics::distribute): it advances only the rows
  // Dynamics::first_row() to end_row(), and from a state whose ghosts' positions are current
  // (a whole initial or resumed state is) it leaves them current (Dynamics::share) before each
  // acceleration and at the step's end, for the post-step and the next step.
  virtual bool distributable() const { return false; }
  // When it is not, the key of the option that keeps it from it, or empty for the type itself.
  virtual std::string undistributable_option() const { return {}; }
  virtual Statistics statistics() const { return {}; }
  // For checkpoints: what the integrator carries from one step to the next (a cached
  // acceleration), and its restoration. Its counters (statistics()) are not kept.
  virtual NamedArrays saved_state() const { return {}; }
  virtual void restore_state(const NamedArrays&) {}
};

// The integrator registered under settings.type; throws InputError naming the valid ones
// otherwise. `file` names the config in error messages.
std::unique_ptr<Integrator> make_integrator(const IntegratorSettings& settings,
                                            const std::string& file);
// The same with default options.
std::unique_ptr<Integrator> make_integrator(const std::string& type, const std::string& file);
std::vector<std::string> integrator_names();

}  // namespace fissure
