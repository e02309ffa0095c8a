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

double Model::forces_and_energy(const double* y, double* f) {
  forces(y, f);
  return elastic_energy(y);
}

double influence(const MaterialPoints& m, int i, const double* xi, double xi_length) {
  if (m.anisotropy.empty()) return m.horizon[i] / xi_length;  // Eq 5
  const auto& G = m.anisotropy[i];
  double g[3];
  for (int r = 0; r < 3; ++r) g[r] = G[3 * r] * xi[0] + G[3 * r + 1] * xi[1] + G[3 * r + 2] * xi[2];
  return m.horizon[i] / std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);  // Eq 17
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
  if (scene.config.anisotropy_enabled()) {
    m.anisotropy.resize(n);
    for (int i = 0; i < n; ++i)
      m.anisotropy[i] = scene.config.bodies[particles.body[i]].material.anisotropy.G;
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
