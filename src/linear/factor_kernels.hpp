#pragma once
// The dense kernels of a supernodal factor kept in single or half precision
// (supernodal_cholesky.hpp), all stored by columns:
// - each diagonal block kept as its triangle's inverse, so that the triangular solves are
//   products whose rows (or columns) split over the threads;
// - the rows below it in IEEE half precision (binary16) with one scale per column,
//   A(i, j) = scale[j] h(i, j), converted in hardware (F16C) and accumulated in single, so a
//   back-solve reads 2 bytes per entry instead of 4.
#include <cstdint>

namespace fissure {

// out[i - a] = sum over j <= i of T(i, j) v[j], for the rows i in [a, b) of a lower triangle T.
void lower_multiply(long a, long b, const float* t, long lda, const float* v, float* out);
// out[j - a] = sum over i >= j of T(i, j) v[i], for the columns j in [a, b) of a lower
// triangle T of n rows: the rows [a, b) of Tᵀ v.
void lower_multiply_transposed(long a, long b, long n, const float* t, long lda, const float* v,
                               float* out);
// The first row (or column) of part `part` of `parts` that give each part about the same
// entries of an n-row lower triangle in those products; n for part >= parts.
long lower_rows_split(long n, int part, int parts);
long lower_columns_split(long n, int part, int parts);

// True when this CPU has the F16C, AVX2 and FMA instructions: the half kernels below need them,
// the triangle products above use them where they are.
bool simd_kernels_available();

// h[i] = v[i] / scale, rounded to the nearest half.
void to_half(long n, const double* v, double scale, std::uint16_t* h);

// y[0..m) = A x, A of m rows and n columns stored by columns, lda apart.
void half_multiply(long m, long n, const std::uint16_t* a, long lda, const float* scale,
                   const float* x, float* y);
// y[0..n) = Aᵀ w.
void half_multiply_transposed(long m, long n, const std::uint16_t* a, long lda, const float* scale,
                              const float* w, float* y);

}  // namespace fissure
