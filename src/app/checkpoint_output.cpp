#include "app/checkpoint_output.hpp"

#include <fmt/format.h>

#include "io/checkpoint_file.hpp"

namespace fissure {

CheckpointOutput::CheckpointOutput(const Config& config,
                                   std::function<NamedArrays()> observers_state)
    : observers_state_(std::move(observers_state)),
      interval_(config.output.checkpoint_every),
      schedule_(interval_, interval_) {}

void CheckpointOutput::resume(const RunParts& run, const NamedArrays& state) {
  schedule_.set_next(saved_number(state, "checkpoint.next"));
  last_time_ = run.state.time;
}

void CheckpointOutput::after_step(const RunParts& run, const Step&) {
  if (interval_ > 0 && run.state.time > 0 && schedule_.due(run.state.time, run.tolerance())) {
    write(run);
    last_time_ = run.state.time;
  }
}

void CheckpointOutput::write(const RunParts& run) const {
  CheckpointWriter w;
  w.add("config", run.config.source);
  w.add("config.file", run.config.file);
  w.add("run.time", std::vector<double>{run.state.time});
  w.add("run.steps", std::vector<double>{double(run.summary.steps)});
  w.add("state.position", run.state.position);
  w.add("state.velocity", run.state.velocity);
  w.add("state.broken", run.post_step.broken());
  for (const NamedArrays& part : {run.post_step.saved_state(), run.dynamics.saved_state(),
                                  run.integrator.saved_state(), observers_state_()})
    for (const auto& [name, values] : part) w.add(name, values);
  w.write(run.config.output.dir + "/checkpoint.bin");
}

NamedArrays CheckpointOutput::saved_state() const {
  return {{"checkpoint.next", {schedule_.next()}}};
}

std::string CheckpointOutput::resume_advice(const std::string& dir) const {
  if (last_time_ < 0) return "no checkpoint was written (output.checkpoint_every)";
  return fmt::format(
      "the last checkpoint (t = {:.6g} s) in {} is intact: with room to write, go on with "
      "`fissure run --resume {}`",
      last_time_, dir, dir);
}

}  // namespace fissure
