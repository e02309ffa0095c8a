// What each effect costs: wall time per step of the same block with one effect enabled at a
// time, relative to the purely elastic block. Prints "effect seconds_per_step ratio" lines, and
// one line comparing the elastic force kernel with the same row passes and no effect code at all.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <vector>

#include "fracture/post_step.hpp"
#include "integrators/integrator.hpp"
#include "model/model.hpp"
#include "pure_elastic_kernel.hpp"
#include "scene/scene.hpp"

namespace {

// Best of five timings of `steps` symplectic Euler steps followed by the shared post-step.
double seconds_per_step(const std::string& yaml, int steps) {
  const fissure::Scene scene = fissure::build_scene(fissure::parse_config(yaml, "bench.yaml"));
  auto model = fissure::make_model(scene);
  fissure::Dynamics dynamics(scene, *model);
  fissure::PostStep post_step(scene, *model);
  auto integrator = fissure::make_integrator("symplectic_euler", "bench");
  const double dt = 0.5 * model->stable_time_step();
  double best = std::numeric_limits<double>::infinity();
  for (int repeat = 0; repeat < 5; ++repeat) {
    fissure::State state{scene.particles.reference, scene.particles.velocity, 0};
    for (std::size_t k = 0; k < state.position.size(); ++k)
      state.position[k] *= 1.0 + 1e-4 * std::sin(0.37 * k);
    const auto start = std::chrono::steady_clock::now();
    for (int s = 0; s < steps; ++s) {
      integrator->step(dynamics, state, dt);
      dynamics.end_step(dt);
      if (post_step.run(state.position.data())) integrator->bonds_changed();
    }
    best = std::min(
        best,
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / steps);
  }
  return best;
}

// Best of seven timings of `calls` force evaluations by the model's elastic kernel and by the
// kernel with no effect code, alternating; prints both, their ratio, how far their forces differ
// (both sum each row in the same lanes: 0) and how far the model's differ from the same forces
// summed in bond order (the target: within 1e-12 of the kernel before the eight-lane rows).
void compare_with_no_effect_code(const std::string& yaml, int calls) {
  const fissure::Scene scene = fissure::build_scene(fissure::parse_config(yaml, "bench.yaml"));
  auto model = fissure::make_model(scene);
  fissure::bench::PureElasticKernel pure(scene);
  std::vector<double> y = scene.particles.reference;
  for (std::size_t k = 0; k < y.size(); ++k) y[k] *= 1.0 + 1e-4 * std::sin(0.37 * k);
  std::vector<double> f_model(y.size()), f_pure(y.size()), f_sequential(y.size());
  auto time = [&](auto&& evaluate) {
    const auto start = std::chrono::steady_clock::now();
    for (int c = 0; c < calls; ++c) evaluate();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / calls;
  };
  double best_model = std::numeric_limits<double>::infinity(), best_pure = best_model;
  for (int repeat = 0; repeat < 7; ++repeat) {
    best_model = std::min(best_model, time([&] { model->forces(y.data(), f_model.data()); }));
    best_pure = std::min(best_pure, time([&] { pure.forces(y.data(), f_pure.data()); }));
  }
  pure.sequential_forces(y.data(), f_sequential.data());
  double difference = 0, sequential = 0, scale = 0;
  for (std::size_t k = 0; k < y.size(); ++k) {
    difference = std::max(difference, std::abs(f_model[k] - f_pure[k]));
    sequential = std::max(sequential, std::abs(f_model[k] - f_sequential[k]));
    scale = std::max(scale, std::abs(f_model[k]));
  }
  if (scale == 0) scale = 1;
  fmt::print(
      "elastic_kernel seconds_per_call {:.4g} no_effect_code_kernel seconds_per_call {:.4g} "
      "ratio {:.3f} (target <= 1.05) max_force_difference {:.1e} "
      "max_force_difference_bond_order {:.1e} row_kernels {}\n",
      best_model, best_pure, best_model / best_pure, difference / scale, sequential / scale,
      fissure::lps::row_kernels().name);
}

}  // namespace

int main(int argc, char** argv) {
  const int steps = argc > 1 ? std::atoi(argv[1]) : 10;
  const std::string block =
      "time: {{end: 1.0}}\n{}bodies:\n  - geometry: {{box: {{min: [0, 0, 0], max: [0.3, 0.3, "
      "0.3]}}}}\n"
      "    resolution: 0.02\n    material: {{density: 1000, bulk_modulus: 5.0e6, shear_modulus: "
      "5.0e6{}}}\n";
  struct Effect {
    const char* name;
    std::string top, material;
  };
  const Effect effects[] = {
      {"elasticity", "", ""},
      {"plasticity", "", ", plasticity: {yield_stress: 1.0e9}"},
      {"anisotropy", "", ", anisotropy: {direction: [1, 0, 0], ratio: 1.5}"},
      {"fracture", "", ", fracture: {critical_stretch: 10}"},
      {"colliders", "colliders:\n  - {plane: {point: [0, 0, -1], normal: [0, 0, 1]}}\n", ""},
      {"contact", "contact: {self: true}\n", ""},
  };
  double elastic = 0;
  for (const Effect& e : effects) {
    const double seconds =
        seconds_per_step(fmt::format(fmt::runtime(block), e.top, e.material), steps);
    if (elastic == 0) elastic = seconds;
    fmt::print("{} seconds_per_step {:.4g} ratio_to_elastic {:.3f}\n", e.name, seconds,
               seconds / elastic);
  }
  compare_with_no_effect_code(fmt::format(fmt::runtime(block), "", ""), 5 * steps);
  return 0;
}
