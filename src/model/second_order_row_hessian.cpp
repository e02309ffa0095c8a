// The Hessian of one second-order row (second_order_row.hpp), over its bond vectors d. Through
// the fit q = Aᵀd (A: 3·bonds × 27, A(3c + a, 3m + a) = a_cm), each corrected bond is
// r_b = d_b − Σ_{m≥3} φ_bm q_m, so ∂ẽ_b/∂d = r̂_bᵀ(E_b − Σ_{m≥3} φ_bm A_mᵀ) = row b of
// J = R − U Aᵀ with R = diag(r̂_bᵀ) and U(b, 3m + a) = φ_bm r̂_b,a.
#include <Eigen/Dense>
#include <cmath>

#include "model/second_order_row.hpp"

namespace fissure {

namespace {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

// sym(X) = ½(X + Xᵀ)
Mat3 sym(const Mat3& X) { return 0.5 * (X + X.transpose()); }

// The cell term's Hessian over q (27 × 27, q(3m + a)): Σ_kl M_kl ∂E_k:C:∂E_l + Σ_k T_k:∂²E_k,
// E_k = sym(Fᵀ G_k), F column l = q_l/s, G_k column l = q_(kl)/s².
Eigen::Matrix<double, 27, 27> cell_hessian(const SecondOrderRow& row, const Eigen::VectorXd& q) {
  const double s = row.scale, lame = row.bulk - 2 * row.shear / 3;
  const auto& c = row.cell_moment;
  const double M[3][3] = {{c[0], c[3], c[4]}, {c[3], c[1], c[5]}, {c[4], c[5], c[2]}};
  auto stress = [&](const Mat3& E) {  // C:E
    return Mat3(lame * E.trace() * Mat3::Identity() + 2 * row.shear * E);
  };
  Mat3 F, G[3];
  for (int l = 0; l < 3; ++l) F.col(l) = q.segment<3>(3 * l) / s;
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) G[k].col(l) = q.segment<3>(3 * kSecondDerivative[k][l]) / (s * s);
  Mat3 T[3];
  for (int k = 0; k < 3; ++k) {
    T[k].setZero();
    for (int l = 0; l < 3; ++l) T[k] += M[k][l] * stress(sym(F.transpose() * G[l]));
  }
  // the derivatives of F and G_k along each unit direction of q
  Mat3 dF[27], dG[27][3];
  for (int p = 0; p < 27; ++p) {
    const int m = p / 3, a = p % 3;
    dF[p].setZero();
    for (int k = 0; k < 3; ++k) dG[p][k].setZero();
    if (m < 3) dF[p](a, m) = 1 / s;
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 3; ++l)
        if (kSecondDerivative[k][l] == m) dG[p][k](a, l) = 1 / (s * s);
  }
  Mat3 dE[27][3];
  for (int p = 0; p < 27; ++p)
    for (int k = 0; k < 3; ++k) dE[p][k] = sym(dF[p].transpose() * G[k] + F.transpose() * dG[p][k]);
  Eigen::Matrix<double, 27, 27> H;
  for (int p = 0; p < 27; ++p)
    for (int r = 0; r <= p; ++r) {
      double h = 0;
      for (int k = 0; k < 3; ++k) {
        for (int l = 0; l < 3; ++l)
          if (M[k][l] != 0) h += M[k][l] * (dE[p][k].array() * stress(dE[r][l]).array()).sum();
        const Mat3 second = sym(dF[p].transpose() * dG[r][k] + dF[r].transpose() * dG[p][k]);
        h += (T[k].array() * second.array()).sum();
      }
      H(p, r) = H(r, p) = h;
    }
  return H;
}

}  // namespace

void second_order_row_hessian(const SecondOrderRow& row, const double* d,
                              Eigen::MatrixXd& hessian) {
  const int n = row.bonds, N = 3 * n;
  const double s = row.scale;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(N, 27);
  for (int c = 0; c < n; ++c)
    for (int m = 0; m < 9; ++m)
      for (int a = 0; a < 3; ++a) A(3 * c + a, 3 * m + a) = row.fit[c](m);
  const Eigen::VectorXd q = A.transpose() * Eigen::Map<const Eigen::VectorXd>(d, N);

  // per bond: φ_b, r̂_b, |r_b|, ẽ_b; then θ and the sums of Eq 8
  Eigen::MatrixXd phi(n, 9), unit(n, 3);
  Eigen::VectorXd stretch(n), rho(n);
  double theta = 0;
  for (int b = 0; b < n; ++b) {
    phi.row(b) = quadratic_basis(Vec3(row.xi[3 * b], row.xi[3 * b + 1], row.xi[3 * b + 2]), s);
    Vec3 r(d[3 * b], d[3 * b + 1], d[3 * b + 2]);
    for (int m = 3; m < 9; ++m) r -= phi(b, m) * q.segment<3>(3 * m);
    rho(b) = r.norm();
    unit.row(b) = r / rho(b);
    stretch(b) = rho(b) - row.length[b];
    theta += row.dilatation_weight[b] * stretch(b) * row.member_volume[b];
  }
  // Σ_b w V ê² = ẽᵀDẽ − 2(gᵀẽ)(hᵀẽ) + s2 (gᵀẽ)², g = cV, D = diag(wV), h = wV|ξ|/3
  Eigen::VectorXd g(n), h(n), D(n);
  double s2 = 0, moment = 0;
  for (int b = 0; b < n; ++b) {
    g(b) = row.dilatation_weight[b] * row.member_volume[b];
    D(b) = row.deviatoric_weight[b] * row.member_volume[b];
    h(b) = D(b) * row.length[b] / 3;
    s2 += D(b) * row.length[b] * row.length[b] / 9;
    moment += D(b) * (stretch(b) - theta * row.length[b] / 3) * row.length[b];
  }
  const double V = row.volume, B = row.deviatoric_modulus;
  const double pressure = row.bulk * theta - B / 3 * moment;

  // J = R − U Aᵀ
  Eigen::MatrixXd U = Eigen::MatrixXd::Zero(n, 27);
  for (int b = 0; b < n; ++b)
    for (int m = 3; m < 9; ++m)
      for (int a = 0; a < 3; ++a) U(b, 3 * m + a) = phi(b, m) * unit(b, a);
  Eigen::MatrixXd J = -U * A.transpose();
  for (int b = 0; b < n; ++b)
    for (int a = 0; a < 3; ++a) J(b, 3 * b + a) += unit(b, a);

  // material part: V [(κ + B s2) JᵀggᵀJ + B (JᵀDJ − Jᵀg hᵀJ − Jᵀh gᵀJ)]
  const Eigen::VectorXd Jg = J.transpose() * g, Jh = J.transpose() * h;
  hessian.noalias() = (V * B) * J.transpose() * D.asDiagonal() * J;
  hessian.noalias() += V * (row.bulk + B * s2) * Jg * Jg.transpose();
  hessian.noalias() -= (V * B) * (Jg * Jh.transpose() + Jh * Jg.transpose());

  // geometric part: Σ_b τ_b L_bᵀ P_b L_b, τ_b = (∂W/∂ẽ_b)/|r_b|, P_b = I − r̂r̂ᵀ,
  // L_b = E_b − Y_b with Y_b(a, 3c + a) = v_bc = Σ_{m≥3} φ_bm a_cm
  Eigen::MatrixXd Ac(6, n);
  for (int c = 0; c < n; ++c)
    for (int m = 3; m < 9; ++m) Ac(m - 3, c) = row.fit[c](m);
  const Eigen::MatrixXd Phi = phi.rightCols(6), v = Phi * Ac;  // v(b, c)
  Eigen::VectorXd tau(n);
  for (int b = 0; b < n; ++b) {
    const double hat = stretch(b) - theta * row.length[b] / 3;
    tau(b) = V * (g(b) * pressure + B * D(b) * hat) / rho(b);
  }
  for (int b = 0; b < n; ++b) {
    const Vec3 r = unit.row(b).transpose();
    const Mat3 Pb = tau(b) * (Mat3::Identity() - r * r.transpose());
    hessian.block<3, 3>(3 * b, 3 * b) += Pb;  // E_bᵀ P E_b
    for (int c = 0; c < n; ++c) {             // −E_bᵀ P Y_b and its transpose
      hessian.block<3, 3>(3 * b, 3 * c) -= v(b, c) * Pb;
      hessian.block<3, 3>(3 * c, 3 * b) -= v(b, c) * Pb;
    }
  }
  for (int a = 0; a < 3; ++a)
    for (int e = 0; e < 3; ++e) {  // Y_bᵀ P Y_b summed: Acᵀ (Φᵀ diag(τ P_ae) Φ) Ac
      Eigen::VectorXd weight(n);
      for (int b = 0; b < n; ++b)
        weight(b) = tau(b) * ((a == e ? 1.0 : 0.0) - unit(b, a) * unit(b, e));
      const Eigen::MatrixXd core = Phi.transpose() * weight.asDiagonal() * Phi;
      const Eigen::MatrixXd block = Ac.transpose() * core * Ac;
      for (int c = 0; c < n; ++c)
        for (int k = 0; k < n; ++k) hessian(3 * c + a, 3 * k + e) += block(c, k);
    }

  // the cell term through q = Aᵀd
  hessian.noalias() += A * cell_hessian(row, q) * A.transpose();

  // the stabilisation, ½ G Σ_b s_b |z_b|² with z = (I − Φ_all Aᵀ) d per component: a constant
  // Zᵀ diag(G s) Z on each component, Z = I − Φ_all A_allᵀ
  if (row.stabilization > 0) {
    Eigen::MatrixXd all(9, n);
    for (int c = 0; c < n; ++c) all.col(c) = row.fit[c];
    Eigen::MatrixXd Z = -phi * all;
    Z.diagonal().array() += 1;
    Eigen::VectorXd weight(n);
    stabilization_weights(row, weight.data());
    const Eigen::MatrixXd scalar = Z.transpose() * weight.asDiagonal() * Z;
    for (int c = 0; c < n; ++c)
      for (int k = 0; k < n; ++k)
        for (int a = 0; a < 3; ++a) hessian(3 * c + a, 3 * k + a) += scalar(c, k);
  }
}

}  // namespace fissure
