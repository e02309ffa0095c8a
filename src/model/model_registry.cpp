#include "model/model_registry.hpp"

#include <fmt/format.h>

#include "core/error.hpp"
#include "model/lps_model.hpp"
#include "model/paper_model.hpp"
#include "scene/kind_list.hpp"
#include "scene/scene.hpp"

namespace fissure {

namespace {

std::vector<ModelKind>& kinds() {
  static std::vector<ModelKind> registered = [] {
    std::vector<ModelKind> builtin;
    add_kind(builtin, lps_model_kind(), "model");
    add_kind(builtin, paper_model_kind(), "model");
    return builtin;
  }();
  return registered;
}

}  // namespace

void register_model(ModelKind kind) { add_kind(kinds(), std::move(kind), "model"); }

std::vector<std::string> model_names() { return kind_names(kinds()); }

MaterialPoints material_points(const Scene& scene) {
  const Particles& particles = scene.particles;
  MaterialPoints m;
  const int n = particles.count();
  m.bulk_modulus.resize(n);
  m.shear_modulus.resize(n);
  m.density.resize(n);
  m.horizon.resize(n);
  for (int i = 0; i < n; ++i) {
    const int b = particles.body[i];
    const Material& material = scene.config.bodies[b].material;
    m.bulk_modulus[i] = material.bulk_modulus;
    m.shear_modulus[i] = material.shear_modulus;
    m.density[i] = material.density;
    m.horizon[i] = scene.horizon_of_body[b];
  }
  if (scene.config.anisotropy_enabled()) {
    m.anisotropy.resize(n);
    for (int i = 0; i < n; ++i)
      m.anisotropy[i] = scene.config.bodies[particles.body[i]].material.anisotropy.G;
  }
  return m;
}

std::unique_ptr<Model> make_model(const Scene& scene) {
  MaterialPoints m = material_points(scene);
  const std::string& name = scene.config.bodies.front().material.model;
  for (const auto& kind : kinds())
    if (kind.name == name) return kind.make(scene, std::move(m));
  throw InputError(
      scene.config.file, "bodies[0].material.model",
      fmt::format("unknown model '{}' (valid: {})", name, fmt::join(model_names(), ", ")));
}

}  // namespace fissure
