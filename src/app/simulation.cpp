#include "app/simulation.hpp"

#include <fmt/format.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>

#include "app/checkpoint.hpp"
#include "app/run_observers.hpp"
#include "app/run_ranks.hpp"
#include "app/summary_json.hpp"
#include "app/time_step.hpp"
#include "core/error.hpp"
#include "fracture/fragments.hpp"
#include "io/checkpoint_file.hpp"

namespace fissure {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

class Simulation {
 public:
  Simulation(const Config& config, const RunOptions& options);
  // Steps to time.end: step, post-step, checks, outputs. Output that cannot be written stops the
  // run (stop_writing).
  RunSummary run();

 private:
  RunSummary run_steps();
  // The step after `steps` of dt: a fixed-step integrator shortens its last step to land on
  // time.end; an adaptive one stops on the observers' times and time.end, and takes at most dt.
  double step_size(long step, long steps) const;
  // Writes a last probes.csv row (unless the state is non-finite) and summary.json with `status`
  // and `message`, then throws RunError(message).
  [[noreturn]] void stop(const std::string& status, const std::string& message);
  // Output that cannot be written: summary.json (where it still can be written) records status
  // failed, and the RunError names the file, the reason and the checkpoint to go on from.
  [[noreturn]] void stop_writing(const OutputError& error);
  void finish(RunEnd end);
  // Takes the run back to the checkpoint's step; the output after it is dropped.
  void resume(const CheckpointReader& checkpoint);
  NamedArrays local_rows(NamedArrays arrays) const;
  // Spreads the run over the ranks (ranks_): each advances and breaks its own rows. Throws
  // InputError for an integrator or effect that cannot be distributed yet.
  void distribute();
  void report_progress(Clock::time_point start, bool final);

  const Config& config_;
  RunOptions options_;
  Clock::time_point setup_start_;
  std::unique_ptr<Integrator> integrator_;
  Scene scene_;
  std::unique_ptr<Model> model_;
  std::unique_ptr<Dynamics> dynamics_;
  std::unique_ptr<PostStep> post_step_;
  State state_;
  RunSummary summary_;
  std::unique_ptr<RunRanks> ranks_;
  std::unique_ptr<RunParts> parts_;
  RunObservers observers_;
};

Simulation::Simulation(const Config& config, const RunOptions& options)
    : config_(config), options_(options), setup_start_(Clock::now()) {
  integrator_ = make_integrator(config.integrator, config.file);
  // over several ranks each keeps only its rows' families and its ghosts'
  scene_ = build_scene(config, RunRanks::split_over(options.comm));
  model_ = make_model(scene_);
  dynamics_ = std::make_unique<Dynamics>(scene_, *model_);
  integrator_->check(*dynamics_);  // before the output folder is touched
  post_step_ = std::make_unique<PostStep>(scene_, *model_, true);
  ranks_ = std::make_unique<RunRanks>(scene_, options.comm);
  if (ranks_->distributed()) distribute();
  options_.progress = options_.progress && ranks_->root();
  summary_.ranks = ranks_->size();
  summary_.integrator = config.integrator.type;
  summary_.particles = scene_.families.total_rows();
  summary_.bonds = static_cast<long>(scene_.families.total_directed_bonds() / 2);
  summary_.stable_dt = model_->stable_time_step();
  summary_.model_statistics = model_->statistics();
  summary_.dt = run_time_step(config, *integrator_, summary_.stable_dt);
  parts_ = std::make_unique<RunParts>(config_, scene_, *model_, *dynamics_, *post_step_,
                                      *integrator_, state_, summary_, *ranks_);
  // Every observer checks its options here, before the output folder is touched.
  observers_ = make_run_observers(scene_, *dynamics_, [this] { return observers_.saved_state(); });
  std::filesystem::create_directories(config.output.dir);
  state_.position = scene_.particles.reference;
  state_.velocity = scene_.particles.velocity;
  dynamics_->constrain_velocity(0.0, state_.velocity.data());
  if (options.resume) {
    ranks_->agree([&] { resume(*options.resume); });
  } else {
    for (auto& observer : observers_.checks) observer->start(*parts_);
    for (auto& observer : observers_.outputs) observer->start(*parts_);
  }
  if (ranks_->root()) std::filesystem::remove(config.output.dir + "/summary.json");
}

void Simulation::distribute() {
  const std::string& type = config_.integrator.type;
  if (!integrator_->distributable()) {
    const std::string option = integrator_->undistributable_option();
    throw InputError(config_.file, option.empty() ? "integrator.type" : option,
                     fmt::format("'{}' cannot run over several ranks yet with these options ({} "
                                 "ranks were started); velocity_verlet, symplectic_euler, "
                                 "arkode (its implicit and IMEX methods with "
                                 "integrator.preconditioner auto or nearest) and petsc_newton "
                                 "(with integrator.preconditioner auto, majoriser, nearest or "
                                 "gamg) can (docs/mpi.md)",
                                 type, ranks_->size()));
  }
  try {
    dynamics_->distribute(ranks_->halo());
    post_step_->distribute(ranks_->halo());
  } catch (const std::invalid_argument& e) {
    throw InputError(config_.file, "", e.what());
  }
}

// The model's and the integrator's per-particle arrays of a checkpoint (a whole number of values
// per particle of the whole scene, as CheckpointOutput gathers them) in this rank's rows.
NamedArrays Simulation::local_rows(NamedArrays arrays) const {
  const Families& families = scene_.families;
  const std::size_t particles = families.total_rows();
  for (auto& [name, values] : arrays)
    if (!model_->per_bond_state(name) && !values.empty() && values.size() % particles == 0)
      values = families.localize_rows(values, static_cast<int>(values.size() / particles));
  return arrays;
}

void Simulation::resume(const CheckpointReader& c) {
  check_loop_sections(c);
  // a checkpoint holds the whole scene's particles; over several ranks these rows take theirs
  const Families& families = scene_.families;
  const std::vector<double> position = c.doubles("state.position");
  if (position.size() != 3 * std::size_t(families.total_rows()))
    throw InputError(c.path(), "state.position",
                     fmt::format("{} particles, but the scene has {}", position.size() / 3,
                                 families.total_rows()));
  state_.position = families.localize_rows(position, 3);
  state_.velocity = families.localize_rows(c.doubles("state.velocity"), 3);
  state_.time = c.number("run.time");
  summary_.steps = static_cast<long>(c.number("run.steps"));
  try {
    NamedArrays post_step = c.arrays("post_step.");
    for (auto& array : local_rows(c.arrays("model."))) post_step.push_back(std::move(array));
    post_step_->restore_state(scene_, post_step, c.bytes("state.broken"));
    // The mesh was split afresh from the broken bonds; its vertices start from the particles.
    if (EmbeddedMesh* mesh = post_step_->embedded_mesh()) mesh->place(state_.position.data());
    dynamics_->restore_state(c.arrays("dynamics."));
    integrator_->restore_state(local_rows(c.arrays("integrator.")));
    for (const auto* list : {&observers_.checks, &observers_.outputs})
      for (const auto& observer : *list)
        observer->resume(*parts_, c.arrays(observer->name() + "."));
  } catch (const InputError& e) {
    if (!e.file().empty()) throw;
    throw InputError(c.path(), e.key(), e.reason());  // a part's state: the file is the checkpoint
  }
}

void Simulation::finish(RunEnd end) {
  for (auto& observer : observers_.outputs) observer->finish(*parts_, end);
  for (auto& observer : observers_.checks) observer->summarize(summary_);
  for (auto& observer : observers_.outputs) observer->summarize(summary_);
  summary_.wall_seconds = seconds_since(setup_start_);
  summary_.peak_rss_mb = ranks_->max(peak_rss_mb());
  if (ranks_->distributed()) {
    // each rank knows its own rows' bonds: their broken ones summed, their fragments joined
    const std::vector<std::uint8_t> broken = post_step_->broken();
    const Families& families = scene_.families;
    double directed = 0;
    if (!broken.empty())
      for (int b = families.offsets[ranks_->begin()]; b < families.offsets[ranks_->end()]; ++b)
        directed += broken[b];
    summary_.broken_bonds = std::lround(ranks_->sum(directed)) / 2;
    summary_.fragments = count_fragments(ranks_->comm(), families, broken);
  } else {
    summary_.broken_bonds = static_cast<long>(post_step_->broken_bonds());
    summary_.fragments = count_fragments(scene_.families, *model_);
  }
  summary_.post_steps = static_cast<long>(post_step_->calls());
  summary_.force_evaluations = dynamics_->force_evaluations();
  summary_.integrator_statistics = integrator_->statistics();
}

void Simulation::stop(const std::string& status, const std::string& message) {
  summary_.status = status;
  summary_.message = message;
  finish(status == "nonfinite" ? RunEnd::nonfinite : RunEnd::stopped);
  if (ranks_->root()) write_summary(config_.output.dir + "/summary.json", summary_);
  throw RunError(message);
}

void Simulation::stop_writing(const OutputError& error) {
  const std::string& dir = config_.output.dir;
  std::string message = fmt::format("{}; the run stopped at t = {:.6g} s; {}", error.what(),
                                    state_.time, observers_.checkpoints->resume_advice(dir));
  summary_.status = "failed";
  summary_.message = message;
  finish(RunEnd::output_failed);
  try {
    if (ranks_->root()) write_summary(dir + "/summary.json", summary_);
  } catch (const OutputError& also) {
    message += fmt::format(" ({} could not record it either: {})", also.path(), also.reason());
  }
  throw RunError(message);
}

void Simulation::report_progress(Clock::time_point start, bool final) {
  const double elapsed = seconds_since(start);
  const double rate = summary_.steps / std::max(elapsed, 1e-9);
  const double remaining =
      (config_.time.end - state_.time) * elapsed / std::max(state_.time, 1e-300);
  fmt::print(stderr, "\rt = {:.4g} / {:.4g} s   {:.0f} steps/s   ETA {:.0f} s   {}", state_.time,
             config_.time.end, rate, std::max(remaining, 0.0), final ? "\n" : "");
}

RunSummary Simulation::run() {
  try {
    return run_steps();
  } catch (const OutputError& error) {
    stop_writing(error);
  }
}

double Simulation::step_size(long step, long steps) const {
  const double dt = summary_.dt, end = config_.time.end;
  if (!integrator_->adaptive())
    return step + 1 == steps ? std::max(end - state_.time, 1e-12 * dt) : dt;
  double h = std::min(dt, end - state_.time);
  for (const auto& observer : observers_.outputs)
    if (observer->next_stop() - state_.time > parts_->tolerance())
      h = std::min(h, observer->next_stop() - state_.time);
  return h;
}

RunSummary Simulation::run_steps() {
  const bool adaptive = integrator_->adaptive();
  const long steps = steps_to(config_.time.end, summary_.dt);
  const double end = config_.time.end;
  summary_.setup_seconds = seconds_since(setup_start_);
  // A checkpoint is the last output of its step: a resumed run has had that step's output (with
  // probe_every below dt the probe schedule stays due and would repeat its row).
  if (!options_.resume)
    for (auto& observer : observers_.outputs) observer->after_step(*parts_, Step(0.0, *parts_));
  const auto start = Clock::now();
  auto last_report = start;
  double stepping_seconds = 0;
  try {
    for (long s = summary_.steps; adaptive ? end - state_.time > 1e-12 * end : s < steps; ++s) {
      const auto step_start = Clock::now();
      for (auto& observer : observers_.checks) observer->before_step(*parts_);
      double h = step_size(s, steps);
      try {
        h = integrator_->step(*dynamics_, state_, h);
      } catch (const RunError& e) {
        stop("failed", fmt::format("{}. Outputs up to t = {:.6g} s are kept in {}", e.what(),
                                   state_.time, config_.output.dir));
      }
      dynamics_->end_step(h);
      if (post_step_->run(state_.position.data(), state_.velocity.data(), h))
        integrator_->bonds_changed();
      ++summary_.steps;
      const Step step(h, *parts_);
      for (auto& observer : observers_.checks) observer->after_step(*parts_, step);
      stepping_seconds += seconds_since(step_start);
      for (auto& observer : observers_.outputs) observer->after_step(*parts_, step);
      if (options_.progress && seconds_since(last_report) > 0.5) {
        report_progress(start, false);
        last_report = Clock::now();
      }
    }
  } catch (const StopRun& stopped) {
    stop(stopped.status(), stopped.what());
  }
  if (options_.progress) report_progress(start, true);
  summary_.seconds_per_step = summary_.steps > 0 ? stepping_seconds / summary_.steps : 0.0;
  finish(RunEnd::completed);
  ranks_->write([&] {
    if (ranks_->root()) write_summary(config_.output.dir + "/summary.json", summary_);
  });
  return summary_;
}

}  // namespace

double peak_rss_mb() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;  // unknown: reported as 0
  return usage.ru_maxrss / 1024.0;                    // ru_maxrss is in KiB on Linux
}

RunSummary run_simulation(const Config& config, const RunOptions& options) {
  Simulation simulation(config, options);
  return simulation.run();
}

}  // namespace fissure
