#pragma once
// probes.csv (io/probes_csv.hpp) every output.probe_every: a row of the probes' mean positions and
// the energy ledger, sampled at that time; also the largest particle speed at a row
// (summary.json max_speed). An output of the run loop (app/observer.hpp).
#include <mpi.h>

#include "app/energy_ledger.hpp"
#include "app/output_schedule.hpp"
#include "io/probes_csv.hpp"

namespace fissure {

class Halo;

class ProbesOutput : public Observer {
 public:
  // Throws InputError if a probe region holds no particle (over several ranks, on every rank:
  // `halo` non-null). Collective.
  ProbesOutput(const Scene& scene, EnergyLedger& ledger, const Halo* halo);
  std::string name() const override { return "probes"; }
  void start(const RunParts& run) override;
  // Cuts probes.csv back to its length at the checkpoint and appends from there.
  void resume(const RunParts& run, const NamedArrays& state) override;
  void after_step(const RunParts& run, const Step& step) override;
  // A last row at the state the run ended in, unless it is not finite or has its row.
  void finish(const RunParts& run, RunEnd end) override;
  void summarize(RunSummary& summary) const override;
  NamedArrays saved_state() const override;

 private:
  void write_row(const RunParts& run);

  EnergyLedger& ledger_;
  std::string path_;
  // Each probe's members among this rank's own rows; over several ranks, where each rank's
  // start among the members of the whole scene (their values are gathered on the root).
  std::vector<std::vector<int>> members_;
  MPI_Comm comm_ = MPI_COMM_NULL;
  std::vector<std::vector<int>> member_boundaries_;
  std::unique_ptr<ProbesCsv> file_;
  OutputSchedule schedule_;
  double last_time_ = -1;  // time of the last row
  double max_speed_ = 0;   // the largest |v_i| at a row [m/s]
};

}  // namespace fissure
