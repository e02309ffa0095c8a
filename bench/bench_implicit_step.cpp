// Cost of one implicit step against the scene's size: a glass cantilever (the bar swing's 1 m ×
// 0.1 m × 0.1 m bar with Table 1's glass moduli, clamped at one end, under gravity) sampled
// with about N particles, stepped by petsc_newton at `factor` times the explicit stable estimate.
// Prints "key value" lines: particles, bonds, seconds of the first step (it factorizes) and per
// later step (the factor reused: the second step, taken `steps` times from the same state in each
// of `batches` batches, the fastest batch's mean), the same per particle, an explicit step for
// comparison, the integrator's counters over all steps (`later_steps` after the first), and the
// peak resident memory of the process. One size per process, so that the peak is that size's
// (bench/run_implicit_bench.sh runs 1e3, 1e4, 1e5).
//   bench_implicit_step [particles] [steps] [factor] [scheme] [preconditioner] [petsc_options]
//                       [batches] [factor_precision]
// (petsc_options as integrator.petsc_options, e.g. "-ksp_rtol 1e-2"; batches 3 by default;
// factor_precision as integrator.factor_precision, the integrator's default when not given).
#include <fmt/format.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <limits>
#include <string>

#include "integrators/integrator.hpp"
#include "integrators/newton_preconditioner.hpp"
#include "integrators/petsc_newton_settings.hpp"
#include "linear/factor_precision.hpp"
#include "model/model.hpp"
#include "scene/scene.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

double peak_resident_gigabytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1048576.0;  // kilobytes on Linux
}

int run(int argc, char** argv) {
  const double target = argc > 1 ? std::atof(argv[1]) : 1.0e4;
  const int steps = argc > 2 ? std::atoi(argv[2]) : 5;
  const double factor = argc > 3 ? std::atof(argv[3]) : 100;
  const std::string scheme = argc > 4 ? argv[4] : "sdirk4";
  const std::string preconditioner = argc > 5 ? argv[5] : "auto";
  const std::string petsc_options = argc > 6 ? argv[6] : "";
  const int batches = argc > 7 ? std::max(1, std::atoi(argv[7])) : 3;
  const std::string precision =
      argc > 8 ? fmt::format(", factor_precision: {}", argv[8]) : std::string();
  // TetGen gives about 14.8 tets per λ³ at its quality settings; the bar is 0.01 m³.
  const double lambda = std::cbrt(14.8 * 0.01 / target);
  const std::string yaml = fmt::format(
      "time: {{end: 1.0}}\ngravity: [0, 0, -9.81]\nintegrator: {{type: petsc_newton, scheme: {1}, "
      "preconditioner: {2}, petsc_options: \"{4}\"{5}}}\nbodies:\n"
      "  - geometry: {{box: {{min: [0, 0, 0], max: [1.0, 0.1, 0.1]}}}}\n"
      "    resolution: {0}\n    horizon: 1.45\n    material: {{model: lps, density: "
      "2200, bulk_modulus: 3.3e10, shear_modulus: 2.0e10}}\nconstraints:\n  - {{region: {{box: "
      "{{min: [-1, -1, -1], max: [{3}, 1, 1]}}}}, fix: true}}\n",
      lambda, scheme, preconditioner, 0.6 * lambda, petsc_options, precision);
  auto start = Clock::now();
  const fissure::Config config = fissure::parse_config(yaml, "bench_implicit_step.yaml");
  const fissure::Scene scene = fissure::build_scene(config);
  auto model = fissure::make_model(scene);
  fissure::Dynamics dynamics(scene, *model);
  const double scene_seconds = seconds_since(start);
  const double dt = factor * model->stable_time_step();
  const fissure::State initial{scene.particles.reference, scene.particles.velocity, 0};

  auto explicit_integrator = fissure::make_integrator("velocity_verlet", "bench");
  fissure::State s = initial;
  explicit_integrator->step(dynamics, s, dt / factor);
  start = Clock::now();
  for (int k = 0; k < 10; ++k) explicit_integrator->step(dynamics, s, dt / factor);
  const double explicit_seconds = seconds_since(start) / 10;

  auto integrator = fissure::make_integrator(config.integrator, "bench");
  s = initial;
  start = Clock::now();
  integrator->step(dynamics, s, dt);
  const double first_seconds = seconds_since(start);
  // Every later step starts from the state after the first, so that each does the same work
  // (consecutive steps settle towards rest and need fewer Newton iterations); the fastest of
  // `batches` batches of `steps` is reported, as this VM's timings of short steps vary 2-3x.
  const fissure::State after_first = s;
  double step_seconds = std::numeric_limits<double>::infinity();
  for (int batch = 0; batch < batches; ++batch) {
    start = Clock::now();
    for (int k = 0; k < steps; ++k) {
      s = after_first;
      integrator->step(dynamics, s, dt);
    }
    step_seconds = std::min(step_seconds, seconds_since(start) / steps);
  }

  const int n = scene.particles.count();
  fmt::print("particles {}\n", n);
  fmt::print("directed_bonds {}\n", scene.families.directed_bonds());
  fmt::print("scheme {}\npreconditioner {}\n", scheme, preconditioner);
  fmt::print("factor_precision {}\n",
             argc > 8
                 ? argv[8]
                 : fissure::factor_precision_name(fissure::PetscNewtonSettings{}.factor_precision));
  if (preconditioner == "auto")
    fmt::print("preconditioner_chosen {}\n",
               fissure::preconditioner_name(fissure::choose_preconditioner(scene.families)));
  fmt::print("dt {:.4g}\nexplicit_dt_factor {}\n", dt, factor);
  fmt::print("later_steps {}\n", steps * batches);
  fmt::print("scene_seconds {:.3f}\n", scene_seconds);
  fmt::print("first_step_seconds {:.4f}\n", first_seconds);
  fmt::print("step_seconds {:.4f}\n", step_seconds);
  fmt::print("step_us_per_particle {:.3f}\n", 1e6 * step_seconds / n);
  fmt::print("first_step_us_per_particle {:.3f}\n", 1e6 * first_seconds / n);
  fmt::print("explicit_step_seconds {:.5f}\n", explicit_seconds);
  fmt::print("implicit_step_in_explicit_steps {:.1f}\n", step_seconds / explicit_seconds);
  for (const auto& [name, value] : integrator->statistics())
    if (value != 0) fmt::print("{} {:.0f}\n", name, value);
  fmt::print("peak_memory_gb {:.3f}\n", peak_resident_gigabytes());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    // a step that fails (e.g. with smoother options that break CG) is reported, not a crash
    fmt::print(stderr, "bench_implicit_step: {}\n", e.what());
    return 1;
  }
}
