// What each effect costs: wall time per step of the same block with one effect enabled at a
// time, relative to the purely elastic block. Prints "effect seconds_per_step ratio" lines.
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "fracture/post_step.hpp"
#include "integrators/integrator.hpp"
#include "model/model.hpp"
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
  return 0;
}
