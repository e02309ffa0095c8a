#include "app/info.hpp"

#include <fmt/format.h>

#include "integrators/integrator.hpp"
#include "model/model.hpp"
#include "scene/scene.hpp"

namespace fissure {

void print_info(const Config& config) {
  make_integrator(config.integrator, config.file);
  const Scene scene = build_scene(config);
  const auto model = make_model(scene);
  const double stable_dt = model->stable_time_step();
  const auto directed = scene.families.directed_bonds();
  const int n = scene.particles.count();
  fmt::print("scene: {} ({})\n", config.name, config.file);
  fmt::print("particles: {}\n", n);
  fmt::print("bonds: {} (each pair once; {:.1f} family members per particle)\n", directed / 2,
             n > 0 ? static_cast<double>(directed) / n : 0.0);
  fmt::print("bytes per bond: {} (stored per directed bond; a force evaluation reads {})\n",
             model->bytes_per_bond(), model->bytes_read_per_bond());
  fmt::print("model: {}\n", model->name());
  for (const auto& [name, value] : model->statistics()) fmt::print("  {}: {:.6g}\n", name, value);
  fmt::print("integrator: {}\n", config.integrator.type);
  fmt::print("stable dt estimate: {:.4g} s\n", stable_dt);
  if (config.time.dt_auto)
    fmt::print("dt: {:.4g} s (auto, safety {})\n", config.time.safety * stable_dt,
               config.time.safety);
  else
    fmt::print("dt: {:.4g} s{}\n", config.time.dt,
               config.time.dt > stable_dt ? " (above the stable estimate)" : "");
  fmt::print("effects: elasticity{}{}{}{}{}{}{}\n",
             config.plasticity_enabled() ? ", plasticity" : "",
             config.anisotropy_enabled() ? ", anisotropy" : "",
             config.fracture_enabled() ? ", fracture" : "", config.contact.self ? ", contact" : "",
             config.colliders.empty() ? "" : ", colliders",
             config.output.surface ? ", surface" : "", config.output.tets ? ", tets" : "");
}

}  // namespace fissure
