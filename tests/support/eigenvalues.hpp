#pragma once
// The eigenvalues of a dense symmetric matrix, compiled once (eigenvalues.cpp) for every test
// program: Eigen's SelfAdjointEigenSolver costs about 9 s of compile time in each file that
// instantiates it.
#include <Eigen/Core>

namespace fissure::test {

// The eigenvalues of symmetric `A` (its lower triangle is read), ascending, without eigenvectors
// (tridiagonal QR). Throws std::runtime_error when the iteration does not converge.
Eigen::VectorXd symmetric_eigenvalues(const Eigen::MatrixXd& A);

}  // namespace fissure::test
