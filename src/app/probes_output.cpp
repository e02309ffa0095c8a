#include "app/probes_output.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/error.hpp"

namespace fissure {

namespace {

// The largest particle speed |v_i| over the particles [begin, end).
double max_speed(const std::vector<double>& velocity, int begin, int end) {
  double largest = 0;
#pragma omp parallel for reduction(max : largest) schedule(static)
  for (int i = begin; i < end; ++i) {
    const double* v = &velocity[3 * i];
    largest = std::max(largest, v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  }
  return std::sqrt(largest);
}

}  // namespace

ProbesOutput::ProbesOutput(const Scene& scene, EnergyLedger& ledger)
    : ledger_(ledger),
      path_(scene.config.output.dir + "/probes.csv"),
      members_(probe_members(scene.config, scene.particles)),
      schedule_(scene.config.output.probe_every, 0.0) {
  for (const auto& members : members_)
    member_rows_.insert(member_rows_.end(), members.begin(), members.end());
}

void ProbesOutput::start(const RunParts& run) {
  run.ranks.write([&] {
    if (run.ranks.root())
      file_ = std::make_unique<ProbesCsv>(path_, run.config, run.scene.particles,
                                          std::move(members_), ledger_.names());
  });
}

void ProbesOutput::resume(const RunParts& run, const NamedArrays& state) {
  schedule_.set_next(saved_number(state, "probes.next"));
  last_time_ = saved_number(state, "probes.last_time");
  max_speed_ = saved_number(state, "probes.max_speed");
  const double bytes = saved_number(state, "probes.bytes");
  if (!run.ranks.root()) return;  // the root writes probes.csv
  if (!std::filesystem::exists(path_) || std::filesystem::file_size(path_) < bytes)
    throw InputError(path_, "",
                     "shorter than when the checkpoint was written: cannot resume without the "
                     "rows before it");
  std::filesystem::resize_file(path_, static_cast<std::uintmax_t>(bytes));
  file_ = std::make_unique<ProbesCsv>(path_, run.config, run.scene.particles, std::move(members_),
                                      ledger_.names(), true);
}

void ProbesOutput::after_step(const RunParts& run, const Step&) {
  if (schedule_.due(run.state.time, run.tolerance())) write_row(run);
}

void ProbesOutput::finish(const RunParts& run, RunEnd end) {
  const bool finite_end = end == RunEnd::completed || end == RunEnd::stopped;
  if (finite_end && last_time_ < run.state.time) write_row(run);
}

void ProbesOutput::write_row(const RunParts& run) {
  const RunRanks& ranks = run.ranks;
  ledger_.sample(run);
  max_speed_ =
      std::max(max_speed_, ranks.max(max_speed(run.state.velocity, ranks.begin(), ranks.end())));
  std::vector<double> columns;
  for (const auto& [name, value] : ledger_.entries()) columns.push_back(value);
  std::vector<double> position;  // over several ranks, the members' on the root
  if (ranks.distributed()) {
    if (!members_to_root_) members_to_root_ = ranks.to_root(member_rows_);
    position = run.state.position;
    members_to_root_->fill(position.data(), 3);
  }
  ranks.write([&] {
    if (ranks.root())
      file_->write_row(run.state.time, ledger_.kinetic(), ledger_.elastic(),
                       ranks.distributed() ? position : run.state.position, columns);
  });
  last_time_ = run.state.time;
}

void ProbesOutput::summarize(RunSummary& summary) const { summary.max_speed = max_speed_; }

NamedArrays ProbesOutput::saved_state() const {
  std::error_code error;
  const auto bytes = std::filesystem::file_size(path_, error);
  if (error)
    throw OutputError(path_, "cannot read its size for the checkpoint: " + error.message());
  return {{"probes.next", {schedule_.next()}},
          {"probes.last_time", {last_time_}},
          {"probes.max_speed", {max_speed_}},
          {"probes.bytes", {double(bytes)}}};
}

}  // namespace fissure
