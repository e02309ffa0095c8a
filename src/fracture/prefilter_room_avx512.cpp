// prefilter_room.hpp with AVX-512: eight bonds per iteration, the neighbours' positions gathered,
// the bond arrays prefetched ahead as the LPS row passes do (lps_rows_avx512.cpp).
#include "fracture/prefilter_room.hpp"

#if defined(__AVX512F__) && defined(__AVX512VL__) && defined(__AVX512DQ__)
#include <immintrin.h>

#include <limits>

namespace fissure {

namespace {

double room_avx512(int begin, int end, const int* neighbor, const float* bound, const double* y,
                   int i) {
  const __m512d x0 = _mm512_set1_pd(y[3 * i]), x1 = _mm512_set1_pd(y[3 * i + 1]),
                x2 = _mm512_set1_pd(y[3 * i + 2]), zero = _mm512_setzero_pd();
  __m512d room = _mm512_set1_pd(std::numeric_limits<double>::infinity());
  for (int b = begin; b < end; b += 8) {
    _mm_prefetch(reinterpret_cast<const char*>(neighbor + b + 256), _MM_HINT_T0);
    _mm_prefetch(reinterpret_cast<const char*>(bound + b + 256), _MM_HINT_T0);
    const int left = end - b;
    const __mmask8 m = left >= 8 ? __mmask8(0xff) : __mmask8((1u << left) - 1);
    const __m256i j = _mm256_maskz_loadu_epi32(m, neighbor + b);
    const __m256i j3 = _mm256_add_epi32(j, _mm256_slli_epi32(j, 1));
    const __m512d d0 = _mm512_sub_pd(_mm512_mask_i32gather_pd(zero, m, j3, y, 8), x0);
    const __m512d d1 = _mm512_sub_pd(_mm512_mask_i32gather_pd(zero, m, j3, y + 1, 8), x1);
    const __m512d d2 = _mm512_sub_pd(_mm512_mask_i32gather_pd(zero, m, j3, y + 2, 8), x2);
    const __m512d length = _mm512_sqrt_pd(_mm512_add_pd(
        _mm512_add_pd(_mm512_mul_pd(d0, d0), _mm512_mul_pd(d1, d1)), _mm512_mul_pd(d2, d2)));
    const __m512d left_room =
        _mm512_sub_pd(_mm512_cvtps_pd(_mm256_maskz_loadu_ps(m, bound + b)), length);
    room = _mm512_mask_min_pd(room, m, left_room, room);
  }
  return _mm512_reduce_min_pd(room);
}

}  // namespace

PrefilterRoom prefilter_room_avx512() {
  if (!__builtin_cpu_supports("avx512f") || !__builtin_cpu_supports("avx512vl") ||
      !__builtin_cpu_supports("avx512dq"))
    return nullptr;
  return room_avx512;
}

}  // namespace fissure

#else

namespace fissure {

PrefilterRoom prefilter_room_avx512() { return nullptr; }

}  // namespace fissure

#endif
