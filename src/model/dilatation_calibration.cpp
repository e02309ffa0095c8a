#include "model/dilatation_calibration.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace fissure {

namespace {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

Vector6 strain_projection(const double u[3]) {
  Vector6 phi;
  phi << u[0] * u[0], u[1] * u[1], u[2] * u[2], 2 * u[0] * u[1], 2 * u[0] * u[2], 2 * u[1] * u[2];
  return phi;
}

}  // namespace

std::vector<float> dilatation_weights(const Particles& particles, const Families& families,
                                      const std::vector<float>& omega,
                                      const std::vector<double>& weighted_volume) {
  const auto& x = particles.reference;
  const auto& V = particles.volume;
  std::vector<float> weights(families.directed_bonds());
#pragma omp parallel for schedule(static)
  for (int i = families.first_own_row(); i < families.end_own_row(); ++i) {
    const int begin = families.offsets[i], end = families.offsets[i + 1];
    auto direction = [&](int b, double u[3]) {
      const int j = families.neighbors[b];
      for (int k = 0; k < 3; ++k)
        u[k] = (x[3 * j + k] - x[3 * i + k]) / families.reference_length[b];
    };
    Matrix6 moment = Matrix6::Zero();
    for (int b = begin; b < end; ++b) {
      double u[3];
      direction(b, u);
      const Vector6 phi = strain_projection(u);
      const double xi = families.reference_length[b];
      moment += double(omega[b]) * xi * xi * V[families.neighbors[b]] * phi * phi.transpose();
    }
    Vector6 trace;
    trace << 1, 1, 1, 0, 0, 0;
    const Eigen::SelfAdjointEigenSolver<Matrix6> eigen(moment);
    const bool determined =
        end - begin >= 6 && eigen.eigenvalues()(0) > 1e-6 * eigen.eigenvalues()(5);
    const Vector6 K =
        determined
            ? Vector6(eigen.eigenvectors() * (eigen.eigenvalues().cwiseInverse().asDiagonal() *
                                              (eigen.eigenvectors().transpose() * trace)))
            : Vector6::Zero();
    for (int b = begin; b < end; ++b) {
      const double xi = families.reference_length[b];
      if (!determined) {
        weights[b] = static_cast<float>(
            weighted_volume[i] > 0 ? 3.0 * omega[b] * xi / weighted_volume[i] : 0.0);
        continue;
      }
      double u[3];
      direction(b, u);
      // ξ̂ᵀ K ξ̂ = φ·K with the off-diagonal entries of φ doubled, as K12 appears twice.
      weights[b] = static_cast<float>(omega[b] * xi * strain_projection(u).dot(K));
    }
  }
  return weights;
}

FamilyWeights isotropic_family_weights(const Particles& particles, const Families& families,
                                       const std::vector<double>& horizon_of_body) {
  const auto& off = families.offsets;
  FamilyWeights f;
  f.omega.resize(families.directed_bonds());
  f.weighted_volume.assign(particles.count(), 0.0);
  for (int i = 0; i < particles.count(); ++i) {
    const double delta = horizon_of_body[particles.body[i]];
    for (int b = off[i]; b < off[i + 1]; ++b) {
      const double length = families.reference_length[b];
      f.omega[b] = static_cast<float>(delta / length);  // Eq 5
      f.weighted_volume[i] +=
          double(f.omega[b]) * length * length * particles.volume[families.neighbors[b]];
    }
  }
  f.dilatation = dilatation_weights(particles, families, f.omega, f.weighted_volume);
  return f;
}

}  // namespace fissure
