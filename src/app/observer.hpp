#pragma once
// What the run loop calls around each step (app/simulation.cpp): the checks after the post-step
// (a finite state, the energy ledger, the energy-growth check) and the outputs (probes, frames,
// checkpoints). Each observer owns its state and hands it to the checkpoint as named arrays under
// its own prefix, so adding one is one file and a line in the simulation's list.
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "app/run_ranks.hpp"
#include "app/simulation.hpp"
#include "core/named_arrays.hpp"
#include "fracture/post_step.hpp"
#include "integrators/integrator.hpp"
#include "model/model.hpp"
#include "scene/scene.hpp"

namespace fissure {

// The parts of a run an observer reads: set up before the first observer is made, alive for the
// whole run. `summary` carries the step count, dt and the stable estimate.
struct RunParts {
  const Config& config;
  const Scene& scene;
  Model& model;
  Dynamics& dynamics;
  PostStep& post_step;
  Integrator& integrator;
  const State& state;
  const RunSummary& summary;
  // The ranks the run is spread over: a rank's state is current on its own rows and their
  // ghosts only, so whatever an observer reads of every particle is reduced or gathered over
  // them (docs/mpi.md); one rank, on its own, has every row.
  const RunRanks& ranks;
  // Two times closer than this are the same output time: 1e-9 dt.
  double tolerance() const { return 1e-9 * summary.dt; }
};

// The step just completed: its size and K = ½ Σ m|v|² at its end, computed once when asked.
class Step {
 public:
  Step(double h, const RunParts& run) : h_(h), run_(run) {}
  double h() const { return h_; }
  // Over all ranks: collective, so every rank asks, or none.
  double kinetic() const;
  // This rank's rows' share.
  double own_kinetic() const;

 private:
  double h_;
  const RunParts& run_;
  mutable std::optional<double> kinetic_, own_kinetic_;
};

// Thrown by a check to end the run early; summary.json records `status` (nonfinite | unstable)
// and the message.
class StopRun : public std::runtime_error {
 public:
  StopRun(std::string status, const std::string& message)
      : std::runtime_error(message), status_(std::move(status)) {}
  const std::string& status() const { return status_; }

 private:
  std::string status_;
};

// How a run ended, for Observer::finish.
enum class RunEnd {
  completed,      // reached time.end
  stopped,        // a check or the integrator stopped it; the state is finite
  nonfinite,      // stopped with a non-finite state
  output_failed,  // output could not be written
};

class Observer {
 public:
  virtual ~Observer() = default;
  // The prefix of its checkpoint sections: "probes" saves "probes.next", ...
  virtual std::string name() const = 0;
  // A new run: removes what an earlier run left of its files and opens them. The constructor
  // checks the options and touches no file: every observer is made before the output folder is.
  virtual void start(const RunParts&) {}
  // A resumed run: takes back its state from saved_state()'s arrays (names with the prefix) and
  // its files to the checkpoint. A missing array is an InputError with no file (saved_array()).
  virtual void resume(const RunParts&, const NamedArrays&) {}
  virtual void before_step(const RunParts&) {}
  // After the post-step of a completed step; for the outputs also once at t = 0 of a new run,
  // with h = 0. A check throws StopRun to end the run.
  virtual void after_step(const RunParts&, const Step&) {}
  // A time the next step must not pass (an adaptive integrator lands on it).
  virtual double next_stop() const { return std::numeric_limits<double>::infinity(); }
  // The run ended: a last output, where it is due.
  virtual void finish(const RunParts&, RunEnd) {}
  // Its entries of the run's summary.
  virtual void summarize(RunSummary&) const {}
  virtual NamedArrays saved_state() const { return {}; }
};

// The array `name` of `state`; InputError(no file, name, "missing from the checkpoint") if absent.
const std::vector<double>& saved_array(const NamedArrays& state, const std::string& name);
// Its one number.
double saved_number(const NamedArrays& state, const std::string& name);

}  // namespace fissure
