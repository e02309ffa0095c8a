// The row passes of lps_rows.hpp with AVX-512 intrinsics: eight bonds per iteration, their
// neighbours' positions and terms gathered, the bond arrays prefetched well ahead (the passes
// stream them from memory: without the prefetch one thread waits on them, bench/README.md).
// Per bond the same operations as lps_rows_portable.cpp, so both give the same bits.
#include "model/lps_rows.hpp"

#if defined(__AVX512F__) && defined(__AVX512VL__) && defined(__AVX512DQ__)
#include <immintrin.h>

namespace fissure::lps {

namespace {

// How many bonds ahead the bond arrays are prefetched: measured on the bench block, 64 gave
// 3.9 ns per directed bond, 256 and 512 3.4 (bench_elastic_step, one thread).
constexpr int prefetch_distance = 256;

template <class T>
void prefetch(const T* p) {
  _mm_prefetch(reinterpret_cast<const char*>(p), _MM_HINT_T0);
}

// (l + l+4), then (l + l+2), then (0 + 1): the portable reduce().
double reduce(__m512d sum) {
  const __m256d half = _mm256_add_pd(_mm512_castpd512_pd256(sum), _mm512_extractf64x4_pd(sum, 1));
  const __m128d quarter = _mm_add_pd(_mm256_castpd256_pd128(half), _mm256_extractf128_pd(half, 1));
  return _mm_cvtsd_f64(_mm_add_sd(quarter, _mm_unpackhi_pd(quarter, quarter)));
}

__mmask8 lanes_left(int b, int end) {
  const int left = end - b;
  return left >= 8 ? __mmask8(0xff) : __mmask8((1u << left) - 1);
}

__m512d widen(__mmask8 m, const float* p) { return _mm512_cvtps_pd(_mm256_maskz_loadu_ps(m, p)); }

// Row i's 8 bond vectors d = y_j − y_i from the neighbours' indices j.
struct Bonds {
  __m512d d0, d1, d2;
};

Bonds bond_vectors(__mmask8 m, __m256i j, const double* y, const double* yi) {
  const __m256i j3 = _mm256_add_epi32(j, _mm256_slli_epi32(j, 1));
  const __m512d zero = _mm512_setzero_pd();
  return {_mm512_sub_pd(_mm512_mask_i32gather_pd(zero, m, j3, y, 8), _mm512_set1_pd(yi[0])),
          _mm512_sub_pd(_mm512_mask_i32gather_pd(zero, m, j3, y + 1, 8), _mm512_set1_pd(yi[1])),
          _mm512_sub_pd(_mm512_mask_i32gather_pd(zero, m, j3, y + 2, 8), _mm512_set1_pd(yi[2]))};
}

__m512d squared_length(const Bonds& d) {
  return _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(d.d0, d.d0), _mm512_mul_pd(d.d1, d.d1)),
                       _mm512_mul_pd(d.d2, d.d2));
}

template <bool Plastic, bool Extension>
DilatationSums dilatation_row_sums(const BondRow& row, int i, const double* y, const double* V,
                                   const double* ep, double* extension) {
  __m512d theta = _mm512_setzero_pd(), moment = theta;
  const __m512d zero = _mm512_setzero_pd();
  for (int b = row.begin; b < row.end; b += 8) {
    prefetch(row.reference_length + b + prefetch_distance);
    prefetch(row.neighbor + b + prefetch_distance);
    prefetch(row.weight + b + prefetch_distance);
    prefetch(row.deviatoric + b + prefetch_distance);
    const __mmask8 m = lanes_left(b, row.end);
    const __m256i j = _mm256_maskz_loadu_epi32(m, row.neighbor + b);
    const __m512d xi = _mm512_maskz_loadu_pd(m, row.reference_length + b);
    const __m512d e =
        _mm512_sub_pd(_mm512_sqrt_pd(squared_length(bond_vectors(m, j, y, y + 3 * i))), xi);
    if constexpr (Extension) _mm512_mask_storeu_pd(extension + (b - row.begin), m, e);
    const __m512d Vj = _mm512_mask_i32gather_pd(zero, m, j, V, 8);
    const __m512d eV = _mm512_mul_pd(e, Vj);
    theta = _mm512_mask_add_pd(theta, m, theta, _mm512_mul_pd(widen(m, row.weight + b), eV));
    const __m512d w_xi = _mm512_mul_pd(widen(m, row.deviatoric + b), xi);
    __m512d strain = eV;
    if constexpr (Plastic)
      strain = _mm512_sub_pd(eV, _mm512_mul_pd(_mm512_maskz_loadu_pd(m, ep + b), Vj));
    moment = _mm512_mask_add_pd(moment, m, moment, _mm512_mul_pd(w_xi, strain));
  }
  return {reduce(theta), reduce(moment)};
}

DilatationSums dilatation_row(const BondRow& row, int i, const double* y, const double* V,
                              const double* ep, double* extension) {
  if (ep)
    return extension ? dilatation_row_sums<true, true>(row, i, y, V, ep, extension)
                     : dilatation_row_sums<true, false>(row, i, y, V, ep, nullptr);
  return extension ? dilatation_row_sums<false, true>(row, i, y, V, nullptr, extension)
                   : dilatation_row_sums<false, false>(row, i, y, V, nullptr, nullptr);
}

double moment_row(const BondRow& row, const double* extension, const double* V, const double* ep) {
  __m512d moment = _mm512_setzero_pd();
  const __m512d zero = _mm512_setzero_pd();
  for (int b = row.begin; b < row.end; b += 8) {
    const __mmask8 m = lanes_left(b, row.end);
    const __m256i j = _mm256_maskz_loadu_epi32(m, row.neighbor + b);
    const __m512d Vj = _mm512_mask_i32gather_pd(zero, m, j, V, 8);
    const __m512d xi = _mm512_maskz_loadu_pd(m, row.reference_length + b);
    const __m512d eV = _mm512_mul_pd(_mm512_maskz_loadu_pd(m, extension + (b - row.begin)), Vj);
    const __m512d w_xi = _mm512_mul_pd(widen(m, row.deviatoric + b), xi);
    const __m512d strain =
        ep ? _mm512_sub_pd(eV, _mm512_mul_pd(_mm512_maskz_loadu_pd(m, ep + b), Vj)) : eV;
    moment = _mm512_mask_add_pd(moment, m, moment, _mm512_mul_pd(w_xi, strain));
  }
  return reduce(moment);
}

// Separate: as lps_rows_portable.cpp's.
template <bool Energy, bool Separate>
void force_row_sums(const ForceRowInput& in, double force[3], double* squares) {
  const BondRow& row = *in.row;
  const double* terms = &in.terms[0].pressure;  // 4 doubles per particle
  const NeighbourTerms& ti = in.terms[in.i];
  const __m512d Di = _mm512_set1_pd(ti.pressure), Bi = _mm512_set1_pd(ti.deviatoric),
                Si = _mm512_set1_pd(ti.shift), elastic_theta = _mm512_set1_pd(in.elastic_theta),
                three = _mm512_set1_pd(3.0), zero = _mm512_setzero_pd();
  __m512d f0 = zero, f1 = zero, f2 = zero, w = zero;
  for (int b = row.begin; b < row.end; b += 8) {
    prefetch(row.reference_length + b + prefetch_distance);
    prefetch(row.neighbor + b + prefetch_distance);
    prefetch(row.weight + b + prefetch_distance);
    prefetch(row.reverse_weight + b + prefetch_distance);
    prefetch(row.deviatoric + b + prefetch_distance);
    if constexpr (Separate) prefetch(row.reverse_deviatoric + b + prefetch_distance);
    const __mmask8 m = lanes_left(b, row.end);
    const __m256i j = _mm256_maskz_loadu_epi32(m, row.neighbor + b);
    const Bonds d = bond_vectors(m, j, in.y, in.y + 3 * in.i);
    const __m512d length = _mm512_sqrt_pd(squared_length(d));
    const __m512d xi = _mm512_maskz_loadu_pd(m, row.reference_length + b);
    const __m512d e = _mm512_sub_pd(length, xi);
    const __m256i j4 = _mm256_slli_epi32(j, 2);
    const __m512d Dj = _mm512_mask_i32gather_pd(zero, m, j4, terms, 8);
    const __m512d Bj = _mm512_mask_i32gather_pd(zero, m, j4, terms + 1, 8);
    const __m512d Sj = _mm512_mask_i32gather_pd(zero, m, j4, terms + 2, 8);
    const __m512d Vj = _mm512_mask_i32gather_pd(zero, m, j4, terms + 3, 8);
    const __m512d w_ij = widen(m, row.deviatoric + b);
    __m512d deviatoric;
    if constexpr (Separate)
      deviatoric = _mm512_add_pd(
          _mm512_mul_pd(w_ij, _mm512_sub_pd(_mm512_mul_pd(e, Bi), _mm512_mul_pd(xi, Si))),
          _mm512_mul_pd(widen(m, row.reverse_deviatoric + b),
                        _mm512_sub_pd(_mm512_mul_pd(e, Bj), _mm512_mul_pd(xi, Sj))));
    else
      deviatoric = _mm512_mul_pd(w_ij, _mm512_sub_pd(_mm512_mul_pd(e, _mm512_add_pd(Bi, Bj)),
                                                     _mm512_mul_pd(xi, _mm512_add_pd(Si, Sj))));
    const __m512d t =
        _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(widen(m, row.weight + b), Di),
                                    _mm512_mul_pd(widen(m, row.reverse_weight + b), Dj)),
                      deviatoric);
    // a collapsed bond (ℓ = 0) carries no force
    const __mmask8 stretched = _mm512_mask_cmp_pd_mask(m, length, zero, _CMP_GT_OQ);
    const __m512d s = _mm512_maskz_div_pd(stretched, _mm512_mul_pd(t, Vj), length);
    f0 = _mm512_mask_add_pd(f0, m, f0, _mm512_mul_pd(s, d.d0));
    f1 = _mm512_mask_add_pd(f1, m, f1, _mm512_mul_pd(s, d.d1));
    f2 = _mm512_mask_add_pd(f2, m, f2, _mm512_mul_pd(s, d.d2));
    if constexpr (Energy) {
      const __m512d e_hat =
          _mm512_sub_pd(e, _mm512_div_pd(_mm512_mul_pd(elastic_theta, xi), three));
      w = _mm512_mask_add_pd(w, m, w,
                             _mm512_mul_pd(_mm512_mul_pd(_mm512_mul_pd(w_ij, Vj), e_hat), e_hat));
    }
  }
  force[0] = reduce(f0);
  force[1] = reduce(f1);
  force[2] = reduce(f2);
  if constexpr (Energy) *squares = reduce(w);
}

void force_row(const ForceRowInput& in, double force[3], double* squares) {
  const bool separate = in.row->reverse_deviatoric != in.row->deviatoric;
  if (squares)
    separate ? force_row_sums<true, true>(in, force, squares)
             : force_row_sums<true, false>(in, force, squares);
  else
    separate ? force_row_sums<false, true>(in, force, nullptr)
             : force_row_sums<false, false>(in, force, nullptr);
}

bool yields(const BondRow& row, const double* extension, double B, double trial_theta,
            double yield_force) {
  const __m512d deviatoric = _mm512_set1_pd(B), theta = _mm512_set1_pd(trial_theta),
                critical = _mm512_set1_pd(yield_force), two = _mm512_set1_pd(2.0),
                three = _mm512_set1_pd(3.0), zero = _mm512_setzero_pd();
  for (int b = row.begin; b < row.end; b += 8) {
    const __mmask8 m = lanes_left(b, row.end);
    const __m512d xi = _mm512_maskz_loadu_pd(m, row.reference_length + b);
    const __m512d stiffness = _mm512_mul_pd(_mm512_mul_pd(two, widen(m, row.deviatoric + b)),
                                            deviatoric);  // 4ωb, w for ω
    const __m512d e = _mm512_maskz_loadu_pd(m, extension + (b - row.begin));
    const __m512d trial =
        _mm512_mul_pd(stiffness, _mm512_sub_pd(e, _mm512_div_pd(_mm512_mul_pd(theta, xi), three)));
    const __mmask8 stiff = _mm512_mask_cmp_pd_mask(m, stiffness, zero, _CMP_GT_OQ);
    if (_mm512_mask_cmp_pd_mask(stiff, _mm512_abs_pd(trial), critical, _CMP_GT_OQ)) return true;
  }
  return false;
}

// Eight bonds' n = d (1/ℓ), v_j − v_i and s = n·(v_j − v_i); false if one of them is
// collapsed, whose row the portable kernel then takes whole (the same bits: it is rare).
struct BondRates {
  __m512d n0, n1, n2, dv0, dv1, dv2, s;
};

bool bond_rates(__mmask8 m, __m256i j, __m512d xi, const TangentRowInput& in, BondRates& r) {
  const Bonds d = bond_vectors(m, j, in.y, in.y + 3 * in.i);
  const __m512d length = _mm512_sqrt_pd(squared_length(d));
  if (_mm512_mask_cmp_pd_mask(m, length, _mm512_mul_pd(_mm512_set1_pd(kCollapsedBond), xi),
                              _CMP_LE_OQ))
    return false;
  const Bonds dv = bond_vectors(m, j, in.v, in.v + 3 * in.i);
  const __m512d inverse = _mm512_maskz_div_pd(m, _mm512_set1_pd(1.0), length);
  const __m512d n0 = _mm512_mul_pd(d.d0, inverse), n1 = _mm512_mul_pd(d.d1, inverse),
                n2 = _mm512_mul_pd(d.d2, inverse);
  const __m512d s = _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(n0, dv.d0), _mm512_mul_pd(n1, dv.d1)),
                                  _mm512_mul_pd(n2, dv.d2));
  r = {n0, n1, n2, dv.d0, dv.d1, dv.d2, s};
  return true;
}

TangentSums tangent_sums(const TangentRowInput& in) {
  const BondRow& row = *in.row;
  const __m512d zero = _mm512_setzero_pd();
  __m512d P = zero, Q = zero;
  for (int b = row.begin; b < row.end; b += 8) {
    prefetch(row.reference_length + b + prefetch_distance);
    prefetch(row.neighbor + b + prefetch_distance);
    prefetch(row.weight + b + prefetch_distance);
    prefetch(row.deviatoric + b + prefetch_distance);
    const __mmask8 m = lanes_left(b, row.end);
    const __m256i j = _mm256_maskz_loadu_epi32(m, row.neighbor + b);
    const __m512d xi = _mm512_maskz_loadu_pd(m, row.reference_length + b);
    BondRates r;
    if (!bond_rates(m, j, xi, in, r)) return portable_row_kernels().tangent_sums(in);
    const __m512d sV = _mm512_mul_pd(r.s, _mm512_mask_i32gather_pd(zero, m, j, in.volume, 8));
    P = _mm512_mask_add_pd(P, m, P, _mm512_mul_pd(widen(m, row.weight + b), sV));
    Q = _mm512_mask_add_pd(Q, m, Q,
                           _mm512_mul_pd(_mm512_mul_pd(widen(m, row.deviatoric + b), xi), sV));
  }
  return {reduce(P), reduce(Q)};
}

void tangent_row(const TangentRowInput& in, double out[3]) {
  const BondRow& row = *in.row;
  const double* terms = &in.terms[0].x;  // 4 doubles per particle
  const TangentTerms& ti = in.terms[in.i];
  const __m512d Xi = _mm512_set1_pd(ti.x), Yi = _mm512_set1_pd(ti.y),
                three_gamma = _mm512_set1_pd(3.0 * ti.gamma), Vi = _mm512_set1_pd(ti.volume),
                three = _mm512_set1_pd(3.0), zero = _mm512_setzero_pd();
  __m512d o0 = zero, o1 = zero, o2 = zero;
  for (int b = row.begin; b < row.end; b += 8) {
    prefetch(row.reference_length + b + prefetch_distance);
    prefetch(row.neighbor + b + prefetch_distance);
    prefetch(row.weight + b + prefetch_distance);
    prefetch(row.reverse_weight + b + prefetch_distance);
    prefetch(row.deviatoric + b + prefetch_distance);
    prefetch(row.reverse_deviatoric + b + prefetch_distance);
    prefetch(in.geometric + b + prefetch_distance);
    const __mmask8 m = lanes_left(b, row.end);
    const __m256i j = _mm256_maskz_loadu_epi32(m, row.neighbor + b);
    const __m512d xi = _mm512_maskz_loadu_pd(m, row.reference_length + b);
    BondRates r;
    if (!bond_rates(m, j, xi, in, r)) return portable_row_kernels().tangent(in, out);
    const __m256i j4 = _mm256_slli_epi32(j, 2);
    const __m512d Xj = _mm512_mask_i32gather_pd(zero, m, j4, terms, 8);
    const __m512d Yj = _mm512_mask_i32gather_pd(zero, m, j4, terms + 1, 8);
    const __m512d Gj = _mm512_mask_i32gather_pd(zero, m, j4, terms + 2, 8);
    const __m512d Vj = _mm512_mask_i32gather_pd(zero, m, j4, terms + 3, 8);
    const __m512d g = _mm512_maskz_loadu_pd(m, in.geometric + b);
    const __m512d t_own =
        _mm512_mul_pd(Vj, _mm512_add_pd(_mm512_mul_pd(widen(m, row.weight + b), Xi),
                                        _mm512_mul_pd(widen(m, row.deviatoric + b),
                                                      _mm512_sub_pd(_mm512_mul_pd(three_gamma, r.s),
                                                                    _mm512_mul_pd(xi, Yi)))));
    const __m512d t_member = _mm512_mul_pd(
        Vi, _mm512_add_pd(_mm512_mul_pd(widen(m, row.reverse_weight + b), Xj),
                          _mm512_mul_pd(widen(m, row.reverse_deviatoric + b),
                                        _mm512_sub_pd(_mm512_mul_pd(_mm512_mul_pd(three, Gj), r.s),
                                                      _mm512_mul_pd(xi, Yj)))));
    const __m512d along = _mm512_sub_pd(_mm512_sub_pd(_mm512_mul_pd(g, r.s), t_own), t_member);
    o0 = _mm512_mask_add_pd(o0, m, o0,
                            _mm512_sub_pd(_mm512_mul_pd(along, r.n0), _mm512_mul_pd(g, r.dv0)));
    o1 = _mm512_mask_add_pd(o1, m, o1,
                            _mm512_sub_pd(_mm512_mul_pd(along, r.n1), _mm512_mul_pd(g, r.dv1)));
    o2 = _mm512_mask_add_pd(o2, m, o2,
                            _mm512_sub_pd(_mm512_mul_pd(along, r.n2), _mm512_mul_pd(g, r.dv2)));
  }
  out[0] = reduce(o0);
  out[1] = reduce(o1);
  out[2] = reduce(o2);
}

}  // namespace

RowKernels avx512_row_kernels() {
  if (!__builtin_cpu_supports("avx512f") || !__builtin_cpu_supports("avx512vl") ||
      !__builtin_cpu_supports("avx512dq"))
    return {"avx512", nullptr, nullptr, nullptr, nullptr, nullptr, nullptr};
  return {"avx512", dilatation_row, moment_row, force_row, yields, tangent_sums, tangent_row};
}

}  // namespace fissure::lps

#else

namespace fissure::lps {

RowKernels avx512_row_kernels() {
  return {"avx512", nullptr, nullptr, nullptr, nullptr, nullptr, nullptr};
}

}  // namespace fissure::lps

#endif
