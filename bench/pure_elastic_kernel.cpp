#include "pure_elastic_kernel.hpp"

#include <cmath>

#include "model/dilatation_calibration.hpp"

namespace fissure::bench {

PureElasticKernel::PureElasticKernel(const Scene& scene) : families_(scene.families) {
  const Particles& p = scene.particles;
  const int n = p.count();
  const auto& off = families_.offsets;
  const auto& nbr = families_.neighbors;
  const auto& xi = families_.reference_length;
  omega_.resize(families_.directed_bonds());
  weighted_volume_.resize(n);
  bulk_modulus_.resize(n);
  volume_ = p.volume;
  terms_.resize(n);
  for (int i = 0; i < n; ++i) {
    const Material& material = scene.config.bodies[p.body[i]].material;
    double m = 0;
    for (int b = off[i]; b < off[i + 1]; ++b) {
      omega_[b] = static_cast<float>(scene.horizon_of_body[p.body[i]] / xi[b]);
      m += double(omega_[b]) * xi[b] * xi[b] * p.volume[nbr[b]];
    }
    weighted_volume_[i] = m;
    bulk_modulus_[i] = material.bulk_modulus;
    terms_[i] = {0.0, m > 0 ? 15.0 * material.shear_modulus / m : 0.0, 0.0, p.volume[i]};
  }
  weight_ = dilatation_weights(p, families_, omega_, weighted_volume_);
  reverse_weight_.resize(weight_.size());
  for (std::size_t b = 0; b < weight_.size(); ++b)
    reverse_weight_[b] = weight_[families_.reverse[b]];
}

// D_i and S_i from θ_i and Σ_j ω e |ξ| V_j (LpsModel::set_terms, elastic).
void PureElasticKernel::set_terms(int i, double theta, double moment) {
  const double B = terms_[i].deviatoric;
  terms_[i].pressure =
      bulk_modulus_[i] * theta - B / 3.0 * (moment - theta * weighted_volume_[i] / 3.0);
  terms_[i].shift = B * theta / 3.0;
}

void PureElasticKernel::forces(const double* y, double* f) {
  const int n = static_cast<int>(terms_.size());
  auto row = [&](int i) {
    return lps::BondRow{families_.offsets[i],
                        families_.offsets[i + 1],
                        families_.neighbors.data(),
                        families_.reference_length.data(),
                        omega_.data(),
                        omega_.data(),
                        weight_.data(),
                        reverse_weight_.data()};
  };
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    const lps::DilatationSums sums =
        kernels_.dilatation(row(i), i, y, volume_.data(), nullptr, nullptr);
    set_terms(i, sums.theta, sums.moment);
  }
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    const lps::BondRow r = row(i);
    double force[3];
    kernels_.force({&r, i, y, terms_.data(), 0.0}, force, nullptr);
    for (int k = 0; k < 3; ++k) f[3 * i + k] = terms_[i].volume * force[k];
  }
}

void PureElasticKernel::sequential_forces(const double* y, double* f) {
  const int n = static_cast<int>(terms_.size());
  const int* off = families_.offsets.data();
  const int* nbr = families_.neighbors.data();
  const double* xi = families_.reference_length.data();
  const float* omega = omega_.data();
  const float* c = weight_.data();
  const float* c_reverse = reverse_weight_.data();
  NeighbourTerms* terms = terms_.data();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    const double yi0 = y[3 * i], yi1 = y[3 * i + 1], yi2 = y[3 * i + 2];
    double theta = 0, moment = 0;
    for (int b = off[i]; b < off[i + 1]; ++b) {
      const int j = nbr[b];
      const double* yj = y + 3 * j;
      const double d0 = yj[0] - yi0, d1 = yj[1] - yi1, d2 = yj[2] - yi2;
      const double extension = (std::sqrt(d0 * d0 + d1 * d1 + d2 * d2) - xi[b]) * terms[j].volume;
      theta += c[b] * extension;               // Eq 6
      moment += omega[b] * xi[b] * extension;  // Σ ω e |ξ| V_j
    }
    set_terms(i, theta, moment);
  }
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    const double yi0 = y[3 * i], yi1 = y[3 * i + 1], yi2 = y[3 * i + 2];
    const double Di = terms[i].pressure, Bi = terms[i].deviatoric, Si = terms[i].shift;
    double f0 = 0, f1 = 0, f2 = 0;
    for (int b = off[i]; b < off[i + 1]; ++b) {
      const int j = nbr[b];
      const double* yj = y + 3 * j;
      const double d0 = yj[0] - yi0, d1 = yj[1] - yi1, d2 = yj[2] - yi2;
      const double length = std::sqrt(d0 * d0 + d1 * d1 + d2 * d2);
      const NeighbourTerms& tj = terms[j];
      const double deviatoric = (length - xi[b]) * (Bi + tj.deviatoric) - xi[b] * (Si + tj.shift);
      const double t = c[b] * Di + c_reverse[b] * tj.pressure + omega[b] * deviatoric;  // Eqs 4, 8
      const double s = length > 0 ? t * tj.volume / length : 0.0;
      f0 += s * d0;
      f1 += s * d1;
      f2 += s * d2;
    }
    const double Vi = terms[i].volume;
    f[3 * i] = Vi * f0;
    f[3 * i + 1] = Vi * f1;
    f[3 * i + 2] = Vi * f2;
  }
}

}  // namespace fissure::bench
