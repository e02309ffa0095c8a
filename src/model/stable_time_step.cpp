#include "model/stable_time_step.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fissure {

double gershgorin_time_step(const Particles& particles, const Families& families,
                            const MaterialPoints& materials, const BondConstants& k) {
  const int n = particles.count();
  const auto& off = families.offsets;
  const auto& nbr = families.neighbors;
  const auto& V = particles.volume;
  // α = ½(κ − 5μ/3), the θθ coefficient of the energy (notes §3); S_i = Σ_j |c_ij| V_j.
  std::vector<double> alpha_plus(n), S(n);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    alpha_plus[i] =
        std::max(0.0, 0.5 * (materials.bulk_modulus[i] - 5.0 / 3.0 * materials.shear_modulus[i]));
    double s = 0;
    for (int b = off[i]; b < off[i + 1]; ++b) s += std::abs(k.c[b]) * V[nbr[b]];
    S[i] = s;
  }
  double dt = std::numeric_limits<double>::infinity();
#pragma omp parallel for reduction(min : dt) schedule(static)
  for (int i = 0; i < n; ++i) {
    double row = 0;
    for (int b = off[i]; b < off[i + 1]; ++b) {
      const int j = nbr[b];
      // C_ij = 2(b_i ω_ij + b_j ω_ji) + 2α_i⁺ S_i |c_ij| + 2α_j⁺ S_j |c_ji| (notes §4; absolute
      // values keep Cauchy–Schwarz valid for calibrated weights of either sign)
      const double c = 2.0 * (k.b[i] + k.b[j]) * k.omega[b] +
                       2.0 * (alpha_plus[i] * S[i] * std::abs(k.c[b]) +
                              alpha_plus[j] * S[j] * std::abs(k.c[families.reverse[b]]));
      row += c * V[j];
    }
    if (row > 0) dt = std::min(dt, std::sqrt(2.0 * materials.density[i] / row));
  }
  return dt;
}

}  // namespace fissure
