#pragma once
// The run's step size: time.dt, or with dt: auto the integrator's choice, checked against the
// explicit stable estimate and the step count before anything is written.
#include "integrators/integrator.hpp"
#include "scene/config.hpp"

namespace fissure {

// time.dt, or for dt: auto the explicit estimate times time.safety; for the static scheme,
// time.end over its load increments; for an adaptive integrator, the frame interval (its largest
// step). Throws InputError for an explicit step above `stable_dt` (unless
// integrator.allow_unstable_dt, then a warning on stderr) and for more than 1e9 steps.
double run_time_step(const Config& config, const Integrator& integrator, double stable_dt);

}  // namespace fissure
