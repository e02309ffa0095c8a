// `fissure run` over several ranks: a velocity Verlet fracture run with a pre-crack crossing rank
// boundaries gives positions, damage and broken bonds bitwise equal at every frame; a checkpoint
// written on 2 ranks resumes on 1 and on 3 and matches an uninterrupted run; summary.json records
// ranks; a run on N ranks writes .pvtu frames. The
// whole run loop (run_simulation) runs on the ranks of the test and on sub-communicators of them,
// against the same scene run on one rank.
#include <gtest/gtest.h>
#include <petscsys.h>
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include "app/checkpoint.hpp"
#include "app/simulation.hpp"
#include "core/error.hpp"
#include "io/checkpoint_file.hpp"
#include "io/vtu_reader.hpp"
#include "parallel/ownership.hpp"
#include "ranks.hpp"
#include "scene/scene.hpp"

namespace fissure {
namespace {

namespace fs = std::filesystem;

constexpr double kEnd = 0.02;  // s: about 200 steps, the crack opens through the cuts

// The slab of DistributedRun, pulled apart across a pre-crack, through the run loop: frames every
// kEnd/5, probes every frame, a checkpoint at 0.6 kEnd (the last one the run writes).
Config pulled_slab(const std::string& dir, const std::string& integrator,
                   const std::vector<std::string>& overrides = {}) {
  const std::string yaml = fmt::format(
      "time: {{end: {}, dt: auto}}\n"
      "integrator: {}\n"
      "gravity: [0, -9.81, 0]\n"
      "bodies:\n"
      "  - geometry: {{box: {{min: [0, 0, 0], max: [0.3, 0.1, 0.05]}}}}\n"
      "    resolution: 0.02\n"
      "    material: {{density: 1000, bulk_modulus: 2.0e6, shear_modulus: 1.0e6, fracture: "
      "{{critical_stretch: 0.01, alpha: 1.0}}}}\n"
      "initial_cracks:\n"
      "  - {{plane: {{point: [0.15, 0, 0], normal: [1, 0, 0], region: {{box: {{min: [-1, -1, -1], "
      "max: [1, 0.04, 1]}}}}}}}}\n"
      "constraints:\n"
      "  - {{region: {{box: {{min: [-1, -1, -1], max: [0.03, 1, 1]}}}}, velocity: [-2, 0, 0]}}\n"
      "  - {{region: {{box: {{min: [0.27, -1, -1], max: [1, 1, 1]}}}}, velocity: [2, 0, 0]}}\n"
      "probes:\n"
      "  - {{name: end, region: {{box: {{min: [0.27, -1, -1], max: [1, 1, 1]}}}}}}\n"
      "output: {{dir: {}, every: {}, probe_every: {}, checkpoint_every: {}}}\n",
      kEnd, integrator, dir, kEnd / 5, kEnd / 5, 0.6 * kEnd);
  return parse_config(yaml, "pulled_slab.yaml", overrides);
}

Config pulled_slab(const std::string& dir) { return pulled_slab(dir, "{type: velocity_verlet}"); }

// An elastic slab held at both ends, struck in the middle (across the ranks' cuts) by a light
// dynamic sphere, which the slab's reaction throws back.
Config struck_slab(const std::string& dir, const std::string& integrator) {
  const std::string yaml = fmt::format(
      "time: {{end: {}, dt: auto}}\n"
      "integrator: {}\n"
      "bodies:\n"
      "  - geometry: {{box: {{min: [0, 0, 0], max: [0.3, 0.1, 0.05]}}}}\n"
      "    resolution: 0.02\n"
      "    material: {{density: 1000, bulk_modulus: 2.0e6, shear_modulus: 1.0e6}}\n"
      "constraints:\n"
      "  - {{region: {{box: {{min: [-1, -1, -1], max: [0.03, 1, 1]}}}}, fix: true}}\n"
      "  - {{region: {{box: {{min: [0.27, -1, -1], max: [1, 1, 1]}}}}, fix: true}}\n"
      "colliders:\n"
      "  - {{sphere: {{center: [0.15, 0.05, 0.098], radius: 0.05}}, velocity: [0, 0, -1], mass: "
      "0.5}}\n"
      "output: {{dir: {}, every: {}}}\n",
      kEnd, integrator, dir, kEnd / 5);
  return parse_config(yaml, "struck_slab.yaml");
}

Config struck_slab(const std::string& dir) { return struck_slab(dir, "{type: velocity_verlet}"); }

// The first `size` ranks of the test's, or MPI_COMM_NULL on the others (MPI_Comm_split).
MPI_Comm first_ranks(int size) {
  MPI_Comm comm = MPI_COMM_NULL;
  const int in = test::rank() < size ? 0 : MPI_UNDEFINED;
  EXPECT_EQ(MPI_Comm_split(PETSC_COMM_WORLD, in, test::rank(), &comm), MPI_SUCCESS);
  return comm;
}

// Runs the scene into `dir` on the first `size` ranks; the others wait. The root's summary.
RunSummary run_on(
    int size, const std::string& dir, const CheckpointReader* resume = nullptr,
    const std::function<Config(const std::string&)>& scene = [](const auto& dir) {
      return pulled_slab(dir);
    }) {
  RunSummary summary;
  MPI_Comm comm = first_ranks(size);
  if (comm != MPI_COMM_NULL) {
    RunOptions options;
    options.comm = comm;
    options.resume = resume;
    const Config config = resume ? checkpoint_config(*resume, dir) : scene(dir);
    summary = run_simulation(config, options);
    MPI_Comm_free(&comm);
  }
  test::idle_barrier();
  return summary;
}

// A run's summary (the fields the tests read) sent from rank `from` to every rank.
RunSummary shared_summary(const RunSummary& s, int from) {
  std::string text;
  if (test::rank() == from) {
    text = fmt::format("{} {} {} {} {} {:a} {}\n", s.ranks, s.steps, s.broken_bonds, s.fragments,
                       s.post_steps, s.energy_drift, s.status);
    for (const auto* entries : {&s.energy, &s.integrator_statistics}) {
      text += fmt::format("{}\n", entries->size());
      for (const auto& [name, value] : *entries) text += fmt::format("{} {:a}\n", name, value);
    }
  }
  int length = static_cast<int>(text.size());
  EXPECT_EQ(MPI_Bcast(&length, 1, MPI_INT, from, PETSC_COMM_WORLD), MPI_SUCCESS);
  text.resize(length);
  EXPECT_EQ(MPI_Bcast(text.data(), length, MPI_CHAR, from, PETSC_COMM_WORLD), MPI_SUCCESS);
  std::istringstream in(text);
  std::string drift, value;
  RunSummary r;
  in >> r.ranks >> r.steps >> r.broken_bonds >> r.fragments >> r.post_steps >> drift >> r.status;
  r.energy_drift = std::strtod(drift.c_str(), nullptr);
  for (auto* entries : {&r.energy, &r.integrator_statistics}) {
    std::size_t count = 0;
    in >> count;
    entries->resize(count);
    for (auto& [name, number] : *entries) {
      in >> name >> value;
      number = std::strtod(value.c_str(), nullptr);
    }
  }
  return r;
}

// A one-rank run: its folder, its scene, and about how long it takes.
struct AloneRun {
  std::string dir;
  std::function<Config(const std::string&)> scene;
  double cost = 1;
};

// Runs each of `runs` alone on one rank, side by side over the ranks (the costliest first, each
// on the rank with the least work so far): a run on one rank is the same on any rank. Every rank
// gets every run's summary.
std::vector<RunSummary> run_each_alone(const std::vector<AloneRun>& runs) {
  std::vector<std::size_t> order(runs.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return runs[a].cost > runs[b].cost; });
  std::vector<double> load(test::ranks(), 0.0);
  std::vector<int> on(runs.size());
  for (const std::size_t k : order) {
    on[k] = static_cast<int>(std::min_element(load.begin(), load.end()) - load.begin());
    load[on[k]] += runs[k].cost;
  }
  std::vector<RunSummary> summaries(runs.size());
  MPI_Comm alone = MPI_COMM_NULL;
  EXPECT_EQ(MPI_Comm_split(PETSC_COMM_WORLD, test::rank(), 0, &alone), MPI_SUCCESS);
  for (const std::size_t k : order)
    if (on[k] == test::rank()) {
      RunOptions options;
      options.comm = alone;
      summaries[k] = run_simulation(runs[k].scene(runs[k].dir), options);
    }
  MPI_Comm_free(&alone);
  test::idle_barrier();
  for (std::size_t k = 0; k < runs.size(); ++k) summaries[k] = shared_summary(summaries[k], on[k]);
  return summaries;
}

// A fresh folder, the same on every rank; one per number of ranks, as ctest runs them side by
// side (the next run of the same ranks clears it).
std::string scratch(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / fmt::format("fissure_parallel_{}_{}", name, test::ranks());
  if (test::rank() == 0) fs::remove_all(dir);
  test::idle_barrier();
  return dir.string();
}

// Frame k of a run's folder: particles_k.vtu on one rank, particles_k.pvtu on several.
std::string frame(const std::string& dir, int k) {
  const std::string stem = fmt::format("{}/particles_{:06d}", dir, k);
  return fs::exists(stem + ".pvtu") ? stem + ".pvtu" : stem + ".vtu";
}

// The pulled slab yielding before it breaks.
Config plastic_slab(const std::string& dir) {
  return pulled_slab(dir, "{type: velocity_verlet}",
                     {"bodies.0.material.plasticity.yield_stress=2.0e3"});
}

// The pulled slab stepped by ARKODE's Bogacki–Shampine method at a fixed step.
Config arkode_fixed_slab(const std::string& dir) {
  return pulled_slab(dir, "{type: arkode, method: BOGACKI_SHAMPINE_4_2_3, fixed_step: true}");
}

// The one-rank runs the tests below compare with, run once in the program and side by side
// (run_each_alone); the tests never write into their folders. Folder and summary by name.
const std::pair<std::string, RunSummary>& one_rank_run(const std::string& name) {
  static std::map<std::string, std::pair<std::string, RunSummary>> runs;
  if (runs.empty()) {
    const std::vector<std::string> names = {"pulled", "struck", "plastic", "arkode_fixed"};
    const std::vector<AloneRun> alone = {
        {scratch("pulled_one"), [](const std::string& dir) { return pulled_slab(dir); }, 2},
        {scratch("struck_one"), [](const std::string& dir) { return struck_slab(dir); }, 1},
        {scratch("plastic_one"), plastic_slab, 3},
        {scratch("arkode_fixed_one"), arkode_fixed_slab, 5}};
    const std::vector<RunSummary> summaries = run_each_alone(alone);
    for (std::size_t k = 0; k < names.size(); ++k)
      runs.emplace(names[k], std::pair{alone[k].dir, summaries[k]});
  }
  return runs.at(name);
}

// The pulled slab (velocity Verlet) on the first `size` ranks, run once in the program: the
// tests that compare with it share it and never write into its folder. Its folder and summary.
const std::pair<std::string, RunSummary>& pulled_run(int size) {
  if (size == 1) return one_rank_run("pulled");
  static std::map<int, std::pair<std::string, RunSummary>> runs;
  auto found = runs.find(size);
  if (found == runs.end()) {
    const std::string dir = scratch(fmt::format("pulled_on_{}", size));
    found = runs.emplace(size, std::pair{dir, run_on(size, dir)}).first;
  }
  return found->second;
}

// The entries of frames `a` and `b` whose bits differ, over the positions and every point array.
long differing_entries(const std::string& a, const std::string& b) {
  const VtuGrid x = read_vtu(a), y = read_vtu(b);
  auto differ = [](const std::vector<double>& u, const std::vector<double>& v) {
    if (u.size() != v.size()) return static_cast<long>(std::max(u.size(), v.size()));
    long count = 0;
    for (std::size_t k = 0; k < u.size(); ++k)
      count += std::memcmp(&u[k], &v[k], sizeof(double)) != 0;
    return count;
  };
  long count = differ(x.points, y.points);
  for (const auto& [name, array] : x.point_data) {
    const auto other = y.point_data.find(name);
    count += other == y.point_data.end() ? 1 : differ(array.values, other->second.values);
  }
  return count + (x.point_data.size() != y.point_data.size());
}

// Copies the run folder `from` into each of `copies` (on rank 0; every rank waits for it).
void copy_run(const std::string& from, const std::vector<std::string>& copies) {
  if (test::rank() == 0)
    for (const std::string& copy : copies) fs::copy(from, copy, fs::copy_options::recursive);
  test::idle_barrier();
}

// The energy ledger's entry `name` in a run's summary, NaN when it has none.
double energy_entry(const RunSummary& s, const std::string& name) {
  for (const auto& [entry, value] : s.energy)
    if (entry == name) return value;
  return std::nan("");
}

TEST(DistributedRunLoop, FramesEqualOneRankBitwise) {
  const auto& [one, reference] = pulled_run(1);
  const auto& [all, spread] = pulled_run(test::ranks());
  if (test::rank() != 0) return;
  ASSERT_EQ(spread.status, "completed");
  EXPECT_EQ(spread.ranks, test::ranks());
  EXPECT_EQ(spread.steps, reference.steps);
  EXPECT_EQ(spread.broken_bonds, reference.broken_bonds);
  EXPECT_GT(reference.broken_bonds, 200);  // the crack runs through the cuts
  EXPECT_EQ(spread.fragments, reference.fragments);
  // the ledger is summed in another order: equal to round-off, not bitwise
  EXPECT_NEAR(spread.energy_drift, reference.energy_drift, 1e-9);
  EXPECT_EQ(spread.post_steps, reference.post_steps);
  for (int k = 0; k <= 5; ++k) {
    SCOPED_TRACE(k);
    EXPECT_EQ(fs::exists(fmt::format("{}/particles_{:06d}.pvtu", all, k)), test::ranks() > 1);
    EXPECT_EQ(differing_entries(frame(one, k), frame(all, k)), 0);
  }
  // probes.csv: the same rows (printed to 9 digits)
  std::ifstream a(one + "/probes.csv"), b(all + "/probes.csv");
  const std::string rows_a((std::istreambuf_iterator<char>(a)), std::istreambuf_iterator<char>());
  const std::string rows_b((std::istreambuf_iterator<char>(b)), std::istreambuf_iterator<char>());
  EXPECT_EQ(std::count(rows_a.begin(), rows_a.end(), '\n'), 7);
  EXPECT_EQ(rows_a, rows_b);
}

// The largest |a − b| over the positions of frames `a` and `b`.
double largest_difference(const std::string& a, const std::string& b) {
  const VtuGrid x = read_vtu(a), y = read_vtu(b);
  if (x.points.size() != y.points.size()) return HUGE_VAL;
  double largest = 0;
  for (std::size_t k = 0; k < x.points.size(); ++k)
    largest = std::max(largest, std::abs(x.points[k] - y.points[k]));
  return largest;
}

// A dynamic collider moves under the reaction of every rank's particles: summed over the ranks
// (in another order than one rank's sum, so to round-off), not each rank's own.
TEST(DistributedRunLoop, DynamicColliderFeelsEveryRank) {
  const auto& [one, reference] = one_rank_run("struck");
  const std::string all = scratch("struck_all");
  const RunSummary spread =
      run_on(test::ranks(), all, nullptr, [](const std::string& dir) { return struck_slab(dir); });
  if (test::rank() != 0) return;
  ASSERT_EQ(spread.status, "completed");
  auto work = [](const RunSummary& s) { return energy_entry(s, "collider_work"); };
  // the sphere pressed on the slab (its work in and out of the particles did not cancel)
  EXPECT_GT(std::abs(work(reference)), 1e-3);
  // the ledger's sums over the ranks: about 200 steps of round-off (1e-16 relative each)
  EXPECT_NEAR(work(spread), work(reference), 1e-12 * std::abs(work(reference)));
  // round-off of the reaction's sum (1e-16 relative) on millimetre motions stays under 1e-15 m
  // (measured: 0 on 2, 3 and 4 ranks); with each rank's sphere under its own rows' reaction
  // alone, the frames differ by 0.7 to 1.7 mm (measured on 2 and 3 ranks)
  for (int k = 1; k <= 5; ++k) EXPECT_LT(largest_difference(frame(one, k), frame(all, k)), 1e-15);
}

TEST(DistributedRunLoop, CheckpointOfTwoRanksResumesOnOneAndOnThree) {
  const int writers = std::min(2, test::ranks()), resumers = std::min(3, test::ranks());
  const std::string on_one = scratch("on_one"), on_more = scratch("on_more");
  const std::string& whole = pulled_run(1).first;
  const std::string& written = pulled_run(writers).first;
  copy_run(written, {on_one, on_more});
  const CheckpointReader checkpoint_one(on_one + "/checkpoint.bin");
  const CheckpointReader checkpoint_more(on_more + "/checkpoint.bin");
  EXPECT_NEAR(checkpoint_one.number("run.time"), 0.6 * kEnd, kEnd / 50);
  const RunSummary one = run_on(1, on_one, &checkpoint_one);
  const RunSummary more = run_on(resumers, on_more, &checkpoint_more);
  if (test::rank() != 0) return;
  EXPECT_EQ(more.ranks, resumers);
  for (const RunSummary* resumed : {&one, &more}) {
    EXPECT_EQ(resumed->status, "completed");
    EXPECT_GT(resumed->broken_bonds, 200);
  }
  // every frame after the checkpoint (0.8 and 1.0 of kEnd) as the uninterrupted run's
  for (int k = 4; k <= 5; ++k) {
    SCOPED_TRACE(k);
    EXPECT_EQ(differing_entries(frame(whole, k), frame(on_one, k)), 0);
    EXPECT_EQ(differing_entries(frame(whole, k), frame(on_more, k)), 0);
  }
}

// The pulled slab yielding before it breaks: the return map on every rank's rows, e^p of the
// pairs the ranks share exchanged, the frames one rank's bit for bit; the checkpoint written on
// all the test's ranks (with every rank's e^p in it) resumes on one rank and on one rank fewer
// as the uninterrupted run.
TEST(DistributedRunLoop, PlasticRunAndItsCheckpointEqualOneRankBitwise) {
  const int fewer = std::max(1, test::ranks() - 1);
  const auto& [whole, reference] = one_rank_run("plastic");
  const std::string spread = scratch("plastic_spread"), on_one = scratch("plastic_on_one"),
                    on_fewer = scratch("plastic_on_fewer");
  const RunSummary all = run_on(test::ranks(), spread, nullptr, plastic_slab);
  copy_run(spread, {on_one, on_fewer});
  const CheckpointReader checkpoint_one(on_one + "/checkpoint.bin");
  const CheckpointReader checkpoint_fewer(on_fewer + "/checkpoint.bin");
  const RunSummary one = run_on(1, on_one, &checkpoint_one);
  const RunSummary resumed = fewer > 1 ? run_on(fewer, on_fewer, &checkpoint_fewer) : one;
  if (test::rank() != 0) return;
  auto dissipated = [](const RunSummary& s) { return energy_entry(s, "plastic_dissipation"); };
  ASSERT_EQ(all.status, "completed");
  EXPECT_GT(dissipated(reference), 0.0);  // the slab yielded
  EXPECT_GT(reference.broken_bonds, 100);
  EXPECT_EQ(all.broken_bonds, reference.broken_bonds);
  // the ranks' shares summed in another order: to round-off
  EXPECT_NEAR(dissipated(all), dissipated(reference), 1e-9 * dissipated(reference));
  for (int k = 0; k <= 5; ++k)
    EXPECT_EQ(differing_entries(frame(whole, k), frame(spread, k)), 0) << k;
  EXPECT_EQ(one.status, "completed");
  EXPECT_EQ(resumed.status, "completed");
  for (int k = 4; k <= 5; ++k) {
    SCOPED_TRACE(k);
    EXPECT_EQ(differing_entries(frame(whole, k), frame(on_one, k)), 0);
    if (fewer > 1) {
      EXPECT_EQ(differing_entries(frame(whole, k), frame(on_fewer, k)), 0);
    }
  }
}

// ARKODE over several ranks (explicit methods): u is an MPI+X vector of each rank's rows. At a
// fixed step every operation on u is entry by entry, so the frames are one rank's bit for bit;
// adaptive steps take their error norm over all ranks, summed in another order, so the step
// sizes and with them the frames differ by round-off, far inside the tolerance.
TEST(DistributedRunLoop, ArkodeFixedStepEqualsOneRankBitwise) {
  const auto& [one, reference] = one_rank_run("arkode_fixed");
  const std::string all = scratch("arkode_all");
  const RunSummary spread = run_on(test::ranks(), all, nullptr, arkode_fixed_slab);
  if (test::rank() != 0) return;
  ASSERT_EQ(spread.status, "completed");
  EXPECT_EQ(spread.broken_bonds, reference.broken_bonds);
  EXPECT_GT(reference.broken_bonds, 200);
  for (int k = 0; k <= 5; ++k) EXPECT_EQ(differing_entries(frame(one, k), frame(all, k)), 0) << k;
}

// A coarser slab stretched at both ends under gravity (no fracture, no contact), stepped by
// ARKODE's adaptive Bogacki–Shampine method at relative tolerance `rtol` for 4 ms (or as
// `overrides` say).
Config stretched_slab(const std::string& dir, double rtol,
                      const std::string& method = "BOGACKI_SHAMPINE_4_2_3",
                      const std::vector<std::string>& overrides = {}) {
  const std::string yaml = fmt::format(
      "time: {{end: 0.004, dt: auto}}\n"
      "integrator: {{type: arkode, method: {}, rtol: {}}}\n"
      "gravity: [0, -9.81, 0]\n"
      "bodies:\n"
      "  - geometry: {{box: {{min: [0, 0, 0], max: [0.3, 0.1, 0.05]}}}}\n"
      "    resolution: 0.03\n"
      "    material: {{density: 1000, bulk_modulus: 2.0e6, shear_modulus: 1.0e6}}\n"
      "constraints:\n"
      "  - {{region: {{box: {{min: [-1, -1, -1], max: [0.03, 1, 1]}}}}, velocity: [-2, 0, 0]}}\n"
      "  - {{region: {{box: {{min: [0.27, -1, -1], max: [1, 1, 1]}}}}, velocity: [2, 0, 0]}}\n"
      "output: {{dir: {}, every: 0.001}}\n",
      method, rtol, dir);
  return parse_config(yaml, "stretched_slab.yaml", overrides);
}

// "Within rtol": the ranks move the answer by less than the tolerance already does, i.e. less
// than the one-rank run's own error against a run at rtol/1000 (measured at 1e-6 over 2 ms on 2,
// 3 and 4 ranks: at most 0.04 of it; over 4 ms on 2 ranks, 0.04–0.2).
TEST(DistributedRunLoop, ArkodeAdaptiveWithinItsTolerance) {
  constexpr double kRtol = 1e-6;
  const std::string tight = scratch("adaptive_tight"), one = scratch("adaptive_one"),
                    all = scratch("adaptive_all");
  const auto at = [](double rtol) {
    return [rtol](const std::string& dir) {
      return stretched_slab(dir, rtol, "BOGACKI_SHAMPINE_4_2_3",
                            {"time.end=0.002", "output.every=0.0005"});
    };
  };
  run_each_alone({{tight, at(kRtol / 1000), 2}, {one, at(kRtol), 1}});
  const RunSummary spread = run_on(test::ranks(), all, nullptr, at(kRtol));
  if (test::rank() != 0) return;
  ASSERT_EQ(spread.status, "completed");
  for (int k = 1; k <= 4; ++k) {
    const double own_error = largest_difference(frame(one, k), frame(tight, k));
    EXPECT_GT(own_error, 0) << k;
    EXPECT_LE(largest_difference(frame(one, k), frame(all, k)), own_error) << k;
  }
}

// petsc_newton over the ranks, within 1e-9 relative of one rank: the pre-cracked slab pulled apart
// by Newmark at 1.75× the explicit limit, Newton to -snes_rtol 1e-12, checkpoints written, with the
// same preconditioner on both sides: the majoriser, factored by CHOLMOD on one rank and by MUMPS's
// parallel Cholesky on several (the same matrix: the same Newton iterations), and GAMG (set up over
// the ranks: other aggregates, other Krylov iterates). Every frame's positions within 1e-9 of the
// largest displacement of one rank's, the same broken bonds, and bonds broken during the run (10
// steps). Measured on 2, 3 and 4 ranks: 4e-14 to 2e-13 of it with the majoriser, 1e-11 to 3e-11
// with GAMG (over 20 steps: 1e-13 to 2e-11, 4e-11 to 9e-11).
TEST(DistributedRunLoop, PetscNewtonWithinOneBillionthOfOneRank) {
  if (test::ranks() == 1) GTEST_SKIP() << "one rank against itself";
  const std::vector<std::string> preconditioners = {"majoriser", "gamg"};
  const auto scene_until = [](const std::string& preconditioner, const std::string& end) {
    return [=](const std::string& dir) {
      return pulled_slab(dir,
                         "{type: petsc_newton, scheme: newmark, preconditioner: " + preconditioner +
                             ", petsc_options: '-snes_rtol 1e-12'}",
                         {"time.dt=0.0002", "time.end=" + end, "output.every=0.001",
                          "output.checkpoint_every=0.001"});
    };
  };
  // the one-rank runs side by side: each preconditioner's first step (the bonds broken after it:
  // the pre-crack's and the first pull's) and its whole run
  std::vector<AloneRun> alone;
  for (const std::string& preconditioner : preconditioners) {
    alone.push_back(
        {scratch("newton_start_" + preconditioner), scene_until(preconditioner, "0.0002")});
    alone.push_back(
        {scratch("newton_one_" + preconditioner), scene_until(preconditioner, "0.002"), 5});
  }
  const std::vector<RunSummary> alone_summaries = run_each_alone(alone);
  for (std::size_t c = 0; c < preconditioners.size(); ++c) {
    const std::string& preconditioner = preconditioners[c];
    SCOPED_TRACE(preconditioner);
    const std::string& one = alone[2 * c + 1].dir;
    const std::string all = scratch("newton_all_" + preconditioner);
    const RunSummary& start = alone_summaries[2 * c];
    const RunSummary& reference = alone_summaries[2 * c + 1];
    const RunSummary spread =
        run_on(test::ranks(), all, nullptr, scene_until(preconditioner, "0.002"));
    // rank 0 checks; every rank goes on to the next case's collective calls alike
    if (test::rank() != 0) continue;
    EXPECT_EQ(spread.status, "completed");
    EXPECT_EQ(reference.status, "completed");
    if (spread.status != "completed" || reference.status != "completed") continue;
    EXPECT_EQ(spread.broken_bonds, reference.broken_bonds);
    EXPECT_GT(reference.broken_bonds, start.broken_bonds);  // and more in the later steps
    EXPECT_TRUE(fs::exists(all + "/checkpoint.bin"));       // written over the ranks
    const double moved = largest_difference(frame(one, 0), frame(one, 2));
    EXPECT_GT(moved, 0.003);  // 2 m/s for 2 ms
    for (int k = 1; k <= 2; ++k) {
      EXPECT_LE(largest_difference(frame(one, k), frame(all, k)), 1e-9 * moved) << k;
    }
    auto statistic = [](const RunSummary& s, const std::string& name) {
      for (const auto& [key, value] : s.integrator_statistics)
        if (key == name) return value;
      return -1.0;
    };
    if (preconditioner == "majoriser") {
      EXPECT_EQ(statistic(spread, "newton_iterations"), statistic(reference, "newton_iterations"));
    }
  }
}

// ARKODE's implicit and IMEX methods over the ranks: its Newton iteration and CG over the ranks'
// rows, the factor of each rank's diagonal block of the nearest members' matrix (block Jacobi;
// one rank factors the whole matrix), so the linear solves stop at other iterates, within the
// linear tolerance ARKODE asks. "Within rtol" as for the explicit method above: the ranks'
// frames differ from one rank's by less than one rank's own error against rtol/1000, here at
// rtol 1e-4 over 0.5 ms (the sudden pull keeps the adaptive steps near 5 µs: about 100 of them).
// Measured on 2, 3 and 4 ranks: at most 0.17 of that error (0.19 over 1 ms; 0.1 at rtol 1e-6
// over 4 ms).
TEST(DistributedRunLoop, ArkodeImplicitAndImexWithinTheirTolerance) {
  if (test::ranks() == 1) GTEST_SKIP() << "one rank against itself";
  constexpr double kRtol = 1e-4;
  const std::vector<std::string> short_run = {"time.end=0.0005", "output.every=0.000125"};
  const std::vector<std::string> methods = {"KVAERNO_4_2_3", "ARK324L2SA"};
  // every method's one-rank runs, at rtol/1000 and at rtol, side by side
  std::vector<AloneRun> alone;
  for (const std::string& method : methods) {
    const std::string options = method + ", preconditioner: nearest";
    const double cost = method == methods.front() ? 2 : 1;  // KVAERNO's take about twice ARK's
    const auto at = [=](double rtol) {
      return [=](const std::string& dir) { return stretched_slab(dir, rtol, options, short_run); };
    };
    alone.push_back({scratch("implicit_tight_" + method), at(kRtol / 1000), 2.5 * cost});
    alone.push_back({scratch("implicit_one_" + method), at(kRtol), cost});
  }
  run_each_alone(alone);
  for (std::size_t m = 0; m < methods.size(); ++m) {
    const std::string& method = methods[m];
    SCOPED_TRACE(method);
    const std::string &tight = alone[2 * m].dir, &one = alone[2 * m + 1].dir;
    const std::string all = scratch("implicit_all_" + method);
    const RunSummary spread = run_on(test::ranks(), all, nullptr, [&](const std::string& dir) {
      return stretched_slab(dir, kRtol, method + ", preconditioner: nearest", short_run);
    });
    // rank 0 checks; every rank goes on to the next method's collective calls alike
    if (test::rank() != 0) continue;
    EXPECT_EQ(spread.status, "completed");
    if (spread.status != "completed") continue;
    for (int k = 1; k <= 4; ++k) {
      const double own_error = largest_difference(frame(one, k), frame(tight, k));
      EXPECT_GT(own_error, 0) << k;
      EXPECT_LE(largest_difference(frame(one, k), frame(all, k)), own_error) << k;
    }
  }
}

// What cannot be spread over ranks yet is refused on every rank before the output folder exists,
// with the key that asks for it (docs/mpi.md).
TEST(DistributedRunLoop, WhatCannotRunOverRanksYetIsRefusedWithItsKey) {
  if (test::ranks() == 1) GTEST_SKIP() << "one rank runs all of these";
  const std::string dir = scratch("refused");
  const std::pair<std::vector<std::string>, std::string> cases[] = {
      {{"integrator.type=petsc_newton", "integrator.preconditioner=scalar"},
       "integrator.preconditioner: 'petsc_newton' cannot run over"},
      {{"integrator.type=petsc_newton", "integrator.preconditioner=tangent"},
       "integrator.preconditioner: 'petsc_newton' cannot run over"},
      {{"integrator.type=arkode", "integrator.method=SDIRK_2_1_2",
        "integrator.preconditioner=tangent"},
       "integrator.preconditioner: 'arkode' cannot run over"},
      {{"contact.self=true"}, "contact.self cannot run over several ranks yet"},
      {{"output.surface=true"}, "output.surface and output.tets cannot be written over several"},
      {{"bodies.0.material.model=paper"},
       "material.model paper cannot be evaluated over several ranks yet"}};
  for (const auto& [overrides, expected] : cases) {
    SCOPED_TRACE(overrides.front());
    std::string message;
    try {
      RunOptions options;
      options.comm = PETSC_COMM_WORLD;
      run_simulation(pulled_slab(dir, "{type: velocity_verlet}", overrides), options);
    } catch (const InputError& e) {
      message = e.what();
    }
    EXPECT_NE(message.find(expected), std::string::npos) << message;
    EXPECT_FALSE(fs::exists(dir));
  }
  // the second-order model, on a slab without fracture (it has none yet)
  std::string message;
  try {
    RunOptions options;
    options.comm = PETSC_COMM_WORLD;
    run_simulation(stretched_slab(dir, 1e-6, "BOGACKI_SHAMPINE_4_2_3",
                                  {"bodies.0.material.surface_correction=fictitious"}),
                   options);
  } catch (const InputError& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("bodies[0].material.surface_correction: fictitious cannot run over "
                         "several ranks yet"),
            std::string::npos)
      << message;
  EXPECT_FALSE(fs::exists(dir));
}

Config exploding_slab(const std::string& dir) {
  const std::string yaml = fmt::format(
      "time: {{end: 0.01, dt: auto}}\n"
      "integrator: {{type: velocity_verlet, energy_growth_limit: 0}}\n"
      "bodies:\n"
      "  - geometry: {{box: {{min: [0, 0, 0], max: [0.3, 0.1, 0.05]}}}}\n"
      "    resolution: 0.02\n"
      "    material: {{density: 1000, bulk_modulus: 2.0e6, shear_modulus: 1.0e6}}\n"
      "constraints:\n"
      "  - {{region: {{box: {{min: [0.27, -1, -1], max: [1, 1, 1]}}}}, velocity: [1e300, 0, 0]}}\n"
      "output: {{dir: {}, every: 1}}\n",
      dir);
  return parse_config(yaml, "exploding_slab.yaml");
}

// The slab without fracture, its far end driven at 1e300 m/s, the energy-growth check off: the
// state becomes non-finite there first, within a few steps. Every rank stops with
// one rank's message: the same step, the same first particle by its id in the whole scene, and
// its reference position and body, which on several ranks only the rank that owns it knows (the
// far end is the last rank's).
TEST(DistributedRunLoop, NonFiniteStateNamesOneRanksParticleOnEveryRank) {
  // the message of the first `size` ranks' run (up to the output folder's name); the others wait
  auto stopped_on = [&](int size, const std::string& dir) {
    std::string message = "(not stopped)";
    MPI_Comm comm = first_ranks(size);
    if (comm != MPI_COMM_NULL) {
      try {
        RunOptions options;
        options.comm = comm;
        run_simulation(exploding_slab(dir), options);
      } catch (const RunError& e) {
        message = e.what();
        message = message.substr(0, message.find(" Outputs up to this point"));
      }
      MPI_Comm_free(&comm);
    }
    test::idle_barrier();
    return message;
  };
  std::string one = stopped_on(1, scratch("nonfinite_one"));  // on rank 0
  const std::string all = stopped_on(test::ranks(), scratch("nonfinite_all"));
  int length = static_cast<int>(one.size());
  ASSERT_EQ(MPI_Bcast(&length, 1, MPI_INT, 0, PETSC_COMM_WORLD), MPI_SUCCESS);
  one.resize(length);
  ASSERT_EQ(MPI_Bcast(one.data(), length, MPI_CHAR, 0, PETSC_COMM_WORLD), MPI_SUCCESS);
  EXPECT_NE(one.find("state became non-finite at step"), std::string::npos) << one;
  EXPECT_EQ(all, one);
  // the particle is the far end's, owned on several ranks by another rank than the root
  const std::size_t at = one.find("first at particle "), x_at = one.find("reference position ");
  ASSERT_NE(at, std::string::npos) << one;
  ASSERT_NE(x_at, std::string::npos) << one;
  const int particle = std::stoi(one.substr(at + 18));
  EXPECT_GT(std::stod(one.substr(x_at + 19)), 0.2) << one;
  const Scene scene = build_scene(exploding_slab(scratch("nonfinite_scene")));
  const std::vector<int> boundaries = split_rows_by_bonds(scene.families.offsets, test::ranks());
  if (test::ranks() > 1) {
    EXPECT_GT(owner_of(boundaries, particle), 0) << one;
  }
}

// Two particles cannot be split over three or more ranks (a rank would own none): every rank
// refuses the scene with the same message before anything is written.
TEST(DistributedRunLoop, MoreRanksThanParticlesIsRefusedOnEveryRank) {
  if (test::ranks() < 3) GTEST_SKIP() << "two particles split over one or two ranks";
  const std::string dir = scratch("too_few"), points = dir + "_points.txt";
  if (test::rank() == 0) std::ofstream(points) << "0 0 0 1e-6\n0.01 0 0 1e-6\n";
  test::idle_barrier();
  const std::string yaml = fmt::format(
      "time: {{end: 1.0e-3, dt: auto}}\n"
      "integrator: {{type: velocity_verlet}}\n"
      "bodies:\n"
      "  - geometry: {{points: {{file: {}}}}}\n"
      "    resolution: 0.01\n"
      "    material: {{density: 1000, bulk_modulus: 2.0e6, shear_modulus: 1.0e6}}\n"
      "output: {{dir: {}}}\n",
      points, dir);
  std::string message;
  try {
    RunOptions options;
    options.comm = PETSC_COMM_WORLD;
    run_simulation(parse_config(yaml, "two_points.yaml"), options);
  } catch (const InputError& e) {
    message = e.what();
  }
  EXPECT_NE(message.find(fmt::format("2 particles are too few for {} ranks", test::ranks())),
            std::string::npos)
      << message;
  EXPECT_FALSE(fs::exists(dir));
}

// A write that fails on one rank only (the last rank's file-size limit, below one piece of a
// frame) stops the run on every rank with that rank's file and reason, within the test's
// timeout; rank 0 records the failure in summary.json.
TEST(DistributedRunLoop, AWriteFailingOnOneRankStopsEveryRank) {
  const std::string dir = scratch("write_fails");
  const int last = test::ranks() - 1;
  ASSERT_NE(std::signal(SIGXFSZ, SIG_IGN), SIG_ERR);  // EFBIG instead of the signal
  rlimit limit{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &limit), 0);
  const rlimit unlimited = limit;
  if (test::rank() == last) {
    limit.rlim_cur = 4096;  // bytes: a piece of a frame here is about 100 kB
    ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &limit), 0);
  }
  std::string message;
  try {
    RunOptions options;
    options.comm = PETSC_COMM_WORLD;
    run_simulation(pulled_slab(dir), options);
  } catch (const RunError& e) {
    message = e.what();
  }
  if (test::rank() == last) {
    ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &unlimited), 0);
  }
  const std::string piece =
      test::ranks() > 1 ? fmt::format("particles_000000_p{}.vtu", last) : "particles_000000.vtu";
  EXPECT_NE(message.find("cannot write " + dir + "/" + piece), std::string::npos) << message;
  if (last > 0) {
    EXPECT_NE(message.find(fmt::format("(on rank {})", last)), std::string::npos) << message;
  }
  test::idle_barrier();
  if (test::rank() != 0) return;
  std::ifstream summary(dir + "/summary.json");
  const std::string text((std::istreambuf_iterator<char>(summary)),
                         std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\"status\": \"failed\""), std::string::npos) << text;
}

}  // namespace
}  // namespace fissure
