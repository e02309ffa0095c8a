#include "linear/cholmod_factor.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>

#include "core/error.hpp"
#include "linear/blas_threads.hpp"

namespace fissure {

void CholmodFactor::factorize(const SparseSymmetric& A) {
  if (!analyzed_) {
    matrix_ = Eigen::Map<const Eigen::SparseMatrix<double>>(
        A.rows, A.rows, static_cast<Eigen::Index>(A.values.size()), A.offsets.data(),
        A.columns.data(), A.values.data());
    factor_.analyzePattern(matrix_);
    factor_nonzeros_ = factor_.cholmod().lnz;
    analyzed_ = true;
  }
  std::copy(A.values.begin(), A.values.end(), matrix_.valuePtr());
  // BLAS threads help the factorization's dense blocks and slow the solves' small BLAS-2 calls
  // (blas_threads.hpp; ARKODE's ark436l2sa on the bar swing: 16.6 s with them, 6.8 s without).
  set_blas_threads(omp_get_max_threads());
  factor_.factorize(matrix_);
  set_blas_threads(1);
  ++factorizations_;
  if (factor_.info() != Eigen::Success)
    throw RunError(
        fmt::format("CHOLMOD: the {}×{} system matrix is not positive definite", A.rows, A.rows));
}

void CholmodFactor::solve(const double* b, double* x) const {
  const Eigen::Map<const Eigen::VectorXd> rhs(b, matrix_.rows());
  Eigen::Map<Eigen::VectorXd>(x, matrix_.rows()) = factor_.solve(rhs);
}

}  // namespace fissure
