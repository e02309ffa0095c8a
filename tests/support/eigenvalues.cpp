#include "support/eigenvalues.hpp"

#include <Eigen/Eigenvalues>
#include <stdexcept>

namespace fissure::test {

Eigen::VectorXd symmetric_eigenvalues(const Eigen::MatrixXd& A) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(A, Eigen::EigenvaluesOnly);
  if (solver.info() != Eigen::Success)
    throw std::runtime_error("symmetric_eigenvalues: the QR iteration did not converge");
  return solver.eigenvalues();
}

}  // namespace fissure::test
