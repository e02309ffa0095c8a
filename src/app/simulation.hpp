#pragma once
// The shared run loop: integrator step, checks, output as it goes, summary at the end.
#include <mpi.h>

#include <string>
#include <utility>
#include <vector>

#include "scene/config.hpp"

namespace fissure {

class CheckpointReader;

struct RunOptions {
  bool progress = false;  // a progress line on stderr
  // Go on from this checkpoint of a run of the same config into config.output.dir (the output
  // after the checkpoint is dropped), instead of starting at t = 0.
  const CheckpointReader* resume = nullptr;
  // The ranks to spread the run over: MPI_COMM_NULL for those mpirun started (one without it).
  // On several, each rank advances its own rows and writes its piece of each frame
  // (docs/mpi.md); every rank calls run_simulation with the same config.
  MPI_Comm comm = MPI_COMM_NULL;
};

struct RunSummary {
  long particles = 0;
  int ranks = 1;   // MPI ranks the run was spread over
  long bonds = 0;  // each pair counted once
  long steps = 0;
  double dt = 0;
  double stable_dt = 0;
  double wall_seconds = 0;
  double seconds_per_step = 0;
  double setup_seconds = 0;
  double peak_rss_mb = 0;            // over several ranks, the largest rank's
  double max_speed = 0;              // the largest particle speed at a probe row [m/s]
  double energy_drift = 0;           // the energy ledger's balance error at the end (relative)
  long broken_bonds = 0;             // each pair counted once, initial cracks included
  long fragments = 0;                // connected components of intact bonds at the end
  std::string status = "completed";  // completed | nonfinite | unstable | failed
  std::string message;               // why a run stopped early
  // The energy ledger at the end (app/energy_ledger.hpp): kinetic, elastic, initial, scale,
  // balance, then probes.csv's ledger columns.
  std::vector<std::pair<std::string, double>> energy;
  long post_steps = 0;         // calls of the shared post-step (one per accepted step)
  long force_evaluations = 0;  // evaluations of the model's internal forces
  std::string integrator;      // integrator.type
  std::vector<std::pair<std::string, double>> integrator_statistics;
  std::vector<std::pair<std::string, double>> model_statistics;  // Model::statistics()
};

// Runs the scene into config.output.dir. Throws InputError for unusable input and RunError when
// the run cannot go on: the state turned non-finite, energy grew without a load putting it in,
// or the integrator failed; summary.json then records the status and the message. With
// output.checkpoint_every it writes output.dir/checkpoint.bin as it goes (docs/output.md).
RunSummary run_simulation(const Config& config, const RunOptions& options);

double peak_rss_mb();

}  // namespace fissure
