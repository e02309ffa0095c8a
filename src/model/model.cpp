#include "model/model.hpp"

#include <limits>

#include "model/lps_model.hpp"
#include "model/paper_model.hpp"
#include "scene/scene.hpp"

namespace fissure {

double Model::elastic_energy(const double* y) {
  const auto& volume = particles_.volume;
  std::vector<double> w(volume.size());
  energy_density(y, w.data());
  double total = 0;
#pragma omp parallel for reduction(+ : total) schedule(static)
  for (std::size_t i = 0; i < w.size(); ++i) total += volume[i] * w[i];
  return total;
}

std::unique_ptr<Model> make_model(const Scene& scene) {
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
  if (scene.config.bodies.front().material.model == ModelVariant::paper)
    return std::make_unique<PaperModel>(particles, scene.families, std::move(m));
  PlasticPoints plasticity;
  if (scene.config.plasticity_enabled()) {
    plasticity.yield_potential.resize(n);
    plasticity.yield_stress.resize(n);
    plasticity.max_plastic_stretch.resize(n);
    for (int i = 0; i < n; ++i) {
      const PlasticitySettings& p = scene.config.bodies[particles.body[i]].material.plasticity;
      // A body without plasticity in a plastic scene never yields.
      plasticity.yield_potential[i] = p.enabled ? p.yield : std::numeric_limits<double>::infinity();
      plasticity.yield_stress[i] = p.yield_stress;
      plasticity.max_plastic_stretch[i] = p.max_plastic_stretch;
    }
  }
  return std::make_unique<LpsModel>(particles, scene.families, std::move(m),
                                    scene.config.bodies.front().material.surface_correction,
                                    scene.config.plasticity_enabled() ? &plasticity : nullptr);
}

}  // namespace fissure
