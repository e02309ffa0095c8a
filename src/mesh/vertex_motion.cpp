#include "mesh/vertex_motion.hpp"

#include <cstddef>

namespace fissure {

namespace {

// Σ_p m_p a_p / Σ_p m_p over the particles of the tets around vertex v, for the per-particle
// vector a = f(p) (3 components); the ¼ of Eqs 20–21 cancels.
template <class Field>
void mass_average(const SplitMesh& mesh, const std::vector<int>& particle, const double* mass,
                  int v, Field field, double out[3]) {
  double weight = 0, sum[3] = {0, 0, 0};
  const int o = mesh.origin[v];
  for (const int* c = mesh.corners_begin(o); c != mesh.corners_end(o); ++c) {
    if (mesh.mesh.tets[*c] != v) continue;
    const int p = particle[*c / 4];
    const double m = mass[p];
    weight += m;
    for (int k = 0; k < 3; ++k) sum[k] += m * field(p, k);
  }
  for (int k = 0; k < 3; ++k) out[k] = weight > 0 ? sum[k] / weight : 0.0;
}

}  // namespace

void advance_vertices(SplitMesh& mesh, const std::vector<int>& particle, const double* mass,
                      const double* velocity, double dt) {
  const int n = mesh.vertex_count();
#pragma omp parallel for schedule(static)
  for (int v = 0; v < n; ++v) {
    double vv[3];
    mass_average(
        mesh, particle, mass, v, [&](int p, int k) { return velocity[3 * p + k]; }, vv);
    for (int k = 0; k < 3; ++k) mesh.position[3 * static_cast<std::size_t>(v) + k] += dt * vv[k];
  }
}

void place_vertices(SplitMesh& mesh, const std::vector<int>& particle, const double* mass,
                    const double* reference, const double* y) {
  const int n = mesh.vertex_count();
#pragma omp parallel for schedule(static)
  for (int v = 0; v < n; ++v) {
    double u[3];
    mass_average(
        mesh, particle, mass, v, [&](int p, int k) { return y[3 * p + k] - reference[3 * p + k]; },
        u);
    for (int k = 0; k < 3; ++k) {
      const std::size_t i = 3 * static_cast<std::size_t>(v) + k;
      mesh.position[i] = mesh.mesh.vertices[i] + u[k];
    }
  }
}

}  // namespace fissure
