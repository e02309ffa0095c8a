#include "app/energy.hpp"

namespace fissure {

double kinetic_energy(const std::vector<double>& mass, const std::vector<double>& velocity) {
  double sum = 0;
  const int n = static_cast<int>(mass.size());
#pragma omp parallel for reduction(+ : sum) schedule(static)
  for (int i = 0; i < n; ++i) {
    const double* v = &velocity[3 * i];
    sum += mass[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  }
  return 0.5 * sum;
}

}  // namespace fissure
