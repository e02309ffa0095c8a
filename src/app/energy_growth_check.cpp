#include "app/energy_growth_check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "parallel/collective.hpp"
#include "parallel/halo.hpp"

namespace fissure {

EnergyGrowthCheck::EnergyGrowthCheck(const Scene& scene, const EnergyLedger& ledger,
                                     const Halo* halo)
    : ledger_(ledger) {
  const Vec3& g = scene.config.gravity;
  const double g_norm = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
  // over several ranks each sums its own rows
  const int begin = halo ? halo->begin() : 0, end = halo ? halo->end() : scene.particles.count();
  for (int i = begin; i < end; ++i) {
    const double* x = &scene.particles.reference[3 * i];
    round_off_energy_ += 1e-12 * scene.particles.mass[i] * g_norm *
                         std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
  }
  if (halo) round_off_energy_ = sum_over_ranks(halo->comm(), round_off_energy_);
}

void EnergyGrowthCheck::after_step(const RunParts& run, const Step& step) {
  const double limit = run.config.integrator.energy_growth_limit;
  if (limit <= 0) return;
  const double kinetic = step.kinetic(), work = ledger_.work(), losses = ledger_.losses();
  const double excess = kinetic + losses - (ledger_.initial() + work);
  // The energy put in, |E(0)| + Σ |work|: not the largest energy seen, which the growth itself
  // raises (a block dropped on the ground gaining 7 times the gravity work at Newmark's impacts
  // raised it with every probe row and was never stopped).
  const double budget =
      std::max({ledger_.absolute_work(std::abs(ledger_.initial())), round_off_energy_, 1e-300});
  // A load's work can be booked a step late (velocity Verlet at a first contact), so the excess
  // must last: a growing mode stays above the limit, a late booking drops below it again.
  // A run that ends sooner is judged at its last step: an excess over two steps or more there
  // stops it too (a 7-step run whose ball was launched at its 2nd step had completed).
  constexpr int kSteps = 10;
  excess_steps_ = excess > limit * budget || !std::isfinite(excess) ? excess_steps_ + 1 : 0;
  const double end = run.config.time.end;
  const bool last = end - run.state.time <= run.tolerance();
  if (excess_steps_ < kSteps && !(last && excess_steps_ >= 2)) return;
  const std::string& type = run.config.integrator.type;
  const double dt = step.h(), stable_dt = run.summary.stable_dt;
  const std::string what = fmt::format(
      "energy grew without a load to account for it at step {} (t = {:.6g} s): kinetic energy "
      "{:.3g} J exceeds the initial energy plus the work put in ({:.3g} J) by {:.3g} times the "
      "energy put in (integrator.energy_growth_limit = {:g})",
      run.summary.steps, run.state.time, kinetic, ledger_.initial() + work - losses,
      excess / budget, limit);
  const std::string advice =
      run.integrator.explicit_step()
          ? fmt::format(
                "the explicit integrator '{}' is unstable at dt = {:.3g} s; the stable "
                "step estimate is {:.3g} s: use time.dt: auto or a time.dt of at most "
                "{:.3g} s",
                type, dt, stable_dt, stable_dt)
          : fmt::format(
                "the integrator '{}' put energy in at dt = {:.3g} s: try a smaller "
                "time.dt (the explicit stable estimate is {:.3g} s){}",
                type, dt, stable_dt,
                run.dynamics.colliders()
                    ? "; with colliders, an impact far faster than the step is safe with "
                      "petsc_newton's backward_euler and sdirk3, which never gain energy at a "
                      "contact; its newmark (with friction), alpha and esdirk4 may, and "
                      "arkode takes colliders explicitly (docs/integrators.md, \"Contact\")"
                    : "");
  throw StopRun("unstable", fmt::format("{}; {}. Outputs up to this point are kept in {}", what,
                                        advice, run.config.output.dir));
}

NamedArrays EnergyGrowthCheck::saved_state() const {
  return {{"energy_growth.excess_steps", {double(excess_steps_)}}};
}

void EnergyGrowthCheck::resume(const RunParts&, const NamedArrays& state) {
  excess_steps_ = static_cast<int>(saved_number(state, "energy_growth.excess_steps"));
}

}  // namespace fissure
