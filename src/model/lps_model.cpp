#include "model/lps_model.hpp"

#include <cmath>

#include "model/stable_time_step.hpp"

namespace fissure {

LpsModel::LpsModel(const Particles& particles, const Families& families, MaterialPoints materials)
    : Model(particles, families, std::move(materials)) {
  const int n = particles.count();
  const auto& off = families.offsets;
  const auto& nbr = families.neighbors;
  const auto& xi = families.reference_length;
  omega_volume_.resize(families.directed_bonds());
  weighted_volume_.resize(n);
  deviatoric_coef_.resize(n);
  dilatation_coef_.resize(n);
  dilatation_term_.resize(n);
  dilatation_.assign(n, 0.0);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    const double delta = materials_.horizon[i];
    double m = 0;
    for (int b = off[i]; b < off[i + 1]; ++b) {
      const double omega = delta / xi[b];  // Eq 5
      omega_volume_[b] = omega * particles.volume[nbr[b]];
      m += omega_volume_[b] * xi[b] * xi[b];  // m_i = Σ ω|ξ|²V_j (notes §6)
    }
    weighted_volume_[i] = m;
    const double kappa = materials_.bulk_modulus[i], mu = materials_.shear_modulus[i];
    deviatoric_coef_[i] = m > 0 ? 15.0 * mu / m : 0.0;
    dilatation_coef_[i] = m > 0 ? (3.0 * kappa - 5.0 * mu) / m : 0.0;
  }
}

// θ_i = 3/m_i Σ_j ω_ij |ξ_ij| e_ij V_j (Eq 6 with Λ dropped and m_i calibrated; notes §6).
void LpsModel::compute_dilatation(const double* y) {
  const int n = particles_.count();
  const int* off = families_.offsets.data();
  const int* nbr = families_.neighbors.data();
  const double* xi = families_.reference_length.data();
  const double* wv = omega_volume_.data();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    const double yi0 = y[3 * i], yi1 = y[3 * i + 1], yi2 = y[3 * i + 2];
    double sum = 0;
    for (int b = off[i]; b < off[i + 1]; ++b) {
      const double* yj = y + 3 * nbr[b];
      const double d0 = yj[0] - yi0, d1 = yj[1] - yi1, d2 = yj[2] - yi2;
      const double extension = std::sqrt(d0 * d0 + d1 * d1 + d2 * d2) - xi[b];  // e_ij
      sum += wv[b] * xi[b] * extension;
    }
    const double m = weighted_volume_[i];
    dilatation_[i] = m > 0 ? 3.0 * sum / m : 0.0;
    dilatation_term_[i] = dilatation_coef_[i] * dilatation_[i];
  }
}

// F_i = V_i Σ_j (t_ij + t_ji) n_ij V_j with t_ij = ½A_ij = ω_ij [|ξ| θ_i (3κ−5μ)/m_i +
// e_ij 15μ/m_i] (Eqs 2–4 and 8 with the deviatoric extension e − θ|ξ|/3; notes §6).
void LpsModel::forces(const double* y, double* f) {
  compute_dilatation(y);
  const int n = particles_.count();
  const int* off = families_.offsets.data();
  const int* nbr = families_.neighbors.data();
  const double* xi = families_.reference_length.data();
  const double* wv = omega_volume_.data();
  const double* A = dilatation_term_.data();
  const double* B = deviatoric_coef_.data();
  const double* V = particles_.volume.data();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    const double yi0 = y[3 * i], yi1 = y[3 * i + 1], yi2 = y[3 * i + 2];
    const double Ai = A[i], Bi = B[i];
    double f0 = 0, f1 = 0, f2 = 0;
    for (int b = off[i]; b < off[i + 1]; ++b) {
      const int j = nbr[b];
      const double* yj = y + 3 * j;
      const double d0 = yj[0] - yi0, d1 = yj[1] - yi1, d2 = yj[2] - yi2;
      const double length = std::sqrt(d0 * d0 + d1 * d1 + d2 * d2);
      const double extension = length - xi[b];
      const double t = wv[b] * (xi[b] * (Ai + A[j]) + extension * (Bi + B[j]));
      // n = d / |d|; a collapsed bond (|d| = 0) has no direction and carries no force.
      const double s = length > 0 ? t / length : 0.0;
      f0 += s * d0;
      f1 += s * d1;
      f2 += s * d2;
    }
    f[3 * i] = V[i] * f0;
    f[3 * i + 1] = V[i] * f1;
    f[3 * i + 2] = V[i] * f2;
  }
}

// W_i = ½κθ_i² + 15μ/(2m_i) Σ_j ω_ij ê_ij² V_j, ê = e − θ_i|ξ|/3 (notes §3, §6).
void LpsModel::energy_density(const double* y, double* w) {
  compute_dilatation(y);
  const int n = particles_.count();
  const auto& off = families_.offsets;
  const auto& nbr = families_.neighbors;
  const auto& xi = families_.reference_length;
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    const double theta = dilatation_[i];
    double sum = 0;
    for (int b = off[i]; b < off[i + 1]; ++b) {
      const double* yi = y + 3 * i;
      const double* yj = y + 3 * nbr[b];
      const double d0 = yj[0] - yi[0], d1 = yj[1] - yi[1], d2 = yj[2] - yi[2];
      const double deviatoric =
          std::sqrt(d0 * d0 + d1 * d1 + d2 * d2) - xi[b] - theta * xi[b] / 3.0;
      sum += omega_volume_[b] * deviatoric * deviatoric;
    }
    w[i] = 0.5 * materials_.bulk_modulus[i] * theta * theta + 0.5 * deviatoric_coef_[i] * sum;
  }
}

double LpsModel::stable_time_step() const {
  const int n = particles_.count();
  std::vector<double> b(n), c_scale(n), omega(families_.directed_bonds()),
      c_shape(families_.directed_bonds());
  for (int i = 0; i < n; ++i) {
    b[i] = 0.5 * deviatoric_coef_[i];  // b_i = 15μ/(2m_i)
    c_scale[i] = weighted_volume_[i] > 0 ? 3.0 / weighted_volume_[i] : 0.0;
    for (int k = families_.offsets[i]; k < families_.offsets[i + 1]; ++k) {
      omega[k] = materials_.horizon[i] / families_.reference_length[k];
      c_shape[k] = omega[k] * families_.reference_length[k];  // c_ij = 3ω|ξ|/m_i
    }
  }
  return gershgorin_time_step(particles_, families_, materials_, {b, omega, c_scale, c_shape});
}

std::size_t LpsModel::bytes_per_bond() const {
  return sizeof(int) + sizeof(double) + sizeof(double);  // neighbour, |ξ|, ω V_j
}

}  // namespace fissure
