#include "linear/factor_kernels.hpp"

#include <cpuid.h>
#include <immintrin.h>

#include <algorithm>
#include <cmath>

// The kernels that use AVX2, FMA and F16C are compiled for them alone and called only where the
// CPU has them (simd_kernels_available).
#define FISSURE_SIMD_TARGET __attribute__((target("avx2,fma,f16c")))

namespace fissure {

namespace {

FISSURE_SIMD_TARGET inline __m256 load8(const std::uint16_t* h) {
  return _mm256_cvtph_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(h)));
}

FISSURE_SIMD_TARGET inline float load1(const std::uint16_t* h) { return _cvtsh_ss(*h); }

FISSURE_SIMD_TARGET inline float sum8(__m256 v) {
  __m128 s = _mm_add_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
  s = _mm_add_ps(s, _mm_movehl_ps(s, s));
  s = _mm_add_ss(s, _mm_movehdup_ps(s));
  return _mm_cvtss_f32(s);
}

// Without AVX2: plain loops the compiler vectorizes as it can.
void lower_multiply_plain(long a, long b, const float* t, long lda, const float* v, float* out) {
  std::fill(out, out + (b - a), 0.0f);
  for (long j = 0; j < b; ++j) {
    const float* column = t + j * lda;
    const float vj = v[j];
#pragma omp simd
    for (long i = std::max(a, j); i < b; ++i) out[i - a] += column[i] * vj;
  }
}

void lower_multiply_transposed_plain(long a, long b, long n, const float* t, long lda,
                                     const float* v, float* out) {
  for (long j = a; j < b; ++j) {
    const float* column = t + j * lda;
    float sum = 0;
#pragma omp simd reduction(+ : sum)
    for (long i = j; i < n; ++i) sum += column[i] * v[i];
    out[j - a] = sum;
  }
}

// With AVX2, four columns at a time as in the half kernels below; the rows where the four
// columns' triangle starts (i < j + 3) are taken one by one.
FISSURE_SIMD_TARGET void lower_multiply_avx2(long a, long b, const float* t, long lda,
                                             const float* v, float* out) {
  std::fill(out, out + (b - a), 0.0f);
  long j = 0;
  for (; j + 4 <= b; j += 4) {
    const float *c0 = t + j * lda, *c1 = c0 + lda, *c2 = c1 + lda, *c3 = c2 + lda;
    const float v0 = v[j], v1 = v[j + 1], v2 = v[j + 2], v3 = v[j + 3];
    const long full = std::max(a, j + 3);
    for (long i = std::max(a, j); i < full; ++i)
      out[i - a] +=
          c0[i] * v0 + (i >= j + 1 ? c1[i] * v1 : 0.0f) + (i >= j + 2 ? c2[i] * v2 : 0.0f);
    const __m256 w0 = _mm256_set1_ps(v0), w1 = _mm256_set1_ps(v1);
    const __m256 w2 = _mm256_set1_ps(v2), w3 = _mm256_set1_ps(v3);
    long i = full;
    for (; i + 8 <= b; i += 8) {
      __m256 acc = _mm256_loadu_ps(out + i - a);
      acc = _mm256_fmadd_ps(_mm256_loadu_ps(c0 + i), w0, acc);
      acc = _mm256_fmadd_ps(_mm256_loadu_ps(c1 + i), w1, acc);
      acc = _mm256_fmadd_ps(_mm256_loadu_ps(c2 + i), w2, acc);
      acc = _mm256_fmadd_ps(_mm256_loadu_ps(c3 + i), w3, acc);
      _mm256_storeu_ps(out + i - a, acc);
    }
    for (; i < b; ++i) out[i - a] += c0[i] * v0 + c1[i] * v1 + c2[i] * v2 + c3[i] * v3;
  }
  for (; j < b; ++j) {
    const float* column = t + j * lda;
    for (long i = std::max(a, j); i < b; ++i) out[i - a] += column[i] * v[j];
  }
}

FISSURE_SIMD_TARGET void lower_multiply_transposed_avx2(long a, long b, long n, const float* t,
                                                        long lda, const float* v, float* out) {
  long j = a;
  for (; j + 4 <= b; j += 4) {
    const float *c0 = t + j * lda, *c1 = c0 + lda, *c2 = c1 + lda, *c3 = c2 + lda;
    // Rows j .. j + 2 hold fewer than four columns' entries.
    float t0 = c0[j] * v[j] + c0[j + 1] * v[j + 1] + c0[j + 2] * v[j + 2];
    float t1 = c1[j + 1] * v[j + 1] + c1[j + 2] * v[j + 2];
    float t2 = c2[j + 2] * v[j + 2];
    float t3 = 0;
    __m256 s0 = _mm256_setzero_ps(), s1 = s0, s2 = s0, s3 = s0;
    long i = j + 3;
    for (; i + 8 <= n; i += 8) {
      const __m256 w = _mm256_loadu_ps(v + i);
      s0 = _mm256_fmadd_ps(_mm256_loadu_ps(c0 + i), w, s0);
      s1 = _mm256_fmadd_ps(_mm256_loadu_ps(c1 + i), w, s1);
      s2 = _mm256_fmadd_ps(_mm256_loadu_ps(c2 + i), w, s2);
      s3 = _mm256_fmadd_ps(_mm256_loadu_ps(c3 + i), w, s3);
    }
    for (; i < n; ++i)
      t0 += c0[i] * v[i], t1 += c1[i] * v[i], t2 += c2[i] * v[i], t3 += c3[i] * v[i];
    out[j - a] = t0 + sum8(s0), out[j + 1 - a] = t1 + sum8(s1);
    out[j + 2 - a] = t2 + sum8(s2), out[j + 3 - a] = t3 + sum8(s3);
  }
  for (; j < b; ++j) {
    const float* column = t + j * lda;
    float sum = 0;
    for (long i = j; i < n; ++i) sum += column[i] * v[i];
    out[j - a] = sum;
  }
}

}  // namespace

bool simd_kernels_available() {
  // Called from a static initializer too (below), possibly before the compiler's own detection.
  __builtin_cpu_init();
  // F16C from CPUID leaf 1 (not every compiler's __builtin_cpu_supports knows it).
  unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
  const bool f16c = __get_cpuid(1, &eax, &ebx, &ecx, &edx) && (ecx & bit_F16C);
  return f16c && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
}

namespace {

const bool kSimd = simd_kernels_available();

}  // namespace

void lower_multiply(long a, long b, const float* t, long lda, const float* v, float* out) {
  if (kSimd) {
    lower_multiply_avx2(a, b, t, lda, v, out);
  } else {
    lower_multiply_plain(a, b, t, lda, v, out);
  }
}

void lower_multiply_transposed(long a, long b, long n, const float* t, long lda, const float* v,
                               float* out) {
  if (kSimd) {
    lower_multiply_transposed_avx2(a, b, n, t, lda, v, out);
  } else {
    lower_multiply_transposed_plain(a, b, n, t, lda, v, out);
  }
}

// Row i holds i + 1 entries: the rows before n sqrt(part / parts) hold that share of them.
long lower_rows_split(long n, int part, int parts) {
  if (part >= parts) return n;
  return static_cast<long>(std::lround(n * std::sqrt(static_cast<double>(part) / parts)));
}

// Column j holds n - j entries: the mirror of the rows' split.
long lower_columns_split(long n, int part, int parts) {
  if (part >= parts) return n;
  return n - lower_rows_split(n, parts - part, parts);
}

FISSURE_SIMD_TARGET void to_half(long n, const double* v, double scale, std::uint16_t* h) {
  for (long i = 0; i < n; ++i)
    h[i] = _cvtss_sh(static_cast<float>(v[i] / scale), _MM_FROUND_TO_NEAREST_INT);
}

// Four columns at a time: each pass over y streams four columns of A.
FISSURE_SIMD_TARGET void half_multiply(long m, long n, const std::uint16_t* a, long lda,
                                       const float* scale, const float* x, float* y) {
  const long m8 = m - m % 8;
  for (long i = 0; i < m; ++i) y[i] = 0;
  long j = 0;
  for (; j + 4 <= n; j += 4) {
    const std::uint16_t *c0 = a + j * lda, *c1 = c0 + lda, *c2 = c1 + lda, *c3 = c2 + lda;
    const float x0 = scale[j] * x[j], x1 = scale[j + 1] * x[j + 1];
    const float x2 = scale[j + 2] * x[j + 2], x3 = scale[j + 3] * x[j + 3];
    const __m256 v0 = _mm256_set1_ps(x0), v1 = _mm256_set1_ps(x1);
    const __m256 v2 = _mm256_set1_ps(x2), v3 = _mm256_set1_ps(x3);
    for (long i = 0; i < m8; i += 8) {
      __m256 acc = _mm256_loadu_ps(y + i);
      acc = _mm256_fmadd_ps(load8(c0 + i), v0, acc);
      acc = _mm256_fmadd_ps(load8(c1 + i), v1, acc);
      acc = _mm256_fmadd_ps(load8(c2 + i), v2, acc);
      acc = _mm256_fmadd_ps(load8(c3 + i), v3, acc);
      _mm256_storeu_ps(y + i, acc);
    }
    for (long i = m8; i < m; ++i)
      y[i] += load1(c0 + i) * x0 + load1(c1 + i) * x1 + load1(c2 + i) * x2 + load1(c3 + i) * x3;
  }
  for (; j < n; ++j) {
    const std::uint16_t* c = a + j * lda;
    const float xj = scale[j] * x[j];
    const __m256 v = _mm256_set1_ps(xj);
    for (long i = 0; i < m8; i += 8)
      _mm256_storeu_ps(y + i, _mm256_fmadd_ps(load8(c + i), v, _mm256_loadu_ps(y + i)));
    for (long i = m8; i < m; ++i) y[i] += load1(c + i) * xj;
  }
}

// Four columns at a time: each load of w serves four dot products.
FISSURE_SIMD_TARGET void half_multiply_transposed(long m, long n, const std::uint16_t* a, long lda,
                                                  const float* scale, const float* w, float* y) {
  const long m8 = m - m % 8;
  long j = 0;
  for (; j + 4 <= n; j += 4) {
    const std::uint16_t *c0 = a + j * lda, *c1 = c0 + lda, *c2 = c1 + lda, *c3 = c2 + lda;
    __m256 s0 = _mm256_setzero_ps(), s1 = s0, s2 = s0, s3 = s0;
    for (long i = 0; i < m8; i += 8) {
      const __m256 v = _mm256_loadu_ps(w + i);
      s0 = _mm256_fmadd_ps(load8(c0 + i), v, s0);
      s1 = _mm256_fmadd_ps(load8(c1 + i), v, s1);
      s2 = _mm256_fmadd_ps(load8(c2 + i), v, s2);
      s3 = _mm256_fmadd_ps(load8(c3 + i), v, s3);
    }
    float t0 = sum8(s0), t1 = sum8(s1), t2 = sum8(s2), t3 = sum8(s3);
    for (long i = m8; i < m; ++i) {
      t0 += load1(c0 + i) * w[i], t1 += load1(c1 + i) * w[i];
      t2 += load1(c2 + i) * w[i], t3 += load1(c3 + i) * w[i];
    }
    y[j] = scale[j] * t0, y[j + 1] = scale[j + 1] * t1;
    y[j + 2] = scale[j + 2] * t2, y[j + 3] = scale[j + 3] * t3;
  }
  for (; j < n; ++j) {
    const std::uint16_t* c = a + j * lda;
    __m256 s = _mm256_setzero_ps();
    for (long i = 0; i < m8; i += 8) s = _mm256_fmadd_ps(load8(c + i), _mm256_loadu_ps(w + i), s);
    float t = sum8(s);
    for (long i = m8; i < m; ++i) t += load1(c + i) * w[i];
    y[j] = scale[j] * t;
  }
}

}  // namespace fissure
