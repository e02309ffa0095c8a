#include "app/probes_output.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/error.hpp"
#include "parallel/collective.hpp"
#include "parallel/halo.hpp"

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

// Per probe, where each rank's members start among the whole scene's, and their count last.
std::vector<std::vector<int>> member_boundaries(MPI_Comm comm,
                                                const std::vector<std::vector<int>>& members) {
  int size = 1;
  if (MPI_Comm_size(comm, &size) != MPI_SUCCESS) throw RunError("MPI: MPI_Comm_size failed");
  const int probes = static_cast<int>(members.size());
  std::vector<int> own, all(std::size_t(size) * probes);
  for (const auto& m : members) own.push_back(static_cast<int>(m.size()));
  if (MPI_Allgather(own.data(), probes, MPI_INT, all.data(), probes, MPI_INT, comm) != MPI_SUCCESS)
    throw RunError("MPI: MPI_Allgather failed");
  std::vector<std::vector<int>> boundaries(probes, std::vector<int>(size + 1, 0));
  for (int p = 0; p < probes; ++p)
    for (int r = 0; r < size; ++r)
      boundaries[p][r + 1] = boundaries[p][r] + all[std::size_t(r) * probes + p];
  return boundaries;
}

}  // namespace

ProbesOutput::ProbesOutput(const Scene& scene, EnergyLedger& ledger, const Halo* halo)
    : ledger_(ledger),
      path_(scene.config.output.dir + "/probes.csv"),
      members_(probe_members(scene.config, scene.particles, halo ? halo->begin() : 0,
                             halo ? halo->end() : scene.particles.count())),
      comm_(halo ? halo->comm() : MPI_COMM_NULL),
      schedule_(scene.config.output.probe_every, 0.0) {
  std::vector<double> counts;
  for (const auto& members : members_) counts.push_back(static_cast<double>(members.size()));
  if (halo) {
    member_boundaries_ = member_boundaries(comm_, members_);
    sum_over_ranks(comm_, counts);
  }
  check_probe_members(scene.config, counts);
}

void ProbesOutput::start(const RunParts& run) {
  run.ranks.write([&] {
    if (run.ranks.root()) file_ = std::make_unique<ProbesCsv>(path_, run.config, ledger_.names());
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
  file_ = std::make_unique<ProbesCsv>(path_, run.config, ledger_.names(), true);
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
  // each member's position and displacement; over several ranks gathered on the root
  std::vector<std::vector<double>> members(members_.size());
  const std::vector<double>& y = run.state.position;
  const std::vector<double>& x = run.scene.particles.reference;
  for (std::size_t p = 0; p < members_.size(); ++p) {
    for (const int i : members_[p]) {
      for (int k = 0; k < 3; ++k) members[p].push_back(y[3 * i + k]);
      for (int k = 0; k < 3; ++k) members[p].push_back(y[3 * i + k] - x[3 * i + k]);
    }
    if (comm_ != MPI_COMM_NULL)
      members[p] = gather_owned(comm_, member_boundaries_[p], members[p].data(), 6);
  }
  ranks.write([&] {
    if (ranks.root())
      file_->write_row(run.state.time, ledger_.kinetic(), ledger_.elastic(), members, columns);
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
