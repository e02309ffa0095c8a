#include "model/second_order_row.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <vector>

namespace fissure {

namespace {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

}  // namespace

double second_order_row_energy(const SecondOrderRow& row, const double* d, double* gradient,
                               double* dilatation) {
  const int n = row.bonds;
  const double s = row.scale;
  // q_m = Σ_b a_bm d_b
  std::array<Vec3, 9> q;
  for (Vec3& v : q) v.setZero();
  for (int b = 0; b < n; ++b) {
    const Vec3 db(d[3 * b], d[3 * b + 1], d[3 * b + 2]);
    for (int m = 0; m < 9; ++m) q[m] += row.fit[b](m) * db;
  }
  // per bond, once: φ(ξ_b/s), and r_b = d_b − Σ_{m≥3} φ_m q_m (the bond less the fitted
  // curvature) as its length and direction; scratch kept per thread, grown only
  struct Corrected {
    QuadraticBasis phi;
    Vec3 unit;
    double length;
  };
  thread_local std::vector<Corrected> bond;
  bond.resize(n);
  double theta = 0;  // θ = Σ c ẽ V, ẽ_b = |r_b| − |ξ_b| (Eq 6)
  for (int b = 0; b < n; ++b) {
    bond[b].phi = quadratic_basis(Vec3(row.xi[3 * b], row.xi[3 * b + 1], row.xi[3 * b + 2]), s);
    Vec3 r(d[3 * b], d[3 * b + 1], d[3 * b + 2]);
    for (int m = 3; m < 9; ++m) r -= bond[b].phi(m) * q[m];
    bond[b].length = r.norm();
    bond[b].unit = r / bond[b].length;
    theta += row.dilatation_weight[b] * (bond[b].length - row.length[b]) * row.member_volume[b];
  }
  if (dilatation) *dilatation = theta;
  // ê_b and the deviatoric sums (Eq 8): Σ w ê² V and Σ w ê |ξ| V
  auto hat = [&](int b) { return bond[b].length - row.length[b] - theta * row.length[b] / 3; };
  double squares = 0, moment = 0;
  for (int b = 0; b < n; ++b) {
    squares += row.deviatoric_weight[b] * hat(b) * hat(b) * row.member_volume[b];
    moment += row.deviatoric_weight[b] * hat(b) * row.length[b] * row.member_volume[b];
  }
  const double bond_energy =
      row.volume * (0.5 * row.bulk * theta * theta + 0.5 * row.deviatoric_modulus * squares);

  // the cell term: F, ∂_kF, ∂_kE = sym(Fᵀ∂_kF), T_k = Σ_l M_kl C:∂_lE
  const auto& c = row.cell_moment;
  const double M[3][3] = {{c[0], c[3], c[4]}, {c[3], c[1], c[5]}, {c[4], c[5], c[2]}};
  Mat3 F, G[3], E[3], T[3];
  for (int l = 0; l < 3; ++l) F.col(l) = q[l] / s;
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) G[k].col(l) = q[kSecondDerivative[k][l]] / (s * s);
  for (int k = 0; k < 3; ++k) E[k] = 0.5 * (F.transpose() * G[k] + G[k].transpose() * F);
  const double lame = row.bulk - 2 * row.shear / 3;
  double cell_energy = 0;
  for (int k = 0; k < 3; ++k) {
    T[k].setZero();
    for (int l = 0; l < 3; ++l)
      T[k] += M[k][l] * (lame * E[l].trace() * Mat3::Identity() + 2 * row.shear * E[l]);
    cell_energy += 0.5 * (T[k].array() * E[k].array()).sum();
  }
  // the stabilisation ½ Σ_b G s_b |z_b|², z_b = r_b − Σ_{m<3} φ_m q_m (the bond less the whole
  // fitted quadratic), and its pull G s_b z_b on each bond
  thread_local std::vector<double> weight;
  thread_local std::vector<Vec3> pull;
  weight.resize(n);
  pull.assign(n, Vec3::Zero());
  double stabilization_energy = 0;
  if (row.stabilization > 0) {
    stabilization_weights(row, weight.data());
    for (int b = 0; b < n; ++b) {
      Vec3 z = bond[b].length * bond[b].unit;
      for (int m = 0; m < 3; ++m) z -= bond[b].phi(m) * q[m];
      stabilization_energy += 0.5 * weight[b] * z.squaredNorm();
      pull[b] = weight[b] * z;
    }
  }
  const double energy = bond_energy + cell_energy + stabilization_energy;
  if (!gradient) return energy;

  // ∂/∂ẽ_b = V_i [c_b V_b (κθ − (B/3) Σ w ê |ξ| V) + B w_b ê_b V_b], along r̂_b; through q, the
  // curvature removed from every bond: P_m = −Σ_b φ_bm t_b r̂_b (m ≥ 3), plus the cell term's
  // ∂W_cell/∂q_m: Σ_k ∂_kF T_k for F (over s), F T_k for ∂_kF (over s²).
  const double pressure = row.bulk * theta - row.deviatoric_modulus / 3 * moment;
  std::array<Vec3, 9> P;
  for (Vec3& v : P) v.setZero();
  for (int b = 0; b < n; ++b) {
    const double t = row.volume * row.member_volume[b] *
                     (row.dilatation_weight[b] * pressure +
                      row.deviatoric_modulus * row.deviatoric_weight[b] * hat(b));
    const Vec3 g = t * bond[b].unit;
    for (int a = 0; a < 3; ++a) gradient[3 * b + a] = g[a] + pull[b][a];
    for (int m = 3; m < 9; ++m) P[m] -= bond[b].phi(m) * g;
    for (int m = 0; m < 9; ++m) P[m] -= bond[b].phi(m) * pull[b];
  }
  Mat3 dF = Mat3::Zero();
  for (int k = 0; k < 3; ++k) dF += G[k] * T[k];
  for (int l = 0; l < 3; ++l) P[l] += dF.col(l) / s;
  for (int k = 0; k < 3; ++k) {
    const Mat3 dG = F * T[k];
    for (int l = 0; l < 3; ++l) P[kSecondDerivative[k][l]] += dG.col(l) / (s * s);
  }
  for (int b = 0; b < n; ++b)
    for (int m = 0; m < 9; ++m)
      for (int a = 0; a < 3; ++a) gradient[3 * b + a] += row.fit[b](m) * P[m][a];
  return energy;
}

void stabilization_weights(const SecondOrderRow& row, double* weight) {
  const double s = row.scale;
  double mass = 0;  // Σ_b ω_b V_b
  for (int b = 0; b < row.bonds; ++b) mass += s / row.length[b] * row.member_volume[b];
  const double modulus = row.stabilization * row.shear * row.volume / mass;
  for (int b = 0; b < row.bonds; ++b) {
    const double l = row.length[b];
    weight[b] = modulus * s * row.member_volume[b] / (l * l * l);  // G ω_b V_b / |ξ_b|²
  }
}

}  // namespace fissure
