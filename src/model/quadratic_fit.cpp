#include "model/quadratic_fit.hpp"

#include <Eigen/Cholesky>

namespace fissure {

QuadraticBasis quadratic_basis(const Eigen::Vector3d& xi, double scale) {
  const Eigen::Vector3d d = xi / scale;
  QuadraticBasis phi;
  phi << d[0], d[1], d[2], 0.5 * d[0] * d[0], 0.5 * d[1] * d[1], 0.5 * d[2] * d[2], d[0] * d[1],
      d[0] * d[2], d[1] * d[2];
  return phi;
}

bool quadratic_fit(const std::vector<Eigen::Vector3d>& xi, const std::vector<double>& weight,
                   double scale, std::vector<QuadraticBasis>& coefficients) {
  coefficients.clear();
  if (xi.size() < 9) return false;
  Eigen::Matrix<double, 9, 9> moments = Eigen::Matrix<double, 9, 9>::Zero();
  std::vector<QuadraticBasis> weighted(xi.size());
  for (std::size_t j = 0; j < xi.size(); ++j) {
    const QuadraticBasis phi = quadratic_basis(xi[j], scale);
    weighted[j] = weight[j] * phi;
    moments += weighted[j] * phi.transpose();  // Σ_j w_j φ_j φ_jᵀ
  }
  const Eigen::LDLT<Eigen::Matrix<double, 9, 9>> fit(moments);
  if (fit.info() != Eigen::Success || !fit.isPositive() ||
      fit.vectorD().minCoeff() <= 1e-12 * fit.vectorD().maxCoeff())
    return false;
  coefficients.resize(xi.size());
  for (std::size_t j = 0; j < xi.size(); ++j) coefficients[j] = fit.solve(weighted[j]);
  return true;
}

}  // namespace fissure
