// The row passes of lps_rows.hpp in plain C++: eight lane sums, reduced in the order the AVX-512
// version reduces them, with the same operations per bond (no fused multiply-add: the model's
// sources are compiled with -ffp-contract=off), so that both give the same bits.
#include <cmath>

#include "model/lps_rows.hpp"

namespace fissure::lps {

namespace {

constexpr int lanes = 8;

double reduce(const double (&sum)[lanes]) {
  const double a0 = sum[0] + sum[4], a1 = sum[1] + sum[5], a2 = sum[2] + sum[6],
               a3 = sum[3] + sum[7];
  return (a0 + a2) + (a1 + a3);
}

DilatationSums dilatation_row(const BondRow& row, int i, const double* y, const double* V,
                              const double* ep, double* extension) {
  const double yi0 = y[3 * i], yi1 = y[3 * i + 1], yi2 = y[3 * i + 2];
  double theta[lanes] = {}, moment[lanes] = {};
  for (int b = row.begin; b < row.end; ++b) {
    const int lane = (b - row.begin) % lanes, j = row.neighbor[b];
    const double* yj = y + 3 * j;
    const double d0 = yj[0] - yi0, d1 = yj[1] - yi1, d2 = yj[2] - yi2;
    const double xi = row.reference_length[b];
    const double e = std::sqrt(d0 * d0 + d1 * d1 + d2 * d2) - xi;  // e_ij
    if (extension) extension[b - row.begin] = e;
    const double eV = e * V[j];
    theta[lane] += double(row.weight[b]) * eV;  // c_ij e_ij V_j (Eq 6)
    const double w_xi = double(row.deviatoric[b]) * xi;
    moment[lane] += ep ? w_xi * (eV - ep[b] * V[j]) : w_xi * eV;
  }
  return {reduce(theta), reduce(moment)};
}

double moment_row(const BondRow& row, const double* extension, const double* V, const double* ep) {
  double moment[lanes] = {};
  for (int b = row.begin; b < row.end; ++b) {
    const int lane = (b - row.begin) % lanes, j = row.neighbor[b];
    const double xi = row.reference_length[b];
    const double w_xi = double(row.deviatoric[b]) * xi, eV = extension[b - row.begin] * V[j];
    moment[lane] += ep ? w_xi * (eV - ep[b] * V[j]) : w_xi * eV;
  }
  return reduce(moment);
}

// t_ij + t_ji = c_ij D_i + c_ji D_j + w_ij (e B_i − |ξ| S_i) + w_ji (e B_j − |ξ| S_j) (Eqs 4, 8,
// 12; notes §6; w = ω uncalibrated), times V_j/ℓ along d = y_j − y_i.
// Separate: w_ji has its own array (calibrated); else w_ji = w_ij (pair_deviatoric).
template <bool Separate>
void force_row_sums(const ForceRowInput& in, double force[3], double* squares) {
  const BondRow& row = *in.row;
  const int i = in.i;
  const double* y = in.y;
  const NeighbourTerms* terms = in.terms;
  const double yi0 = y[3 * i], yi1 = y[3 * i + 1], yi2 = y[3 * i + 2];
  const NeighbourTerms& ti = terms[i];
  double f0[lanes] = {}, f1[lanes] = {}, f2[lanes] = {}, w[lanes] = {};
  for (int b = row.begin; b < row.end; ++b) {
    const int lane = (b - row.begin) % lanes, j = row.neighbor[b];
    const double* yj = y + 3 * j;
    const double d0 = yj[0] - yi0, d1 = yj[1] - yi1, d2 = yj[2] - yi2;
    const double length = std::sqrt(d0 * d0 + d1 * d1 + d2 * d2);
    const double xi = row.reference_length[b];
    const double e = length - xi;
    const NeighbourTerms& tj = terms[j];
    const double w_ij = row.deviatoric[b];
    const double t =
        (double(row.weight[b]) * ti.pressure + double(row.reverse_weight[b]) * tj.pressure) +
        pair_deviatoric<Separate>(e, xi, w_ij, row.reverse_deviatoric[b], ti, tj, 0, 0);
    // n = d / |d|; a collapsed bond (|d| = 0) has no direction and carries no force.
    const double s = length > 0 ? t * tj.volume / length : 0.0;
    f0[lane] += s * d0;
    f1[lane] += s * d1;
    f2[lane] += s * d2;
    if (squares) {
      const double e_hat = e - in.elastic_theta * xi / 3.0;  // ê_ij
      w[lane] += w_ij * tj.volume * e_hat * e_hat;
    }
  }
  force[0] = reduce(f0);
  force[1] = reduce(f1);
  force[2] = reduce(f2);
  if (squares) *squares = reduce(w);
}

void force_row(const ForceRowInput& in, double force[3], double* squares) {
  if (in.row->reverse_deviatoric != in.row->deviatoric)
    force_row_sums<true>(in, force, squares);
  else
    force_row_sums<false>(in, force, squares);
}

bool yields(const BondRow& row, const double* extension, double B, double trial_theta,
            double yield_force) {
  for (int b = row.begin; b < row.end; ++b) {
    const double xi = row.reference_length[b];
    const double stiffness = 2.0 * row.deviatoric[b] * B;  // 4ωb, with w for ω
    const double trial = stiffness * (extension[b - row.begin] - trial_theta * xi / 3.0);
    if (stiffness > 0 && std::abs(trial) > yield_force) return true;
  }
  return false;
}

// Bond b of row i (to member j): n_b = d (1/ℓ) (bond_geometry's d/ℓ to round-off), v_j − v_i and
// s_b = n_b·(v_j − v_i).
struct BondRate {
  double n[3], dv[3], s;
};

BondRate bond_rate(const TangentRowInput& in, int b, int j) {
  const double* yi = in.y + 3 * in.i;
  const double* yj = in.y + 3 * j;
  const double xi = in.row->reference_length[b];
  double d[3] = {yj[0] - yi[0], yj[1] - yi[1], yj[2] - yi[2]};
  double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (length <= kCollapsedBond * xi) {
    for (int k = 0; k < 3; ++k) d[k] = in.reference[3 * j + k] - in.reference[3 * in.i + k];
    length = xi;
  }
  BondRate r;
  const double inverse = 1.0 / length;  // one division instead of three
  for (int k = 0; k < 3; ++k) {
    r.n[k] = d[k] * inverse;
    r.dv[k] = in.v[3 * j + k] - in.v[3 * in.i + k];
  }
  r.s = r.n[0] * r.dv[0] + r.n[1] * r.dv[1] + r.n[2] * r.dv[2];
  return r;
}

TangentSums tangent_sums(const TangentRowInput& in) {
  const BondRow& row = *in.row;
  double P[lanes] = {}, Q[lanes] = {};
  for (int b = row.begin; b < row.end; ++b) {
    const int lane = (b - row.begin) % lanes, j = row.neighbor[b];
    const double sV = bond_rate(in, b, j).s * in.volume[j];
    P[lane] += double(row.weight[b]) * sV;
    Q[lane] += double(row.deviatoric[b]) * row.reference_length[b] * sV;
  }
  return {reduce(P), reduce(Q)};
}

void tangent_row(const TangentRowInput& in, double out[3]) {
  const BondRow& row = *in.row;
  const TangentTerms ti = in.terms[in.i];
  const double three_gamma = 3.0 * ti.gamma;
  double o[3][lanes] = {};
  for (int b = row.begin; b < row.end; ++b) {
    const int lane = (b - row.begin) % lanes, j = row.neighbor[b];
    const BondRate r = bond_rate(in, b, j);
    const TangentTerms& tj = in.terms[j];
    const double xi = row.reference_length[b], g = in.geometric[b];
    const double t_own = tj.volume * (double(row.weight[b]) * ti.x +
                                      double(row.deviatoric[b]) * (three_gamma * r.s - xi * ti.y));
    const double t_member =
        ti.volume * (double(row.reverse_weight[b]) * tj.x +
                     double(row.reverse_deviatoric[b]) * (3.0 * tj.gamma * r.s - xi * tj.y));
    const double along = g * r.s - t_own - t_member;
    for (int k = 0; k < 3; ++k) o[k][lane] += along * r.n[k] - g * r.dv[k];
  }
  for (int k = 0; k < 3; ++k) out[k] = reduce(o[k]);
}

}  // namespace

RowKernels portable_row_kernels() {
  return {"portable", dilatation_row, moment_row, force_row, yields, tangent_sums, tangent_row};
}

RowKernels row_kernels() {
  const RowKernels simd = avx512_row_kernels();
  return simd.force ? simd : portable_row_kernels();
}

}  // namespace fissure::lps
