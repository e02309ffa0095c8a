#include "linear/supernodal_cholesky.hpp"

#include <cblas.h>
#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <cstring>
#include <numeric>

#include "core/error.hpp"
#include "linear/banded_ordering.hpp"
#include "linear/blas_threads.hpp"

namespace fissure {

namespace {

// A supernode's rows are split over the threads only from this many entries below its diagonal
// block (128 KB in single precision): below it a parallel region costs more than it saves.
constexpr long kSplitEntries = 1L << 15;

// The dense kernels of one supernode, in the precision of its values.
void lower_solve(CBLAS_TRANSPOSE t, long n, const float* a, long lda, float* x) {
  cblas_strsv(CblasColMajor, CblasLower, t, CblasNonUnit, n, a, lda, x, 1);
}
void lower_solve(CBLAS_TRANSPOSE t, long n, const double* a, long lda, double* x) {
  cblas_dtrsv(CblasColMajor, CblasLower, t, CblasNonUnit, n, a, lda, x, 1);
}
void multiply(CBLAS_TRANSPOSE t, long m, long n, float alpha, const float* a, long lda,
              const float* x, float beta, float* y) {
  cblas_sgemv(CblasColMajor, t, m, n, alpha, a, lda, x, 1, beta, y, 1);
}
void multiply(CBLAS_TRANSPOSE t, long m, long n, double alpha, const double* a, long lda,
              const double* x, double beta, double* y) {
  cblas_dgemv(CblasColMajor, t, m, n, alpha, a, lda, x, 1, beta, y, 1);
}

void check_cholmod(const cholmod_common& common, const char* call) {
  if (common.status < 0)
    throw RunError(fmt::format("CHOLMOD: {} failed (status {})", call, common.status));
}

// Assigns each subtree (by its work) to the least loaded of `threads` bins, largest first;
// returns the largest bin's work.
double assign(const std::vector<long>& roots, const std::vector<double>& work, int threads,
              std::vector<int>& bin) {
  std::vector<long> order(roots.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](long a, long b) { return work[roots[a]] > work[roots[b]]; });
  std::vector<double> load(threads, 0.0);
  bin.assign(roots.size(), 0);
  for (long k : order) {
    const int t = static_cast<int>(std::min_element(load.begin(), load.end()) - load.begin());
    bin[k] = t;
    load[t] += work[roots[k]];
  }
  return *std::max_element(load.begin(), load.end());
}

}  // namespace

SupernodalCholesky::SupernodalCholesky(FactorPrecision precision) : precision_(precision) {
  if (!cholmod_start(&common_)) throw RunError("CHOLMOD: cholmod_start failed");
  common_.supernodal = CHOLMOD_SUPERNODAL;
  common_.print = 0;  // failures are reported by the exceptions below
}

SupernodalCholesky::~SupernodalCholesky() {
  cholmod_free_factor(&symbolic_, &common_);
  cholmod_finish(&common_);
}

bool SupernodalCholesky::factorize(const SparseSymmetric& A) {
  // A view of A (no copy): the rows of a symmetric matrix are its columns, the upper part read.
  cholmod_sparse view{};
  view.nrow = view.ncol = static_cast<std::size_t>(A.rows);
  view.nzmax = A.values.size();
  view.p = const_cast<int*>(A.offsets.data());
  view.i = const_cast<int*>(A.columns.data());
  view.x = const_cast<double*>(A.values.data());
  view.stype = 1;
  view.itype = CHOLMOD_INT;
  view.xtype = CHOLMOD_REAL;
  view.dtype = CHOLMOD_DOUBLE;
  view.sorted = view.packed = true;
  if (!symbolic_) {
    // CHOLMOD's default strategy with a banded candidate (banded_ordering.hpp): it tries that
    // ordering and AMD, and METIS where AMD's fill is high, and keeps the one with the least work.
    std::vector<int> candidate = reverse_cuthill_mckee(A);
    symbolic_ = cholmod_analyze_p(&view, candidate.data(), nullptr, 0, &common_);
    check_cholmod(common_, "cholmod_analyze");
    if (!symbolic_) throw RunError("CHOLMOD: cholmod_analyze failed");
    if (!symbolic_->is_super)
      throw RunError("CHOLMOD: cholmod_analyze did not return a supernodal analysis");
    // The structure and the work split follow from the pattern: kept until it is analysed again.
    keep_structure(*symbolic_);
    schedule(omp_get_max_threads());
  }
  // The numeric factor lives only until its values are copied: the double factor is not kept.
  cholmod_factor* factor = cholmod_copy_factor(symbolic_, &common_);
  if (!factor) throw RunError("CHOLMOD: cholmod_copy_factor failed");
  // BLAS threads help the factorization's dense blocks, not the solves (blas_threads.hpp).
  set_blas_threads(omp_get_max_threads());
  const int ok = cholmod_factorize(&view, factor, &common_);
  set_blas_threads(1);
  const int status = common_.status;
  const bool definite = ok && status != CHOLMOD_NOT_POSDEF && factor->minor >= factor->n;
  const bool supernodal = factor->is_super && factor->is_ll && factor->xtype == CHOLMOD_REAL &&
                          factor->xsize == entries_;
  if (definite && supernodal) keep_values(*factor);
  cholmod_free_factor(&factor, &common_);
  if (status < 0) {
    cholmod_free_factor(&symbolic_, &common_);
    throw RunError(fmt::format("CHOLMOD: cholmod_factorize failed (status {})", status));
  }
  if (!definite) {
    cholmod_free_factor(&symbolic_, &common_);  // analysed afresh next time
    factored_ = false;
    return false;
  }
  if (!supernodal)
    throw RunError("CHOLMOD: cholmod_factorize did not return the analysed supernodal factor");
  factored_ = true;
  return true;
}

void SupernodalCholesky::keep_structure(const cholmod_factor& factor) {
  const auto* super = static_cast<const int*>(factor.super);
  const auto* pi = static_cast<const int*>(factor.pi);
  const auto* px = static_cast<const int*>(factor.px);
  const auto* s = static_cast<const int*>(factor.s);
  const auto* perm = static_cast<const int*>(factor.Perm);
  const long supernodes = static_cast<long>(factor.nsuper);
  super_.assign(super, super + supernodes + 1);
  row_start_.assign(pi, pi + supernodes + 1);
  value_start_.assign(px, px + supernodes + 1);
  rows_.assign(s, s + row_start_.back());
  permutation_.assign(perm, perm + factor.n);
  entries_ = factor.xsize;
  widest_ = 0;
  for (long k = 0; k < supernodes; ++k)
    widest_ = std::max(widest_, row_start_[k + 1] - row_start_[k]);
}

void SupernodalCholesky::keep_values(const cholmod_factor& factor) {
  const auto* x = static_cast<const double*>(factor.x);
  if (precision_ == FactorPrecision::single) {
    single_.assign(x, x + entries_);
  } else {
    full_.assign(x, x + entries_);
  }
}

void SupernodalCholesky::schedule(int threads) {
  const long supernodes = static_cast<long>(super_.size()) - 1;
  std::vector<long> owner(super_.back());  // supernode of each column
  for (long k = 0; k < supernodes; ++k)
    std::fill(owner.begin() + super_[k], owner.begin() + super_[k + 1], k);
  // The supernodal elimination tree: a supernode's parent owns its first row below the
  // diagonal block. CHOLMOD post-orders it, so a subtree is a contiguous range ending at its root.
  std::vector<long> parent(supernodes, -1), first(supernodes);
  std::vector<double> work(supernodes);
  std::vector<std::vector<long>> children(supernodes);
  bool postordered = true;
  for (long k = 0; k < supernodes; ++k) {
    const long columns = super_[k + 1] - super_[k];
    const long rows = row_start_[k + 1] - row_start_[k];
    work[k] += static_cast<double>(rows) * static_cast<double>(columns);
    if (rows > columns) parent[k] = owner[rows_[row_start_[k] + columns]];
  }
  std::iota(first.begin(), first.end(), 0);
  for (long k = 0; k < supernodes; ++k) {
    const long p = parent[k];
    if (p < 0) continue;
    if (p <= k) postordered = false;
    if (!postordered) break;
    work[p] += work[k];
    first[p] = std::min(first[p], first[k]);
    children[p].push_back(k);
  }
  subtree_first_.clear(), subtree_last_.clear(), top_.clear(), subtree_thread_.clear();
  threads_ = 1;
  if (supernodes == 0) return;
  if (!postordered) {
    // Supernodes in increasing order solve correctly whatever the tree: one thread.
    subtree_first_ = {0}, subtree_last_ = {supernodes - 1}, subtree_thread_ = {0};
    return;
  }
  // Split the forest: descend from the roots into the heaviest subtree while that shortens the
  // estimated solve (the supernodes left above the subtrees are taken one at a time, counted
  // here as if by one thread).
  std::vector<long> roots;
  for (long k = 0; k < supernodes; ++k)
    if (parent[k] < 0) roots.push_back(k);
  threads_ = std::max(1, threads);
  std::vector<long> best_roots = roots, top, best_top;
  std::vector<int> bin, best_bin;
  double top_work = 0;
  double best = assign(roots, work, threads_, best_bin);
  double total = 0;
  for (long r : roots) total += work[r];
  for (int expansion = 0; expansion < 64 && threads_ > 1; ++expansion) {
    const auto heaviest = std::max_element(roots.begin(), roots.end(),
                                           [&](long a, long b) { return work[a] < work[b]; });
    const long k = *heaviest;
    if (children[k].empty()) break;
    roots.erase(heaviest);
    roots.insert(roots.end(), children[k].begin(), children[k].end());
    top.push_back(k);
    double own = work[k];
    for (long c : children[k]) own -= work[c];
    top_work += own;
    const double estimate = top_work + assign(roots, work, threads_, bin);
    if (estimate < best) best = estimate, best_roots = roots, best_bin = bin, best_top = top;
  }
  if (threads_ > 1 && best > 0.75 * total) {
    // Close to a chain: too little to run side by side, so every supernode is solved from the
    // top, its rows split over the threads.
    top_.resize(supernodes);
    std::iota(top_.begin(), top_.end(), 0);
    return;
  }
  for (std::size_t r = 0; r < best_roots.size(); ++r) {
    subtree_first_.push_back(first[best_roots[r]]);
    subtree_last_.push_back(best_roots[r]);
    subtree_thread_.push_back(best_bin[r]);
  }
  top_ = best_top;
  std::sort(top_.begin(), top_.end());
}

double SupernodalCholesky::solve_bytes() const {
  const double value = precision_ == FactorPrecision::single ? sizeof(float) : sizeof(double);
  return 2 * value * static_cast<double>(entries_);
}

void SupernodalCholesky::solve(const double* b, double* x) const {
  if (!factored_) throw RunError("SupernodalCholesky: solve before a successful factorization");
  if (precision_ == FactorPrecision::single) {
    solve_with(single_, b, x);
  } else {
    solve_with(full_, b, x);
  }
}

template <typename Real>
void SupernodalCholesky::solve_with(const std::vector<Real>& values, const double* b,
                                    double* x) const {
  const long n = static_cast<long>(permutation_.size());
  std::vector<Real> y(n);
  for (long k = 0; k < n; ++k) y[k] = static_cast<Real>(b[permutation_[k]]);  // P b
  const long widest = widest_;

  // L z = P b, supernode by supernode: the diagonal block's triangle, then the rows below it.
  // Updates of rows outside the running subtree (the supernodes above it) go to the thread's
  // own accumulator, summed before those supernodes are solved.
  auto forward = [&](long k, Real* tmp, Real* outside, long end) {
    const long c0 = super_[k], columns = super_[k + 1] - c0;
    const long r0 = row_start_[k], rows = row_start_[k + 1] - r0;
    const Real* block = values.data() + value_start_[k];
    lower_solve(CblasNoTrans, columns, block, rows, y.data() + c0);
    if (rows == columns) return;
    multiply(CblasNoTrans, rows - columns, columns, Real(1), block + columns, rows, y.data() + c0,
             Real(0), tmp);
    for (long j = 0; j < rows - columns; ++j) {
      const long r = rows_[r0 + columns + j];
      (r < end ? y[r] : outside[r]) -= tmp[j];
    }
  };
  // Lᵀ w = z, in reverse: the rows below the diagonal block (all solved), then its triangle.
  auto backward = [&](long k, Real* tmp) {
    const long c0 = super_[k], columns = super_[k + 1] - c0;
    const long r0 = row_start_[k], rows = row_start_[k + 1] - r0;
    const Real* block = values.data() + value_start_[k];
    if (rows > columns) {
      for (long j = 0; j < rows - columns; ++j) tmp[j] = y[rows_[r0 + columns + j]];
      multiply(CblasTrans, rows - columns, columns, Real(-1), block + columns, rows, tmp, Real(1),
               y.data() + c0);
    }
    lower_solve(CblasTrans, columns, block, rows, y.data() + c0);
  };

  const bool both = !top_.empty() && !subtree_first_.empty();
  std::vector<std::vector<Real>> outside(threads_, std::vector<Real>(both ? n : 0));
  std::vector<Real> tmp(widest);
#pragma omp parallel num_threads(threads_) if (threads_ > 1 && !subtree_first_.empty())
  {
    const int t = omp_get_thread_num();
    std::vector<Real> own(widest);
    for (std::size_t s = 0; s < subtree_first_.size(); ++s) {
      if (subtree_thread_[s] != t) continue;
      const long end = super_[subtree_last_[s] + 1];
      for (long k = subtree_first_[s]; k <= subtree_last_[s]; ++k)
        forward(k, own.data(), outside[t].data(), end);
    }
  }
  if (both)
    for (long k : top_)
      for (long c = super_[k]; c < super_[k + 1]; ++c)
        for (int t = 0; t < threads_; ++t) y[c] += outside[t][c];
  // Above the subtrees the supernodes are taken one at a time, the rows of each rectangular
  // block split over the threads (memory-bound: each thread streams its own rows). One parallel
  // region for all of them, a barrier between supernodes: a chain (a banded factor) has
  // thousands of small supernodes, where a region per supernode cost more than its rows.
  std::vector<Real> partial(static_cast<std::size_t>(threads_) * widest);
#pragma omp parallel num_threads(threads_) if (threads_ > 1 && !top_.empty())
  {
    const int t = omp_get_thread_num(), team = omp_get_num_threads();
    for (long k : top_) {
      const long c0 = super_[k], columns = super_[k + 1] - c0;
      const long r0 = row_start_[k], below = row_start_[k + 1] - r0 - columns;
      const long lda = below + columns;
      const Real* block = values.data() + value_start_[k];
      const int split = below * columns >= kSplitEntries ? team : 1;
      if (t == 0) lower_solve(CblasNoTrans, columns, block, lda, y.data() + c0);
      if (team > 1) {
#pragma omp barrier
      }
      if (t < split) {
        const long a = below * t / split, b = below * (t + 1) / split;
        if (a < b)
          multiply(CblasNoTrans, b - a, columns, Real(1), block + columns + a, lda, y.data() + c0,
                   Real(0), tmp.data() + a);
        for (long j = a; j < b; ++j) y[rows_[r0 + columns + j]] -= tmp[j];
      }
      if (team > 1) {
#pragma omp barrier
      }
    }
    for (auto it = top_.rbegin(); it != top_.rend(); ++it) {
      const long k = *it;
      const long c0 = super_[k], columns = super_[k + 1] - c0;
      const long r0 = row_start_[k], below = row_start_[k + 1] - r0 - columns;
      const long lda = below + columns;
      const Real* block = values.data() + value_start_[k];
      const int split = below * columns >= kSplitEntries ? team : 1;
      if (t < split) {
        const long a = below * t / split, b = below * (t + 1) / split;
        Real* sum = partial.data() + static_cast<std::size_t>(t) * widest;
        std::fill(sum, sum + columns, Real(0));
        for (long j = a; j < b; ++j) tmp[j] = y[rows_[r0 + columns + j]];
        if (a < b)
          multiply(CblasTrans, b - a, columns, Real(1), block + columns + a, lda, tmp.data() + a,
                   Real(0), sum);
      }
      if (team > 1) {
#pragma omp barrier
      }
      if (t == 0) {
        for (int u = 0; u < split; ++u)
          for (long c = 0; c < columns; ++c)
            y[c0 + c] -= partial[static_cast<std::size_t>(u) * widest + c];
        lower_solve(CblasTrans, columns, block, lda, y.data() + c0);
      }
      if (team > 1) {
#pragma omp barrier
      }
    }
  }
#pragma omp parallel num_threads(threads_) if (threads_ > 1 && !subtree_first_.empty())
  {
    const int t = omp_get_thread_num();
    std::vector<Real> own(widest);
    for (std::size_t s = 0; s < subtree_first_.size(); ++s) {
      if (subtree_thread_[s] != t) continue;
      for (long k = subtree_last_[s]; k >= subtree_first_[s]; --k) backward(k, own.data());
    }
  }
  for (long k = 0; k < n; ++k) x[permutation_[k]] = static_cast<double>(y[k]);  // x = Pᵀ w
}

}  // namespace fissure
