#include "app/time_step.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "core/error.hpp"

namespace fissure {

namespace {

double automatic_time_step(const Config& config, const Integrator& integrator, double stable_dt) {
  const IntegratorSettings& s = config.integrator;
  // A static solve steps through its load increments (IntegratorOptions::load_increments).
  if (const int ramp = s.options ? s.options->load_increments() : 0) return config.time.end / ramp;
  if (integrator.adaptive()) return std::min(config.output.every, config.time.end);
  return config.time.safety * stable_dt;
}

}  // namespace

double run_time_step(const Config& config, const Integrator& integrator, double stable_dt) {
  const double dt =
      config.time.dt_auto ? automatic_time_step(config, integrator, stable_dt) : config.time.dt;
  if (integrator.explicit_step() && !config.time.dt_auto && config.time.dt > stable_dt) {
    const std::string reason =
        fmt::format("{:.3g} s exceeds the stable estimate {:.3g} s of the explicit integrator '{}'",
                    config.time.dt, stable_dt, config.integrator.type);
    if (!config.integrator.allow_unstable_dt)
      throw InputError(config.file, "time.dt",
                       reason +
                           "; use dt: auto, a step below the estimate, an implicit "
                           "integrator (petsc_newton, arkode), or "
                           "integrator.allow_unstable_dt: true to run it anyway");
    fmt::print(stderr, "warning: {}: time.dt = {}; the run may blow up\n", config.file, reason);
  }
  constexpr double max_steps = 1e9;
  if (config.time.end / dt > max_steps)
    throw InputError(
        config.file, config.time.dt_auto ? "time.end" : "time.dt",
        fmt::format("time.end / dt = {:.3g} steps (dt = {:.3g} s) is more than {:.0g}; "
                    "check resolution, moduli and density",
                    config.time.end / dt, dt, max_steps));
  return dt;
}

}  // namespace fissure
