#pragma once
// Sparse Cholesky with CHOLMOD (through Eigen's interface), factorized and solved by CHOLMOD
// itself in double: the reference SupernodalCholesky (supernodal_cholesky.hpp, what the
// integrators use) is checked and timed against (test_supernodal_cholesky.cpp,
// bench_factor_solve). The symbolic analysis once, a numeric factorization whenever the values
// change.
#include <Eigen/CholmodSupport>
#include <Eigen/SparseCore>

#include "linear/sparse_symmetric.hpp"

namespace fissure {

class CholmodFactor {
 public:
  // Numeric factorization of A (symbolic on the first call). Throws RunError when A is not
  // positive definite.
  void factorize(const SparseSymmetric& A);
  // x = A⁻¹ b.
  void solve(const double* b, double* x) const;
  long factorizations() const { return factorizations_; }
  // Nonzeros of L in the ordering CHOLMOD's analysis chose (its default strategy: AMD, and METIS
  // where AMD's fill is high).
  double factor_nonzeros() const { return factor_nonzeros_; }

 private:
  Eigen::SparseMatrix<double> matrix_;  // A's pattern; symmetric, so its rows are its columns
  Eigen::CholmodDecomposition<Eigen::SparseMatrix<double>, Eigen::Lower> factor_;
  bool analyzed_ = false;
  long factorizations_ = 0;
  double factor_nonzeros_ = 0;
};

}  // namespace fissure
