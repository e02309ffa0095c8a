#include "app/finite_state_check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace fissure {

namespace {

// Index of the first particle of [begin, end) whose position or velocity is not finite, or end.
int first_nonfinite(const State& s, int begin, int end) {
  int first = end;
#pragma omp parallel for reduction(min : first) schedule(static)
  for (int i = begin; i < end; ++i)
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(s.position[3 * i + k]) || !std::isfinite(s.velocity[3 * i + k]))
        first = std::min(first, i);
  return first;
}

}  // namespace

void FiniteStateCheck::after_step(const RunParts& run, const Step&) {
  // the first particle over the ranks, by its id in the whole scene
  const Families& families = run.scene.families;
  const int n = families.total_rows(), end = run.ranks.end();
  const int local = first_nonfinite(run.state, run.ranks.begin(), end);
  const int bad = run.ranks.min(local < end ? families.global_row(local) : n);
  if (bad == n) return;
  // its reference position and body, from the rank that owns it to every rank
  std::vector<double> where(4, 0.0);
  if (local < end && families.global_row(local) == bad) {
    const double* x = &run.scene.particles.reference[3 * local];
    where = {x[0], x[1], x[2], double(run.scene.particles.body[local])};
  }
  run.ranks.sum(where);
  throw StopRun(
      "nonfinite",
      fmt::format("state became non-finite at step {} (t = {:.6g} s), first at particle {} of "
                  "body '{}' (reference position {:.6g}, {:.6g}, {:.6g}); dt = {:.3g} s, stable "
                  "estimate {:.3g} s. Outputs up to this point are kept in {}",
                  run.summary.steps, run.state.time, bad,
                  run.config.bodies[static_cast<int>(where[3])].name, where[0], where[1], where[2],
                  run.summary.dt, run.summary.stable_dt, run.config.output.dir));
}

}  // namespace fissure
