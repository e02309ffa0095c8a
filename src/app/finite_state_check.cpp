#include "app/finite_state_check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace fissure {

namespace {

// Index of the first particle of [begin, end) whose position or velocity is not finite, or n.
int first_nonfinite(const State& s, int begin, int end) {
  const int n = static_cast<int>(s.position.size() / 3);
  int first = n;
#pragma omp parallel for reduction(min : first) schedule(static)
  for (int i = begin; i < end; ++i)
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(s.position[3 * i + k]) || !std::isfinite(s.velocity[3 * i + k]))
        first = std::min(first, i);
  return first;
}

}  // namespace

void FiniteStateCheck::after_step(const RunParts& run, const Step&) {
  const int n = run.scene.particles.count();
  const int bad = run.ranks.min(first_nonfinite(run.state, run.ranks.begin(), run.ranks.end()));
  if (bad == n) return;
  const double* x = &run.scene.particles.reference[3 * bad];
  throw StopRun(
      "nonfinite",
      fmt::format("state became non-finite at step {} (t = {:.6g} s), first at particle {} of "
                  "body '{}' (reference position {:.6g}, {:.6g}, {:.6g}); dt = {:.3g} s, stable "
                  "estimate {:.3g} s. Outputs up to this point are kept in {}",
                  run.summary.steps, run.state.time, bad,
                  run.config.bodies[run.scene.particles.body[bad]].name, x[0], x[1], x[2],
                  run.summary.dt, run.summary.stable_dt, run.config.output.dir));
}

}  // namespace fissure
