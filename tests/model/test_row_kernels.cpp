// The LPS row passes (model/lps_rows.hpp): the portable kernels, and the AVX-512 ones where the
// CPU has them, which must give the portable kernels' bits on every row of a tet block (rows of
// every length mod 8, so every tail mask), the dilatation sums and the matrix-free tangent's sums
// equal the same sums taken in bond order to round-off (a collapsed bond included), and the yield
// test decides as the return map's arithmetic does at each row's threshold. A lane reduced in
// another order, a tail lane lost or counted twice, a neighbour's term gathered from the wrong
// field (the portable kernel reads them by name) or a term computed with other operations fails the
// bitwise checks.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "model/lps_rows.hpp"
#include "support/scenes.hpp"

namespace fissure {
namespace {

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

// Random bond arrays on a real family graph, with a few collapsed and zero-weight bonds, and
// deviatoric weights that differ between the two rows of a pair (w_ij ≠ w_ji, as calibrated).
struct Rows {
  explicit Rows(const Scene& scene) : families(scene.families) {
    std::mt19937 random(17);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const Particles& p = scene.particles;
    const std::size_t bonds = families.directed_bonds();
    y = p.reference;
    for (double& v : y) v += 1e-3 * u(random);
    y[3] = y[3 * families.neighbors[families.offsets[1]]];  // a collapsed bond of row 1
    y[4] = y[3 * families.neighbors[families.offsets[1]] + 1];
    y[5] = y[3 * families.neighbors[families.offsets[1]] + 2];
    // a bond just short enough to count as collapsed (ℓ = ½·1e-12 |ξ| > 0) and one just too long
    // (2e-12 |ξ|), each along x from the row's first member
    for (const auto& [i, fraction] :
         {std::pair{p.count() / 3, 0.5e-12}, {2 * p.count() / 3, 2e-12}}) {
      const int b = families.offsets[i], j = families.neighbors[b];
      for (int k = 0; k < 3; ++k) y[3 * i + k] = y[3 * j + k];
      y[3 * i] += fraction * families.reference_length[b];
    }
    volume = p.volume;
    for (std::size_t b = 0; b < bonds; ++b) {
      omega.push_back(static_cast<float>(b % 11 == 0 ? 0.0 : 1.0 + 0.5 * u(random)));
      reverse_omega.push_back(static_cast<float>(b % 11 == 0 ? 0.0 : 1.0 + 0.5 * u(random)));
      weight.push_back(static_cast<float>(b % 13 == 0 ? 0.0 : u(random)));
      reverse_weight.push_back(static_cast<float>(u(random)));
      plastic.push_back(b % 3 == 0 ? 0.0 : 1e-4 * u(random));
    }
    for (int i = 0; i < p.count(); ++i) {
      terms.push_back({u(random), 1.0 + u(random), u(random), p.volume[i]});
      // V_i in the second pass's terms differs from the first pass's V (volume), so that a pass
      // reading the other's fails
      tangent_terms.push_back(
          {u(random), u(random), 1.0 + u(random), p.volume[i] * (1.5 + u(random))});
    }
    for (std::size_t b = 0; b < bonds; ++b) geometric.push_back(u(random));
    for (std::size_t k = 0; k < y.size(); ++k) v.push_back(u(random));
  }
  lps::BondRow row(int i) const {
    return {families.offsets[i],
            families.offsets[i + 1],
            families.neighbors.data(),
            families.reference_length.data(),
            omega.data(),
            reverse_omega.data(),
            weight.data(),
            reverse_weight.data()};
  }
  const Families& families;
  std::vector<double> y, volume, plastic;
  std::vector<float> omega, reverse_omega, weight, reverse_weight;
  std::vector<lps::NeighbourTerms> terms;
  std::vector<lps::TangentTerms> tangent_terms;
  std::vector<double> geometric, v;  // g_b per bond, a direction per particle
};

// θ_i and the moment summed in bond order, with Σ|term| for the round-off bound.
struct OrderedSums {
  double theta, theta_size, moment, moment_size;
};

OrderedSums bond_order(const Rows& r, int i, const double* ep) {
  OrderedSums s{};
  const lps::BondRow row = r.row(i);
  for (int b = row.begin; b < row.end; ++b) {
    const int j = row.neighbor[b];
    double d2 = 0;
    for (int k = 0; k < 3; ++k) d2 += std::pow(r.y[3 * j + k] - r.y[3 * i + k], 2);
    const double xi = row.reference_length[b];
    const double eV = (std::sqrt(d2) - xi) * r.volume[j];
    s.theta += row.weight[b] * eV;
    s.theta_size += std::abs(row.weight[b] * eV);
    const double m = row.deviatoric[b] * xi * (eV - (ep ? ep[b] * r.volume[j] : 0.0));
    s.moment += m;
    s.moment_size += std::abs(m);
  }
  return s;
}

// The force pass's sum in bond order, t_ij + t_ji = c_ij D_i + c_ji D_j + w_ij (e B_i − |ξ| S_i) +
// w_ji (e B_j − |ξ| S_j) (lps_rows.hpp) times V_j d/ℓ, with Σ|term| per component.
struct OrderedForce {
  double force[3], size[3];
};

OrderedForce bond_order_force(const Rows& r, int i) {
  OrderedForce s{};
  const lps::BondRow row = r.row(i);
  const lps::NeighbourTerms& ti = r.terms[i];
  for (int b = row.begin; b < row.end; ++b) {
    const int j = row.neighbor[b];
    const lps::NeighbourTerms& tj = r.terms[j];
    double d[3], d2 = 0;
    for (int k = 0; k < 3; ++k) {
      d[k] = r.y[3 * j + k] - r.y[3 * i + k];
      d2 += d[k] * d[k];
    }
    const double length = std::sqrt(d2), xi = row.reference_length[b], e = length - xi;
    if (length == 0) continue;
    const double t = row.weight[b] * ti.pressure + row.reverse_weight[b] * tj.pressure +
                     row.deviatoric[b] * (e * ti.deviatoric - xi * ti.shift) +
                     row.reverse_deviatoric[b] * (e * tj.deviatoric - xi * tj.shift);
    for (int k = 0; k < 3; ++k) {
      s.force[k] += t * tj.volume * d[k] / length;
      s.size[k] += std::abs(t * tj.volume * d[k] / length);
    }
  }
  return s;
}

// The tangent passes' sums in bond order (lps_rows.hpp), n_b = d/ℓ or, for a collapsed bond, the
// reference direction, with Σ|term| per sum.
struct OrderedTangent {
  double P, P_size, Q, Q_size, out[3], out_size[3];
};

OrderedTangent bond_order_tangent(const Rows& r, const Scene& scene, int i) {
  OrderedTangent s{};
  const lps::BondRow row = r.row(i);
  const lps::TangentTerms& ti = r.tangent_terms[i];
  const double* x = scene.particles.reference.data();
  for (int b = row.begin; b < row.end; ++b) {
    const int j = row.neighbor[b];
    const lps::TangentTerms& tj = r.tangent_terms[j];
    const double xi = row.reference_length[b];
    double d[3];
    for (int k = 0; k < 3; ++k) d[k] = r.y[3 * j + k] - r.y[3 * i + k];
    double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (length <= 1e-12 * xi) {
      for (int k = 0; k < 3; ++k) d[k] = x[3 * j + k] - x[3 * i + k];
      length = xi;
    }
    double rate = 0;
    for (int k = 0; k < 3; ++k) rate += d[k] / length * (r.v[3 * j + k] - r.v[3 * i + k]);
    const double P = row.weight[b] * rate * r.volume[j];
    const double Q = row.deviatoric[b] * xi * rate * r.volume[j];
    s.P += P;
    s.P_size += std::abs(P);
    s.Q += Q;
    s.Q_size += std::abs(Q);
    const double t_own =
        tj.volume * (row.weight[b] * ti.x + row.deviatoric[b] * (3 * ti.gamma * rate - xi * ti.y));
    const double t_member =
        ti.volume * (row.reverse_weight[b] * tj.x +
                     row.reverse_deviatoric[b] * (3 * tj.gamma * rate - xi * tj.y));
    const double g = r.geometric[b];
    for (int k = 0; k < 3; ++k) {
      const double term =
          (g * rate - t_own - t_member) * d[k] / length + g * (r.v[3 * i + k] - r.v[3 * j + k]);
      s.out[k] += term;
      s.out_size[k] += std::abs(g * rate * d[k] / length) + std::abs(t_own * d[k] / length) +
                       std::abs(t_member * d[k] / length) +
                       std::abs(g * (r.v[3 * i + k] - r.v[3 * j + k]));
    }
  }
  return s;
}

// On a CPU without AVX-512 the bitwise comparisons compare the portable kernels with themselves,
// and the sums in bond order, the yield threshold and the kept extensions check them alone.
TEST(RowKernels, EqualTheBondOrderSumsAndAvx512ThePortableBitsOnEveryRow) {
  const lps::RowKernels portable = lps::portable_row_kernels();
  const lps::RowKernels avx512 = lps::avx512_row_kernels();
  const lps::RowKernels simd = avx512.force ? avx512 : portable;
  std::printf("%s\n", avx512.force ? "AVX-512 kernels against the portable ones, bitwise"
                                   : "no AVX-512 on this CPU or build: portable kernels only");
  const Scene scene = test::block_scene(0.1, 0.02, 1e6, 1e6);
  const Rows r(scene);
  const int n = scene.particles.count();
  for (const int i : {n / 3, 2 * n / 3}) {  // the two short bonds are what they should be
    const int b = scene.families.offsets[i], j = scene.families.neighbors[b];
    const double length = std::abs(r.y[3 * j] - r.y[3 * i]),
                 xi = scene.families.reference_length[b];
    ASSERT_GT(length, 0.0);
    ASSERT_EQ(length <= 1e-12 * xi, i == n / 3) << "row " << i << ": ℓ/|ξ| " << length / xi;
  }
  std::vector<int> lengths_mod_8(8, 0);
  long checked = 0, yielding = 0;  // rows with a bond that can yield
  for (int i = 0; i < n; ++i) {
    const lps::BondRow row = r.row(i);
    const int count = row.end - row.begin;
    ++lengths_mod_8[count % 8];
    for (const double* ep : {static_cast<const double*>(nullptr), r.plastic.data()}) {
      std::vector<double> e_simd(count), e_portable(count);
      const auto a = simd.dilatation(row, i, r.y.data(), r.volume.data(), ep, e_simd.data());
      const auto b =
          portable.dilatation(row, i, r.y.data(), r.volume.data(), ep, e_portable.data());
      const auto c = simd.dilatation(row, i, r.y.data(), r.volume.data(), ep, nullptr);
      ASSERT_TRUE(same_bits(a.theta, b.theta)) << "row " << i;
      ASSERT_TRUE(same_bits(a.moment, b.moment)) << "row " << i;
      ASSERT_TRUE(same_bits(a.theta, c.theta) && same_bits(a.moment, c.moment)) << "row " << i;
      for (int k = 0; k < count; ++k) ASSERT_TRUE(same_bits(e_simd[k], e_portable[k]));
      // the return map's moment from the kept extensions: the dilatation pass's bits
      const double m = simd.moment(row, e_simd.data(), r.volume.data(), ep);
      ASSERT_TRUE(same_bits(m, a.moment)) << "row " << i;
      ASSERT_TRUE(same_bits(m, portable.moment(row, e_simd.data(), r.volume.data(), ep)));
      const OrderedSums s = bond_order(r, i, ep);
      EXPECT_LE(std::abs(a.theta - s.theta), 1e-14 * s.theta_size) << "row " << i;
      EXPECT_LE(std::abs(a.moment - s.moment), 1e-14 * s.moment_size) << "row " << i;
      // the yield test at the row's largest trial force: not past it, and just past the one below
      double largest = 0;
      for (int k = row.begin; k < row.end; ++k) {
        const double stiffness = 2.0 * row.deviatoric[k] * 1e3;
        const double trial =
            stiffness * (e_portable[k - row.begin] - a.theta * row.reference_length[k] / 3.0);
        if (stiffness > 0) largest = std::max(largest, std::abs(trial));
      }
      const double below = std::nextafter(largest, 0.0);
      for (const double critical : {largest, below}) {
        const bool y_simd = simd.yields(row, e_simd.data(), 1e3, a.theta, critical);
        ASSERT_EQ(y_simd, portable.yields(row, e_simd.data(), 1e3, a.theta, critical));
        ASSERT_EQ(y_simd, critical < largest) << "row " << i;
      }
      yielding += largest > 0;
    }
    for (const double theta : {0.0, 0.37}) {
      const lps::ForceRowInput in{&row, i, r.y.data(), r.terms.data(), theta};
      double f_simd[3], f_portable[3], w_simd = 0, w_portable = 0, f_plain[3];
      simd.force(in, f_simd, &w_simd);
      portable.force(in, f_portable, &w_portable);
      simd.force(in, f_plain, nullptr);
      const OrderedForce ordered = bond_order_force(r, i);
      for (int k = 0; k < 3; ++k) {
        ASSERT_TRUE(same_bits(f_simd[k], f_portable[k])) << "row " << i << " component " << k;
        ASSERT_TRUE(same_bits(f_simd[k], f_plain[k])) << "row " << i << " component " << k;
        // the pair's two deviatoric weights each with its own row's terms (w_ij ≠ w_ji here)
        EXPECT_LE(std::abs(f_portable[k] - ordered.force[k]), 1e-14 * ordered.size[k])
            << "row " << i << " component " << k;
      }
      ASSERT_TRUE(same_bits(w_simd, w_portable)) << "row " << i;
    }
    // the matrix-free tangent's passes (row 1 has a collapsed bond: its reference direction)
    const lps::TangentRowInput in{&row,
                                  i,
                                  r.y.data(),
                                  scene.particles.reference.data(),
                                  r.v.data(),
                                  r.volume.data(),
                                  r.tangent_terms.data(),
                                  r.geometric.data()};
    const lps::TangentSums sums_simd = simd.tangent_sums(in), sums = portable.tangent_sums(in);
    ASSERT_TRUE(same_bits(sums_simd.P, sums.P) && same_bits(sums_simd.Q, sums.Q)) << "row " << i;
    double out_simd[3], out[3];
    simd.tangent(in, out_simd);
    portable.tangent(in, out);
    const OrderedTangent ordered = bond_order_tangent(r, scene, i);
    EXPECT_LE(std::abs(sums.P - ordered.P), 1e-14 * ordered.P_size) << "row " << i;
    EXPECT_LE(std::abs(sums.Q - ordered.Q), 1e-14 * ordered.Q_size) << "row " << i;
    for (int k = 0; k < 3; ++k) {
      ASSERT_TRUE(same_bits(out_simd[k], out[k])) << "row " << i << " component " << k;
      EXPECT_LE(std::abs(out[k] - ordered.out[k]), 1e-14 * ordered.out_size[k])
          << "row " << i << " component " << k;
    }
    ++checked;
  }
  std::printf("%ld rows, row lengths mod 8:", checked);
  for (int k = 0; k < 8; ++k) std::printf(" %d", lengths_mod_8[k]);
  std::printf("; rows with a bond that can yield, tested at its threshold: %ld of %ld\n", yielding,
              2 * checked);
  for (int k = 0; k < 8; ++k)
    EXPECT_GT(lengths_mod_8[k], 0) << "no row of length " << k << " mod 8";
  EXPECT_GT(yielding, checked);
}

}  // namespace
}  // namespace fissure
