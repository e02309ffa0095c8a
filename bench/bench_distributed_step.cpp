// Weak scaling of the distributed explicit step (docs/mpi.md): an elastic bar whose
// length grows with the number of ranks, so that each rank owns about the same number of
// particles; each step is velocity Verlet's step over the rank's own rows (the ghosts'
// positions and dilatation terms through the halo) and the fracture post-step's search. Run
// under mpirun (bench/run_distributed_bench.sh). Prints "key value" lines from rank 0: the
// largest over ranks of the time per step, the halo's bytes per step, the ghost fraction and
// the peak memory.
#include <fmt/format.h>
#include <mpi.h>
#include <petscsys.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "app/run_ranks.hpp"
#include "fracture/bond_breaking.hpp"
#include "integrators/integrator.hpp"
#include "model/model.hpp"
#include "parallel/halo.hpp"
#include "scene/scene.hpp"

namespace {

double largest_over_ranks(double value) {
  double result = 0;
  MPI_Allreduce(&value, &result, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  return result;
}

double peak_rss_mb() {
  rusage usage{};
  return getrusage(RUSAGE_SELF, &usage) == 0 ? usage.ru_maxrss / 1024.0 : 0.0;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

int run(int argc, char** argv) {
  const double per_rank = argc > 1 ? std::atof(argv[1]) : 2.0e4;
  const int steps = argc > 2 ? std::atoi(argv[2]) : 50;
  int ranks = 1, rank = 0;
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  // TetGen gives about 14.8 particles per λ³ (bench_elastic_step.cpp): a 0.1 × 0.1
  // cross-section at λ = 0.01 holds about 148,000 particles per metre of length.
  const double lambda = 0.01, length = per_rank * ranks / 1.48e5;
  const std::string yaml = fmt::format(
      "time: {{end: 1.0}}\nbodies:\n  - geometry: {{box: {{min: [0, 0, 0], max: [{}, 0.1, "
      "0.1]}}}}\n    resolution: {}\n    horizon: 1.45\n"
      "    material: {{density: 1000, bulk_modulus: 5.0e6, shear_modulus: 5.0e6, fracture: "
      "{{critical_stretch: 0.05}}}}\n",
      length, lambda);
  const auto setup_start = std::chrono::steady_clock::now();
  // each rank keeps its own rows' families and its ghosts' bonds to them, as `fissure run` does
  const fissure::Scene scene = fissure::build_scene(
      fissure::parse_config(yaml, "bench.yaml"), fissure::RunRanks::split_over(PETSC_COMM_WORLD));
  // the peak so far: the whole scene sampled and searched, then its own part kept
  const double scene_peak = peak_rss_mb();
  auto model = fissure::make_model(scene);
  fissure::Dynamics dynamics(scene, *model);
  fissure::BondBreaking fracture(scene, *model);
  const fissure::Halo halo(
      PETSC_COMM_WORLD, scene.families,
      scene.boundaries.empty() ? std::vector<int>{0, scene.particles.count()} : scene.boundaries);
  dynamics.distribute(halo);
  fracture.distribute(halo);
  const double setup = seconds_since(setup_start);

  const int n = scene.families.total_rows(), begin = halo.begin(), end = halo.end();
  fissure::State state{scene.particles.reference, scene.particles.velocity, 0.0};
  for (std::size_t k = 0; k < state.position.size(); ++k)
    state.position[k] *=
        1.0 + 1e-4 * std::sin(0.37 * double(3 * scene.families.global_row(static_cast<int>(k / 3)) +
                                            k % 3));
  const double dt = 0.5 * model->stable_time_step();
  auto integrator = fissure::make_integrator("velocity_verlet", "bench");
  integrator->step(dynamics, state, dt);  // the first step also computes the first acceleration
  MPI_Barrier(PETSC_COMM_WORLD);
  const auto start = std::chrono::steady_clock::now();
  std::size_t broken = 0;
  for (int s = 0; s < steps; ++s) {
    integrator->step(dynamics, state, dt);
    const std::size_t pairs = fracture.run(state.position.data());
    if (pairs > 0) integrator->bonds_changed();
    broken += pairs;
  }
  const double per_step = seconds_since(start) / steps;

  const double owned = end - begin, ghosts = static_cast<double>(halo.ghosts().size());
  // per step: the positions (3 doubles) and the force terms (4 doubles) of every ghost
  const double halo_bytes = static_cast<double>(halo.received_bytes(3) + halo.received_bytes(4));
  const double bonds =
      static_cast<double>(scene.families.offsets[end] - scene.families.offsets[begin]);
  const double results[] = {largest_over_ranks(per_step),
                            largest_over_ranks(ghosts / owned),
                            largest_over_ranks(halo_bytes),
                            largest_over_ranks(peak_rss_mb()),
                            largest_over_ranks(setup),
                            largest_over_ranks(bonds),
                            largest_over_ranks(double(scene.families.directed_bonds())),
                            largest_over_ranks(double(scene.particles.count())),
                            largest_over_ranks(scene_peak)};
  if (rank == 0) {
    fmt::print("ranks {}\n", ranks);
    fmt::print("particles {}\n", n);
    fmt::print("particles_per_rank {:.0f}\n", double(n) / ranks);
    fmt::print("largest_bonds_per_rank {:.0f}\n", results[5]);
    fmt::print("largest_kept_bonds_per_rank {:.0f}\n", results[6]);      // own and ghost rows
    fmt::print("largest_kept_particles_per_rank {:.0f}\n", results[7]);  // own and ghosts
    fmt::print("setup_seconds {:.2f}\n", results[4]);
    fmt::print("seconds_per_step {:.5f}\n", results[0]);
    fmt::print("ghost_fraction {:.3f}\n", results[1]);
    fmt::print("halo_bytes_per_step {:.0f}\n", results[2]);
    fmt::print("peak_rss_mb_per_rank {:.0f}\n", results[3]);
    fmt::print("scene_peak_rss_mb_per_rank {:.0f}\n", results[8]);
    fmt::print("broken_bonds {}\n", broken);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (PetscInitialize(&argc, &argv, nullptr, nullptr) != 0) return 2;
  int result = 1;
  try {
    result = run(argc, argv);
  } catch (const std::exception& e) {
    fmt::print(stderr, "bench_distributed_step: {}\n", e.what());
    MPI_Abort(PETSC_COMM_WORLD, 1);
  }
  PetscFinalize();
  return result;
}
