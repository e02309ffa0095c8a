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

namespace {

// Over several ranks each rank knows its own rows: the model's per-bond arrays (the plastic
// extensions) are gathered on the root by the rows' bonds, and the per-particle arrays of the
// model and the integrator (theirs with a whole number of values per particle) by the rows; the
// rest (the other parts' arrays, and counters such as petsc_newton's load increments) is the
// same on every rank.
NamedArrays gathered(const RunParts& run, NamedArrays part) {
  const RunRanks& ranks = run.ranks;
  if (!ranks.distributed()) return part;
  const std::size_t particles = run.scene.particles.count();  // this rank's: own and ghosts
  for (auto& [name, values] : part) {
    if (run.model.per_bond_state(name)) {
      values = ranks.gather_bonds(values);
      continue;
    }
    // a whole number of values per particle on every rank (the ranks keep different numbers of
    // particles, so a small array of another kind could pass on one rank alone)
    const bool ours = name.rfind("model.", 0) == 0 || name.rfind("integrator.", 0) == 0;
    const int width = ours && !values.empty() && values.size() % particles == 0
                          ? static_cast<int>(values.size() / particles)
                          : 0;
    if (const int agreed = ranks.min(width); agreed > 0) values = ranks.gather(values, agreed);
  }
  return part;
}

}  // namespace

void CheckpointOutput::write(const RunParts& run) const {
  const RunRanks& ranks = run.ranks;
  // in the global numbering, whatever the number of ranks, so a run resumes on any number
  const std::vector<double> position = ranks.gather(run.state.position, 3);
  const std::vector<double> velocity = ranks.gather(run.state.velocity, 3);
  const std::vector<std::uint8_t> broken = ranks.gather_bonds(run.post_step.broken());
  NamedArrays parts;
  for (const NamedArrays& part :
       {gathered(run, run.post_step.saved_state()), run.dynamics.saved_state(),
        gathered(run, run.integrator.saved_state())})
    for (const auto& array : part) parts.push_back(array);
  ranks.write([&] {
    if (!ranks.root()) return;
    CheckpointWriter w;
    w.add("config", run.config.source);
    w.add("config.file", run.config.file);
    w.add("run.time", std::vector<double>{run.state.time});
    w.add("run.steps", std::vector<double>{double(run.summary.steps)});
    w.add("state.position", position);
    w.add("state.velocity", velocity);
    w.add("state.broken", broken);
    for (const NamedArrays& part : {parts, observers_state_()})
      for (const auto& [name, values] : part) w.add(name, values);
    w.write(run.config.output.dir + "/checkpoint.bin");
  });
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
