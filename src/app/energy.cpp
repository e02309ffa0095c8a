#include "app/energy.hpp"

namespace fissure {

double kinetic_energy(const std::vector<double>& mass, const std::vector<double>& velocity) {
  return kinetic_energy(mass, velocity, 0, static_cast<int>(mass.size()));
}

double kinetic_energy(const std::vector<double>& mass, const std::vector<double>& velocity,
                      int first, int end) {
  double sum = 0;
#pragma omp parallel for reduction(+ : sum) schedule(static)
  for (int i = first; i < end; ++i) {
    const double* v = &velocity[3 * i];
    sum += mass[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  }
  return 0.5 * sum;
}

}  // namespace fissure
