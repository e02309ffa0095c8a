#include "linear/supernodal_cholesky.hpp"

#include <cblas.h>
#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <type_traits>

#include "core/error.hpp"
#include "linear/banded_ordering.hpp"
#include "linear/blas_threads.hpp"
#include "linear/factor_kernels.hpp"

namespace fissure {

namespace {

// A supernode's rows are split over the threads only from this many entries below its diagonal
// block (128 KB in single precision): below it a parallel region costs more than it saves.
constexpr long kSplitEntries = 1L << 15;
// A triangle, on the other hand, is split from this many entries: a thread it is not split
// over waits for it at the next barrier.
constexpr long kSplitTriangleEntries = 1L << 12;

// Whether a triangle's solves split over the threads: in single and half, whose kept inverses
// are products (in double, BLAS solves it whole).
bool triangle_splits(FactorPrecision precision, long columns, int threads) {
  return precision != FactorPrecision::full && threads > 1 &&
         columns * columns / 2 >= kSplitTriangleEntries;
}

// Double: CHOLMOD's layout, each supernode one dense block stored by columns, the triangle of
// its diagonal block on top of the rows below it. Its triangles are solved whole, by BLAS.
struct DoubleBlocks {
  using Real = double;
  const double* values;
  const long *super, *row_start, *value_start;

  // out = L_kk⁻¹ v (only whole: a = 0, b = its columns).
  void triangle_solve(long k, long a, long b, const double* v, double* out) const {
    const long lda = row_start[k + 1] - row_start[k];
    std::copy(v + a, v + b, out);
    cblas_dtrsv(CblasColMajor, CblasLower, CblasNoTrans, CblasNonUnit, b - a,
                values + value_start[k], lda, out, 1);
  }
  // out = L_kkᵀ⁻¹ v (only whole).
  void triangle_solve_transposed(long k, long a, long b, const double* v, double* out) const {
    const long lda = row_start[k + 1] - row_start[k];
    std::copy(v + a, v + b, out);
    cblas_dtrsv(CblasColMajor, CblasLower, CblasTrans, CblasNonUnit, b - a, values + value_start[k],
                lda, out, 1);
  }
  // out[0..b-a) = rows [a, b) of the block below the triangle times x.
  void below(long k, long a, long b, const double* x, double* out) const {
    const long columns = super[k + 1] - super[k], lda = row_start[k + 1] - row_start[k];
    cblas_dgemv(CblasColMajor, CblasNoTrans, b - a, columns, 1.0,
                values + value_start[k] + columns + a, lda, x, 1, 0.0, out, 1);
  }
  // sum[0..columns) = those rows, transposed, times w[0..b-a).
  void below_transposed(long k, long a, long b, const double* w, double* sum) const {
    const long columns = super[k + 1] - super[k], lda = row_start[k + 1] - row_start[k];
    cblas_dgemv(CblasColMajor, CblasTrans, b - a, columns, 1.0,
                values + value_start[k] + columns + a, lda, w, 1, 0.0, sum, 1);
  }
};

// Single and half: the inverses of the triangles apart, in single, any rows of whose products
// can be taken; the rows below in single (`Below` float) or in half with a scale per column.
template <typename Below>
struct SplitBlocks {
  using Real = float;
  const float* inverses;
  const Below* belows;
  const float* scale;
  const long *super, *row_start, *triangle_start, *below_start;

  // out[0..b-a) = rows [a, b) of L_kk⁻¹ v.
  void triangle_solve(long k, long a, long b, const float* v, float* out) const {
    lower_multiply(a, b, inverses + triangle_start[k], super[k + 1] - super[k], v, out);
  }
  // out[0..b-a) = rows [a, b) of L_kkᵀ⁻¹ v.
  void triangle_solve_transposed(long k, long a, long b, const float* v, float* out) const {
    const long columns = super[k + 1] - super[k];
    lower_multiply_transposed(a, b, columns, inverses + triangle_start[k], columns, v, out);
  }
  void below(long k, long a, long b, const float* x, float* out) const {
    const long c0 = super[k], columns = super[k + 1] - c0;
    const long lda = row_start[k + 1] - row_start[k] - columns;
    const Below* block = belows + below_start[k] + a;
    if constexpr (std::is_same_v<Below, float>) {
      cblas_sgemv(CblasColMajor, CblasNoTrans, b - a, columns, 1.0f, block, lda, x, 1, 0.0f, out,
                  1);
    } else {
      half_multiply(b - a, columns, block, lda, scale + c0, x, out);
    }
  }
  void below_transposed(long k, long a, long b, const float* w, float* sum) const {
    const long c0 = super[k], columns = super[k + 1] - c0;
    const long lda = row_start[k + 1] - row_start[k] - columns;
    const Below* block = belows + below_start[k] + a;
    if constexpr (std::is_same_v<Below, float>) {
      cblas_sgemv(CblasColMajor, CblasTrans, b - a, columns, 1.0f, block, lda, w, 1, 0.0f, sum, 1);
    } else {
      half_multiply_transposed(b - a, columns, block, lda, scale + c0, w, sum);
    }
  }
};

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

SupernodalCholesky::SupernodalCholesky(FactorPrecision precision, double threaded_bytes)
    : precision_(precision), threaded_bytes_(threaded_bytes) {
  // Without hardware half conversion the half kernels cannot run: single precision instead.
  if (precision_ == FactorPrecision::half && !simd_kernels_available())
    precision_ = FactorPrecision::single;
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
    schedule();
  }
  // The numeric factor lives only until its values are copied: the double factor is not kept.
  cholmod_factor* factor = cholmod_copy_factor(symbolic_, &common_);
  if (!factor) throw RunError("CHOLMOD: cholmod_copy_factor failed");
  // BLAS threads help the factorization's dense blocks, not the solves (blas_threads.hpp).
  set_blas_threads(omp_get_max_threads());
  const int ok = cholmod_factorize(&view, factor, &common_);
  const int status = common_.status;
  const bool definite = ok && status != CHOLMOD_NOT_POSDEF && factor->minor >= factor->n;
  const bool supernodal = factor->is_super && factor->is_ll && factor->xtype == CHOLMOD_REAL &&
                          factor->xsize == entries_;
  if (definite && supernodal) keep_values(*factor);  // inverts the triangles with BLAS-3 too
  set_blas_threads(1);
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
  triangle_start_.assign(1, 0), below_start_.assign(1, 0);
  for (long k = 0; k < supernodes; ++k) {
    const long columns = super_[k + 1] - super_[k], rows = row_start_[k + 1] - row_start_[k];
    widest_ = std::max(widest_, rows);
    triangle_start_.push_back(triangle_start_.back() + columns * columns);
    below_start_.push_back(below_start_.back() + (rows - columns) * columns);
  }
}

void SupernodalCholesky::keep_values(const cholmod_factor& factor) {
  const auto* x = static_cast<const double*>(factor.x);
  if (precision_ == FactorPrecision::full) {
    full_.assign(x, x + entries_);
  } else {
    keep_split_values(x);
  }
}

void SupernodalCholesky::keep_split_values(const double* x) {
  const long supernodes = static_cast<long>(super_.size()) - 1;
  const bool half = precision_ == FactorPrecision::half;
  inverses_.assign(triangle_start_.back(), 0.0f);
  belows_single_.assign(half ? 0 : below_start_.back(), 0.0f);
  belows_half_.assign(half ? below_start_.back() : 0, 0);
  column_scale_.assign(half ? super_.back() : 0, 0.0f);
  std::vector<double> inverse;
  for (long k = 0; k < supernodes; ++k) {
    const long c0 = super_[k], columns = super_[k + 1] - c0;
    const long rows = row_start_[k + 1] - row_start_[k], below = rows - columns;
    const double* block = x + value_start_[k];
    // L_kk⁻¹ = L_kk⁻¹ I, in double before it is rounded (BLAS's triangular solve).
    inverse.assign(columns * columns, 0.0);
    for (long c = 0; c < columns; ++c) inverse[c * columns + c] = 1.0;
    cblas_dtrsm(CblasColMajor, CblasLeft, CblasLower, CblasNoTrans, CblasNonUnit, columns, columns,
                1.0, block, rows, inverse.data(), columns);
    float* kept = inverses_.data() + triangle_start_[k];
    for (long c = 0; c < columns; ++c)
      for (long r = c; r < columns; ++r)
        kept[c * columns + r] = static_cast<float>(inverse[c * columns + r]);
    for (long c = 0; c < columns; ++c) {
      const double* column = block + c * rows + columns;
      const long start = below_start_[k] + c * below;
      if (!half) {
        std::copy(column, column + below, belows_single_.begin() + start);
        continue;
      }
      // Scaled by the column's largest entry below the triangle: every half is then at most 1.
      double largest = 0;
      for (long r = 0; r < below; ++r) largest = std::max(largest, std::abs(column[r]));
      const double scale = largest > 0 ? largest : 1;
      column_scale_[c0 + c] = static_cast<float>(scale);
      to_half(below, column, scale, belows_half_.data() + start);
    }
  }
}

void SupernodalCholesky::schedule() {
  const int threads = solve_bytes() / 2 < threaded_bytes_ ? 1 : omp_get_max_threads();
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

int SupernodalCholesky::split_triangles() const {
  int count = 0;
  for (long k : top_) count += triangle_splits(precision_, super_[k + 1] - super_[k], threads_);
  return count;
}

bool SupernodalCholesky::raise_precision() {
  if (precision_ != FactorPrecision::half) return false;
  precision_ = FactorPrecision::single;
  factored_ = false;
  belows_half_ = {};
  column_scale_ = {};
  // single reads more bytes per solve: the split over threads is chosen again for them
  if (symbolic_) schedule();
  return true;
}

double SupernodalCholesky::solve_bytes() const {
  if (precision_ == FactorPrecision::full)
    return 2 * sizeof(double) * static_cast<double>(entries_);
  const double below = precision_ == FactorPrecision::half ? sizeof(std::uint16_t) : sizeof(float);
  return 2 * (sizeof(float) * static_cast<double>(triangle_start_.back()) +
              below * static_cast<double>(below_start_.back()));
}

void SupernodalCholesky::solve(const double* b, double* x) const {
  if (!factored_) throw RunError("SupernodalCholesky: solve before a successful factorization");
  const long *super = super_.data(), *row_start = row_start_.data();
  const long *triangle_start = triangle_start_.data(), *below_start = below_start_.data();
  if (precision_ == FactorPrecision::full) {
    solve_with(DoubleBlocks{full_.data(), super, row_start, value_start_.data()}, b, x);
  } else if (precision_ == FactorPrecision::single) {
    solve_with(SplitBlocks<float>{inverses_.data(), belows_single_.data(), nullptr, super,
                                  row_start, triangle_start, below_start},
               b, x);
  } else {
    solve_with(
        SplitBlocks<std::uint16_t>{inverses_.data(), belows_half_.data(), column_scale_.data(),
                                   super, row_start, triangle_start, below_start},
        b, x);
  }
}

template <typename Blocks>
void SupernodalCholesky::solve_with(const Blocks& blocks, const double* b, double* x) const {
  using Real = typename Blocks::Real;
  const long n = static_cast<long>(permutation_.size());
  std::vector<Real> y(n);
  for (long k = 0; k < n; ++k) y[k] = static_cast<Real>(b[permutation_[k]]);  // P b
  const long widest = widest_;

  // L z = P b, supernode by supernode: the diagonal block's triangle, then the rows below it.
  // Updates of rows outside the running subtree (the supernodes above it) go to the thread's
  // own accumulator, summed before those supernodes are solved.
  auto forward = [&](long k, Real* tmp, Real* solved, Real* outside, long end) {
    const long c0 = super_[k], columns = super_[k + 1] - c0;
    const long r0 = row_start_[k], below = row_start_[k + 1] - r0 - columns;
    blocks.triangle_solve(k, 0, columns, y.data() + c0, solved);
    std::copy(solved, solved + columns, y.data() + c0);
    if (below == 0) return;
    blocks.below(k, 0, below, y.data() + c0, tmp);
    for (long j = 0; j < below; ++j) {
      const long r = rows_[r0 + columns + j];
      (r < end ? y[r] : outside[r]) -= tmp[j];
    }
  };
  // Lᵀ w = z, in reverse: the rows below the diagonal block (all solved), then its triangle.
  auto backward = [&](long k, Real* tmp, Real* solved) {
    const long c0 = super_[k], columns = super_[k + 1] - c0;
    const long r0 = row_start_[k], below = row_start_[k + 1] - r0 - columns;
    if (below > 0) {
      for (long j = 0; j < below; ++j) tmp[j] = y[rows_[r0 + columns + j]];
      blocks.below_transposed(k, 0, below, tmp, solved);
      for (long c = 0; c < columns; ++c) y[c0 + c] -= solved[c];
    }
    blocks.triangle_solve_transposed(k, 0, columns, y.data() + c0, solved);
    std::copy(solved, solved + columns, y.data() + c0);
  };

  const bool both = !top_.empty() && !subtree_first_.empty();
  std::vector<std::vector<Real>> outside(threads_, std::vector<Real>(both ? n : 0));
#pragma omp parallel num_threads(threads_) if (threads_ > 1 && !subtree_first_.empty())
  {
    const int t = omp_get_thread_num();
    std::vector<Real> own(widest), solved(widest);
    for (std::size_t s = 0; s < subtree_first_.size(); ++s) {
      if (subtree_thread_[s] != t) continue;
      const long end = super_[subtree_last_[s] + 1];
      for (long k = subtree_first_[s]; k <= subtree_last_[s]; ++k)
        forward(k, own.data(), solved.data(), outside[t].data(), end);
    }
  }
  if (both)
    for (long k : top_)
      for (long c = super_[k]; c < super_[k + 1]; ++c)
        for (int t = 0; t < threads_; ++t) y[c] += outside[t][c];
  // Above the subtrees the supernodes are taken one at a time, the rows of each rectangular
  // block (and, kept as an inverse, of its triangle) split over the threads: memory-bound, each
  // thread streams its own rows. One parallel region for all of them, barriers between the
  // phases: a chain (a banded factor) has thousands of small supernodes, where a region per
  // supernode cost more than its rows.
  std::vector<Real> tmp(widest), solved(widest);
  std::vector<Real> partial(static_cast<std::size_t>(threads_) * widest);
#pragma omp parallel num_threads(threads_) if (threads_ > 1 && !top_.empty())
  {
    const int t = omp_get_thread_num(), team = omp_get_num_threads();
    std::vector<Real> remaining(widest);
    for (long k : top_) {
      const long c0 = super_[k], columns = super_[k + 1] - c0;
      const long r0 = row_start_[k], below = row_start_[k + 1] - r0 - columns;
      const int split = below * columns >= kSplitEntries ? team : 1;
      const int split_triangle = triangle_splits(precision_, columns, team) ? team : 1;
      const long ta = lower_rows_split(columns, t, split_triangle);
      const long tb = lower_rows_split(columns, t + 1, split_triangle);
      if (t < split_triangle) blocks.triangle_solve(k, ta, tb, y.data() + c0, solved.data() + ta);
      if (team > 1) {
#pragma omp barrier
      }
      // The rows below read the solved part from `solved`: y's own part is copied meanwhile.
      if (t < split) {
        const long a = below * t / split, b = below * (t + 1) / split;
        if (a < b) blocks.below(k, a, b, solved.data(), tmp.data() + a);
        for (long j = a; j < b; ++j) y[rows_[r0 + columns + j]] -= tmp[j];
      }
      if (t < split_triangle) std::copy(solved.data() + ta, solved.data() + tb, y.data() + c0 + ta);
      if (team > 1) {
#pragma omp barrier
      }
    }
    for (auto it = top_.rbegin(); it != top_.rend(); ++it) {
      const long k = *it;
      const long c0 = super_[k], columns = super_[k + 1] - c0;
      const long r0 = row_start_[k], below = row_start_[k + 1] - r0 - columns;
      const int split = below * columns >= kSplitEntries ? team : 1;
      const int split_triangle = triangle_splits(precision_, columns, team) ? team : 1;
      if (t < split) {
        const long a = below * t / split, b = below * (t + 1) / split;
        Real* sum = partial.data() + static_cast<std::size_t>(t) * widest;
        std::fill(sum, sum + columns, Real(0));
        for (long j = a; j < b; ++j) tmp[j] = y[rows_[r0 + columns + j]];
        if (a < b) blocks.below_transposed(k, a, b, tmp.data() + a, sum);
      }
      if (team > 1) {
#pragma omp barrier
      }
      // Each thread of the triangle's split takes the whole right-hand side, y's part less
      // the rows' sums, and solves its share of the columns.
      const long ta = lower_columns_split(columns, t, split_triangle);
      const long tb = lower_columns_split(columns, t + 1, split_triangle);
      if (t < split_triangle) {
        for (long c = 0; c < columns; ++c) {
          Real v = y[c0 + c];
          for (int u = 0; u < split; ++u) v -= partial[static_cast<std::size_t>(u) * widest + c];
          remaining[c] = v;
        }
        blocks.triangle_solve_transposed(k, ta, tb, remaining.data(), solved.data() + ta);
      }
      if (split_triangle > 1) {
#pragma omp barrier
      }
      if (t < split_triangle) std::copy(solved.data() + ta, solved.data() + tb, y.data() + c0 + ta);
      if (team > 1) {
#pragma omp barrier
      }
    }
  }
#pragma omp parallel num_threads(threads_) if (threads_ > 1 && !subtree_first_.empty())
  {
    const int t = omp_get_thread_num();
    std::vector<Real> own(widest), solved(widest);
    for (std::size_t s = 0; s < subtree_first_.size(); ++s) {
      if (subtree_thread_[s] != t) continue;
      for (long k = subtree_last_[s]; k >= subtree_first_[s]; --k)
        backward(k, own.data(), solved.data());
    }
  }
  for (long k = 0; k < n; ++k) x[permutation_[k]] = static_cast<double>(y[k]);  // x = Pᵀ w
}

}  // namespace fissure
