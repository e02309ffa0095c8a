#include "model/model.hpp"

#include <stdexcept>

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

double Model::rows_energy(const double* y, const std::vector<int>& rows) {
  std::vector<double> w(particles_.volume.size());
  energy_density(y, w.data());
  double total = 0;
  for (const int i : rows) total += particles_.volume[i] * w[i];
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

void Model::distribute(const Halo&) {
  throw std::invalid_argument("material.model " + name() +
                              " cannot be evaluated over several ranks yet (docs/mpi.md)");
}

}  // namespace fissure
