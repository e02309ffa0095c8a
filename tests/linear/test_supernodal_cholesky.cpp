// SupernodalCholesky, the factor petsc_newton's preconditioners keep: in double it solves as
// CHOLMOD's own solve does, to round-off, for every way the solve is split over threads (one
// chain, independent subtrees, subtrees below shared supernodes); in single and half precision
// its backward error is that of their rounding; a matrix that is not positive definite
// is reported, and the next factorization analyses afresh.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <random>

#include "core/error.hpp"
#include "linear/cholmod_factor.hpp"
#include "linear/factor_kernels.hpp"
#include "linear/shifted_system.hpp"
#include "linear/supernodal_cholesky.hpp"
#include "model/model.hpp"
#include "model/stiffness.hpp"
#include "support/scenes.hpp"
#include "support/stage_matrix.hpp"

namespace fissure {
namespace {

using Precision = FactorPrecision;

// The 5-point Laplacian of an n × n grid plus `shift` I, in `copies` disconnected copies: a
// bushy elimination tree (and a forest for several copies).
SparseSymmetric grid_laplacian(int n, double shift, int copies) {
  SparseSymmetric a;
  a.rows = copies * n * n;
  a.offsets.push_back(0);
  for (int c = 0; c < copies; ++c)
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const int base = c * n * n;
        auto add = [&](int r, double v) { a.columns.push_back(base + r), a.values.push_back(v); };
        if (i > 0) add((i - 1) * n + j, -1);
        if (j > 0) add(i * n + j - 1, -1);
        add(i * n + j, 4 + shift);
        if (j + 1 < n) add(i * n + j + 1, -1);
        if (i + 1 < n) add((i + 1) * n + j, -1);
        a.offsets.push_back(static_cast<int>(a.columns.size()));
      }
  return a;
}

std::vector<double> random_vector(int n) {
  std::mt19937 random(11);
  std::normal_distribution<double> normal;
  std::vector<double> b(n);
  for (double& v : b) v = normal(random);
  return b;
}

double norm(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x * x;
  return std::sqrt(s);
}

double relative_difference(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> d(a.size());
  for (std::size_t k = 0; k < a.size(); ++k) d[k] = a[k] - b[k];
  return norm(d) / norm(b);
}

// |b − A x| / (|A|_F |x|): the normwise backward error of a solve.
double backward_error(const SparseSymmetric& a, const std::vector<double>& x,
                      const std::vector<double>& b) {
  std::vector<double> r(b.size());
  a.multiply(x.data(), r.data());
  for (std::size_t k = 0; k < r.size(); ++k) r[k] = b[k] - r[k];
  double frobenius = 0;
  for (double v : a.values) frobenius += v * v;
  return norm(r) / (std::sqrt(frobenius) * norm(x));
}

struct Threads {
  explicit Threads(int n) : before(omp_get_max_threads()) { omp_set_num_threads(n); }
  ~Threads() { omp_set_num_threads(before); }
  int before;
};

struct Case {
  const char* name;
  SparseSymmetric matrix;
};

std::vector<Case> cases() {
  return {{"slender bar (a chain)", test::stage_matrix({.size = {0.6, 0.1, 0.1},
                                                        .resolution = 0.05,
                                                        .bulk = 3.3e10,
                                                        .shear = 2.0e10,
                                                        .density = 2200})},
          {"grid (subtrees below shared supernodes)", grid_laplacian(60, 1e-3, 1)},
          {"two grids (a forest)", grid_laplacian(40, 1e-3, 2)}};
}

// Double precision: the same factor CHOLMOD makes, solved in another order, so the solutions
// agree to round-off times the conditioning: κ ≈ 1 + (ω_max h/4)² ≈ 2e4 for the stage matrix
// (h = 300 × 2/ω_max), about 1e3 for the grids, so κ × 2⁻⁵³ ≤ 3e-12 and the bound 1e-11 leaves
// a few times that for the summation order (measured 1e-14 to 4e-14). A solve that skipped the
// subtrees' contributions to the shared supernodes, or used the wrong permutation, would miss by
// order 1 (measured 0.26 to 0.49 with the accumulators not summed).
TEST(SupernodalCholesky, DoubleSolvesAsCholmodDoesOnEveryWorkSplit) {
  bool split_seen = false, chain_seen = false, forest_seen = false;
  for (const Case& c : cases()) {
    const std::vector<double> b = random_vector(c.matrix.rows);
    std::vector<double> reference(b.size()), x(b.size());
    CholmodFactor cholmod;
    cholmod.factorize(c.matrix);
    cholmod.solve(b.data(), reference.data());
    for (int threads : {1, 2, 3}) {
      Threads scope(threads);
      SupernodalCholesky factor(Precision::full, 0);
      ASSERT_TRUE(factor.factorize(c.matrix)) << c.name;
      factor.solve(b.data(), x.data());
      const double difference = relative_difference(x, reference);
      std::printf(
          "%s, %d threads: %d subtrees, %d supernodes above them, |x − x_cholmod| / |x| = "
          "%.1e\n",
          c.name, threads, factor.subtrees(), factor.top_supernodes(), difference);
      EXPECT_LT(difference, 1e-11) << c.name << ", " << threads << " threads";
      if (threads > 1) {
        split_seen |= factor.subtrees() > 1 && factor.top_supernodes() > 0;
        chain_seen |= factor.subtrees() == 0 && factor.top_supernodes() > 0;
        forest_seen |= factor.subtrees() > 1 && factor.top_supernodes() == 0;
      }
      // The same array for b and x.
      std::vector<double> in_place = b;
      factor.solve(in_place.data(), in_place.data());
      EXPECT_EQ(in_place, x) << c.name;
    }
  }
  // Each way of splitting the solve was exercised.
  EXPECT_TRUE(split_seen);
  EXPECT_TRUE(chain_seen);
  EXPECT_TRUE(forest_seen);
}

// Single precision: L rounded to float and the solve done in float is backward stable with
// errors of order u = 2⁻²⁴ ≈ 6e-8 per entry (|ΔA| ≲ 2u |L||Lᵀ| plus the solves' rounding);
// against |A|_F, which exceeds the 2-norm, the normwise backward error stays below u (measured
// 0.02–0.03 u). The double factor's is about 1e-17; a single-precision path that lost the
// permutation or a block would be of order 1.
TEST(SupernodalCholesky, SingleSolveIsBackwardStableToSinglePrecision) {
  const double u = std::ldexp(1.0, -24);
  bool split_seen = false;
  for (const Case& c : cases()) {
    const std::vector<double> b = random_vector(c.matrix.rows);
    std::vector<double> x(b.size()), x_double(b.size());
    for (int threads : {1, 2, 3}) {
      Threads scope(threads);
      SupernodalCholesky single(Precision::single, 0), full(Precision::full, 0);
      ASSERT_TRUE(single.factorize(c.matrix));
      ASSERT_TRUE(full.factorize(c.matrix));
      single.solve(b.data(), x.data());
      full.solve(b.data(), x_double.data());
      const double error = backward_error(c.matrix, x, b);
      const double error_double = backward_error(c.matrix, x_double, b);
      std::printf("%s, %d threads: backward error single %.2e (%.2f u), double %.2e\n", c.name,
                  threads, error, error / u, error_double);
      EXPECT_LT(error, u) << c.name;
      EXPECT_LT(error_double, 1e-15) << c.name;
      // It holds half the bytes of the double factor.
      EXPECT_EQ(2 * single.solve_bytes(), full.solve_bytes());
      if (threads > 1) split_seen |= single.split_triangles() > 0;
    }
  }
  // The diagonal blocks' inverses were solved split over the threads somewhere.
  EXPECT_TRUE(split_seen);
}

// Half precision: the rows below the diagonal blocks rounded to binary16 after scaling each
// column by its largest entry (relative rounding uₕ = 2⁻¹¹ ≈ 4.9e-4 of that entry), the
// triangles' inverses in single: |ΔL| ≲ uₕ |L| column by column, so the backward error is of
// order uₕ |L||Lᵀ| / |A|_F, below uₕ (measured 0.0007–0.0017 uₕ: most entries are far below
// their column's largest). A factor left in single is near 0.03 u (u = 2⁻²⁴, the test above),
// so the error must also exceed u (measured 5–14 u); one that dropped the column scales or a
// block would be of order 1.
TEST(SupernodalCholesky, HalfSolveIsBackwardStableToHalfPrecision) {
  if (!simd_kernels_available()) GTEST_SKIP() << "this CPU has no hardware half conversion";
  const double u_half = std::ldexp(1.0, -11), u = std::ldexp(1.0, -24);
  bool split_seen = false;
  for (const Case& c : cases()) {
    const std::vector<double> b = random_vector(c.matrix.rows);
    std::vector<double> x(b.size());
    for (int threads : {1, 2, 3}) {
      Threads scope(threads);
      SupernodalCholesky half(Precision::half, 0), single(Precision::single, 0);
      ASSERT_EQ(half.precision(), Precision::half);
      ASSERT_TRUE(half.factorize(c.matrix));
      ASSERT_TRUE(single.factorize(c.matrix));
      half.solve(b.data(), x.data());
      const double error = backward_error(c.matrix, x, b);
      std::printf("%s, %d threads: backward error half %.2e (%.3f u_half)\n", c.name, threads,
                  error, error / u_half);
      EXPECT_LT(error, u_half) << c.name;
      EXPECT_GT(error, u) << c.name;
      // The rows below the triangles read 2 bytes an entry instead of 4.
      EXPECT_LT(half.solve_bytes(), 0.75 * single.solve_bytes()) << c.name;
      if (threads > 1) split_seen |= half.split_triangles() > 0;
    }
  }
  EXPECT_TRUE(split_seen);
}

// A raised factor (half to single, what petsc_newton does where half's rounding spoils its
// solves) is kept in single from its next factorization on: the same bits as a factor made in
// single, a backward error at single's level again, and the work split chosen for single's
// bytes (a threaded size between half's and single's: one thread before, all after). A raise of
// a single factor does nothing.
TEST(SupernodalCholesky, RaisedHalfFactorSolvesAsSingleDoes) {
  if (!simd_kernels_available()) GTEST_SKIP() << "this CPU has no hardware half conversion";
  const Case c = cases().back();
  const std::vector<double> b = random_vector(c.matrix.rows);
  std::vector<double> x(b.size()), y(b.size());
  Threads scope(2);
  SupernodalCholesky probe_half(Precision::half, 0), probe_single(Precision::single, 0);
  ASSERT_TRUE(probe_half.factorize(c.matrix));
  ASSERT_TRUE(probe_single.factorize(c.matrix));
  const double threaded = 0.25 * (probe_half.solve_bytes() + probe_single.solve_bytes());
  SupernodalCholesky raised(Precision::half, threaded), single(Precision::single, threaded);
  ASSERT_TRUE(raised.factorize(c.matrix));
  ASSERT_TRUE(single.factorize(c.matrix));
  EXPECT_EQ(raised.threads(), 1);
  EXPECT_EQ(single.threads(), 2);
  EXPECT_TRUE(raised.raise_precision());
  EXPECT_EQ(raised.precision(), Precision::single);
  EXPECT_EQ(raised.threads(), 2);
  EXPECT_FALSE(raised.raise_precision());
  EXPECT_FALSE(single.raise_precision());
  // the half factor is gone until the next factorization
  EXPECT_THROW(raised.solve(b.data(), x.data()), RunError);
  ASSERT_TRUE(raised.factorize(c.matrix));
  EXPECT_EQ(raised.solve_bytes(), single.solve_bytes());
  raised.solve(b.data(), x.data());
  single.solve(b.data(), y.data());
  EXPECT_EQ(x, y);
  const double error = backward_error(c.matrix, x, b);
  std::printf("%s: backward error after the raise %.2e (%.3f u)\n", c.name, error,
              error / std::ldexp(1.0, -24));
  EXPECT_LT(error, std::ldexp(1.0, -24));
}

// A factor below the threaded size is solved on one thread (in the cache a second one only adds
// barriers: bench_factor_solve, docs/integrators.md); from that size on, on all of them.
TEST(SupernodalCholesky, SmallFactorIsSolvedOnOneThread) {
  const SparseSymmetric a = grid_laplacian(40, 1e-3, 1);
  Threads scope(2);
  SupernodalCholesky small(Precision::half), threaded(Precision::half, 0);
  ASSERT_TRUE(small.factorize(a));
  ASSERT_TRUE(threaded.factorize(a));
  EXPECT_LT(small.solve_bytes() / 2, SupernodalCholesky::kThreadedBytes);
  EXPECT_EQ(small.threads(), 1);
  EXPECT_EQ(threaded.threads(), 2);
  const std::vector<double> b = random_vector(a.rows);
  std::vector<double> x(b.size()), y(b.size());
  small.solve(b.data(), x.data());
  threaded.solve(b.data(), y.data());
  // The same factor, its float sums in another order: within κ u ≈ 8e3 × 6e-8 = 5e-4 (κ of the
  // shifted grid Laplacian about 8 / 1e-3); a thread's share dropped would be of order 1.
  EXPECT_LT(relative_difference(x, y), 5e-4);
}

// A matrix with a negative eigenvalue is reported, not solved; the same pattern with positive
// values factorizes afterwards (the failed analysis is dropped) and solves correctly.
TEST(SupernodalCholesky, ReportsAMatrixThatIsNotPositiveDefinite) {
  SparseSymmetric a = grid_laplacian(20, 1e-2, 1);
  SparseSymmetric indefinite = a;
  for (int r = 0; r < a.rows; ++r) indefinite.values[indefinite.find(r, r)] -= 2;
  SupernodalCholesky factor(Precision::single);
  EXPECT_FALSE(factor.factorize(indefinite));
  const std::vector<double> b = random_vector(a.rows);
  std::vector<double> x(b.size());
  EXPECT_THROW(factor.solve(b.data(), x.data()), RunError);
  ASSERT_TRUE(factor.factorize(a));
  factor.solve(b.data(), x.data());
  EXPECT_LT(backward_error(a, x, b), std::ldexp(1.0, -24));  // as SingleSolveIsBackwardStable…
}

}  // namespace
}  // namespace fissure
