#include "model/lps_model.hpp"

#include <algorithm>
#include <cmath>

#include "model/dilatation_calibration.hpp"
#include "model/stable_time_step.hpp"

namespace fissure {

LpsModel::LpsModel(const Particles& particles, const Families& families, MaterialPoints materials,
                   bool surface_correction)
    : Model(particles, families, std::move(materials)) {
  const int n = particles.count();
  const auto& off = families.offsets;
  const auto& nbr = families.neighbors;
  const auto& xi = families.reference_length;
  const std::size_t bonds = families.directed_bonds();
  std::vector<double> omega(bonds);
  bond_omega_.resize(bonds);
  weighted_volume_.resize(n);
  deviatoric_coef_.resize(n);
  pressure_term_.resize(n);
  shift_term_.resize(n);
  dilatation_.assign(n, 0.0);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    double m = 0;
    for (int b = off[i]; b < off[i + 1]; ++b) {
      bond_omega_[b] = static_cast<float>(materials_.horizon[i] / xi[b]);  // Eq 5
      omega[b] = bond_omega_[b];
      m += omega[b] * xi[b] * xi[b] * particles.volume[nbr[b]];  // m_i = Σ ω|ξ|²V_j (notes §6)
    }
    weighted_volume_[i] = m;
    deviatoric_coef_[i] = m > 0 ? 15.0 * materials_.shear_modulus[i] / m : 0.0;
  }
  std::vector<double> c(bonds);
  if (surface_correction) {
    c = dilatation_weights(particles, families, omega, weighted_volume_);
  } else {
    for (int i = 0; i < n; ++i)
      for (int b = off[i]; b < off[i + 1]; ++b)
        c[b] = weighted_volume_[i] > 0 ? 3.0 * omega[b] * xi[b] / weighted_volume_[i] : 0.0;
  }
  bond_weight_.resize(bonds);
  bond_reverse_weight_.resize(bonds);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i)
    for (int b = off[i]; b < off[i + 1]; ++b) {
      bond_weight_[b] = static_cast<float>(c[b]);
      bond_reverse_weight_[b] = static_cast<float>(c[families.reverse[b]]);
    }
}

// θ_i = Σ_j c_ij e_ij V_j (Eq 6 with Λ dropped and calibrated weights; c = 3ω|ξ|/m_i uncorrected),
// and the per-particle terms of the force: D_i = κθ_i − (B_i/3) Σ_j ω ê_ij |ξ| V_j, B_i θ_i/3.
void LpsModel::compute_dilatation(const double* y) {
  const int n = particles_.count();
  const int* off = families_.offsets.data();
  const int* nbr = families_.neighbors.data();
  const double* xi = families_.reference_length.data();
  const float* omega = bond_omega_.data();
  const float* c = bond_weight_.data();
  const double* V = particles_.volume.data();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    const double yi0 = y[3 * i], yi1 = y[3 * i + 1], yi2 = y[3 * i + 2];
    double theta = 0, moment = 0;
    for (int b = off[i]; b < off[i + 1]; ++b) {
      const int j = nbr[b];
      const double* yj = y + 3 * j;
      const double d0 = yj[0] - yi0, d1 = yj[1] - yi1, d2 = yj[2] - yi2;
      const double extension = (std::sqrt(d0 * d0 + d1 * d1 + d2 * d2) - xi[b]) * V[j];  // e_ij V_j
      theta += c[b] * extension;
      moment += omega[b] * xi[b] * extension;
    }
    const double B = deviatoric_coef_[i];
    // Σ_j ω ê |ξ| V_j = Σ_j ω e |ξ| V_j − θ m/3 (zero without the calibration)
    const double deviatoric_moment = moment - theta * weighted_volume_[i] / 3.0;
    dilatation_[i] = theta;
    pressure_term_[i] = materials_.bulk_modulus[i] * theta - B / 3.0 * deviatoric_moment;
    shift_term_[i] = B * theta / 3.0;
  }
}

// F_i = −∂Π/∂y_i = V_i Σ_j (t_ij + t_ji) n_ij V_j (Eqs 2–3), with the bond force density
// t_ij = ½A_ij = c_ij D_i + ω_ij (B_i e_ij − B_i θ_i |ξ|/3) (Eqs 4 and 8, corrected: notes §6).
void LpsModel::forces(const double* y, double* f) {
  compute_dilatation(y);
  const int n = particles_.count();
  const int* off = families_.offsets.data();
  const int* nbr = families_.neighbors.data();
  const double* xi = families_.reference_length.data();
  const float* omega = bond_omega_.data();
  const float* c = bond_weight_.data();
  const float* c_reverse = bond_reverse_weight_.data();
  const double* D = pressure_term_.data();
  const double* B = deviatoric_coef_.data();
  const double* S = shift_term_.data();
  const double* V = particles_.volume.data();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    const double yi0 = y[3 * i], yi1 = y[3 * i + 1], yi2 = y[3 * i + 2];
    const double Di = D[i], Bi = B[i], Si = S[i];
    double f0 = 0, f1 = 0, f2 = 0;
    for (int b = off[i]; b < off[i + 1]; ++b) {
      const int j = nbr[b];
      const double* yj = y + 3 * j;
      const double d0 = yj[0] - yi0, d1 = yj[1] - yi1, d2 = yj[2] - yi2;
      const double length = std::sqrt(d0 * d0 + d1 * d1 + d2 * d2);
      const double extension = length - xi[b];
      const double t = c[b] * Di + c_reverse[b] * D[j] +
                       omega[b] * (extension * (Bi + B[j]) - xi[b] * (Si + S[j]));
      // n = d / |d|; a collapsed bond (|d| = 0) has no direction and carries no force.
      const double s = length > 0 ? t * V[j] / length : 0.0;
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
    const double* yi = y + 3 * i;
    double sum = 0;
    for (int b = off[i]; b < off[i + 1]; ++b) {
      const double* yj = y + 3 * nbr[b];
      const double d0 = yj[0] - yi[0], d1 = yj[1] - yi[1], d2 = yj[2] - yi[2];
      const double deviatoric =
          std::sqrt(d0 * d0 + d1 * d1 + d2 * d2) - xi[b] - theta * xi[b] / 3.0;
      sum += bond_omega_[b] * particles_.volume[nbr[b]] * deviatoric * deviatoric;
    }
    w[i] = 0.5 * materials_.bulk_modulus[i] * theta * theta + 0.5 * deviatoric_coef_[i] * sum;
  }
}

double LpsModel::stable_time_step() const {
  const int n = particles_.count();
  const std::size_t bonds = families_.directed_bonds();
  std::vector<double> b(n), unit(n, 1.0), omega(bonds), c(bonds);
  for (int i = 0; i < n; ++i) b[i] = 0.5 * deviatoric_coef_[i];  // b_i = 15μ/(2m_i)
  for (std::size_t k = 0; k < bonds; ++k) {
    omega[k] = bond_omega_[k];
    c[k] = std::abs(bond_weight_[k]);  // |c_ij| keeps the Cauchy–Schwarz bound valid
  }
  return gershgorin_time_step(particles_, families_, materials_, {b, omega, unit, c});
}

void LpsModel::break_bond(std::size_t b) {
  bond_omega_[b] = 0;
  bond_weight_[b] = 0;
  bond_reverse_weight_[b] = 0;
}

std::size_t LpsModel::bytes_per_bond() const {
  // neighbour, |ξ|, reverse index; ω, c_ij, c_ji
  return 2 * sizeof(int) + sizeof(double) + 3 * sizeof(float);
}

std::size_t LpsModel::bytes_read_per_bond() const {
  // dilatation pass: neighbour, |ξ|, ω, c_ij; force pass: the same and c_ji
  return 2 * (sizeof(int) + sizeof(double) + 2 * sizeof(float)) + sizeof(float);
}

}  // namespace fissure
