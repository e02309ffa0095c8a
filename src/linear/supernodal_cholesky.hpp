#pragma once
// Sparse Cholesky for a reused preconditioner factor: CHOLMOD's supernodal factorization
// P A Pᵀ = L Lᵀ in double, then its values kept in single, half or double precision and solved by
// this class over the OpenMP threads: independent subtrees of the supernodal elimination tree
// side by side, and the rows of each supernode above them split (in single and half its
// diagonal block too, kept as its triangle's inverse). A back-solve reads every entry
// of L twice and is bound by memory bandwidth (docs/integrators.md, "The linear solves"), so single
// precision halves it and half precision (the rows below the diagonal blocks in binary16, the
// triangles in single) nearly halves it again; the Newton or Krylov iteration around the solve
// corrects its rounding, as it corrects a stale factor's. Only the kept copy stays: CHOLMOD's
// double factor is freed.
#include <cholmod.h>

#include <cstdint>
#include <vector>

#include "linear/factor_precision.hpp"
#include "linear/sparse_symmetric.hpp"

namespace fissure {

class SupernodalCholesky {
 public:
  // Half falls back to single on a CPU without hardware half conversion (precision() says). A
  // factor that keeps fewer than `threaded_bytes` is solved on one thread: it sits in the cache,
  // where a second thread adds barriers and no bandwidth (docs/integrators.md).
  static constexpr double kThreadedBytes = 32e6;
  explicit SupernodalCholesky(FactorPrecision precision, double threaded_bytes = kThreadedBytes);
  ~SupernodalCholesky();
  SupernodalCholesky(const SupernodalCholesky&) = delete;
  SupernodalCholesky& operator=(const SupernodalCholesky&) = delete;

  // Numeric factorization of A (its pattern analysed on the first call and kept). False when A
  // is not positive definite (the next call analyses afresh); RunError when CHOLMOD fails.
  bool factorize(const SparseSymmetric& A);
  // x = A⁻¹ b with the kept factor (b and x may be the same array).
  void solve(const double* b, double* x) const;
  // From half to single precision, for the factorizations from the next one on (the kept factor
  // is dropped): where half's rounding, amplified by the matrix's condition, spoils the solves.
  // False when the factor is not in half precision.
  bool raise_precision();

  // Entries of L as stored (supernodes hold their dense blocks), and the bytes one solve reads.
  long factor_entries() const { return static_cast<long>(entries_); }
  // Nonzeros of L in the ordering the analysis chose (without the supernodes' padding).
  double factor_nonzeros() const { return common_.lnz; }
  double solve_bytes() const;
  // The work split chosen when the pattern was analysed (see below).
  int subtrees() const { return static_cast<int>(subtree_first_.size()); }
  int top_supernodes() const { return static_cast<int>(top_.size()); }
  // Of those, the ones whose triangle's solves are split over the threads (single and half).
  int split_triangles() const;
  int threads() const { return threads_; }
  FactorPrecision precision() const { return precision_; }

 private:
  template <typename Blocks>
  void solve_with(const Blocks& blocks, const double* b, double* x) const;
  void keep_structure(const cholmod_factor& factor);
  void keep_values(const cholmod_factor& factor);
  void keep_split_values(const double* x);
  // The work split over the threads: one thread below threaded_bytes_ of solve_bytes() / 2.
  void schedule();

  FactorPrecision precision_;
  double threaded_bytes_;
  cholmod_common common_{};
  cholmod_factor* symbolic_ = nullptr;  // the analysis of A's pattern, kept
  bool factored_ = false;
  std::size_t entries_ = 0;
  // In double: CHOLMOD's layout (each supernode one block, its diagonal block's triangle on top
  // of the rows below it), solved with BLAS's triangular solves. In single and half: each
  // diagonal block kept apart as its triangle's inverse in single, so its solves are products
  // split over the threads (factor_kernels.hpp), and the rows below it in single or in
  // binary16 with a scale per column; each supernode's stored by columns from its start.
  std::vector<double> full_;
  std::vector<float> inverses_, belows_single_, column_scale_;
  std::vector<std::uint16_t> belows_half_;
  std::vector<long> triangle_start_, below_start_;
  // The supernodal structure of L (CHOLMOD's arrays), and the most rows of a supernode.
  std::vector<long> super_, row_start_, value_start_, rows_, permutation_;
  long widest_ = 0;
  // Work split: subtree k is the supernodes [subtree_first_[k], subtree_last_[k]] (postorder
  // keeps a subtree contiguous), solved by thread subtree_thread_[k]; top_ are the supernodes
  // above every subtree, solved one at a time with their rows split over the threads.
  std::vector<long> subtree_first_, subtree_last_, top_;
  std::vector<int> subtree_thread_;
  int threads_ = 1;
};

}  // namespace fissure
