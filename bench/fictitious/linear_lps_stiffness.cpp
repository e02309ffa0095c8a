#include "fictitious/linear_lps_stiffness.hpp"

#include <algorithm>
#include <stdexcept>

#include "model/quadratic_fit.hpp"

namespace fissure::bench {

namespace {

// The Hessian of V_i W_i over the displacements of the nodes row i reaches (3 each, in the
// order they are first touched): i, its members, or their stencils' particles with `images`.
// local_of maps a node to its place and is left as it was found.
Eigen::MatrixXd row_hessian(const LinearLps& lps, const FictitiousParticles* images, int i,
                            std::vector<int>& nodes, std::vector<int>& local_of) {
  const auto& off = lps.families.offsets;
  const auto& member = lps.families.neighbors;
  const auto& length = lps.families.reference_length;
  const auto& x = lps.particles.reference;
  const auto& volume = lps.particles.volume;
  nodes.clear();
  auto touch = [&](int k) {
    if (local_of[k] < 0) local_of[k] = static_cast<int>(nodes.size()), nodes.push_back(k);
  };
  touch(i);
  for (int b = off[i]; b < off[i + 1]; ++b) {
    const int j = member[b];
    if (!images || j < lps.real) {
      touch(j);
    } else {
      const int g = j - lps.real;
      for (int s = images->offsets[g]; s < images->offsets[g + 1]; ++s) touch(images->particle[s]);
    }
  }
  const int columns = 3 * static_cast<int>(nodes.size()), bonds = off[i + 1] - off[i];
  // u_j − u_i per bond, three rows each, over the nodes' displacements
  Eigen::MatrixXd difference = Eigen::MatrixXd::Zero(3 * bonds, columns);
  for (int b = off[i]; b < off[i + 1]; ++b) {
    const int j = member[b], r = 3 * (b - off[i]);
    for (int a = 0; a < 3; ++a) difference(r + a, 3 * local_of[i] + a) -= 1;
    if (!images || j < lps.real) {
      for (int a = 0; a < 3; ++a) difference(r + a, 3 * local_of[j] + a) += 1;
      continue;
    }
    const int g = j - lps.real;
    for (int s = images->offsets[g]; s < images->offsets[g + 1]; ++s)
      for (int a = 0; a < 3; ++a)
        difference(r + a, 3 * local_of[images->particle[s]] + a) += images->weight[s];
  }
  auto xi = [&](int b, double* out) {
    for (int a = 0; a < 3; ++a) out[a] = x[3 * member[b] + a] - x[3 * i + a];
  };
  // e_ij = ξ̂·(u_j − u_i)
  Eigen::MatrixXd extension(bonds, columns);
  for (int b = off[i]; b < off[i + 1]; ++b) {
    double v[3];
    xi(b, v);
    const int r = b - off[i];
    extension.row(r) = (v[0] * difference.row(3 * r) + v[1] * difference.row(3 * r + 1) +
                        v[2] * difference.row(3 * r + 2)) /
                       length[b];
  }
  Eigen::MatrixXd gradient_energy;
  if (lps.cell_moment) {
    // the fit u_j − u_i ≈ Σ_m q_m φ_m(ξ/δ) (model/quadratic_fit.hpp), weights ω V_j
    double delta = 0;
    for (int b = off[i]; b < off[i + 1]; ++b) delta = std::max(delta, length[b]);
    std::vector<Eigen::Vector3d> members(bonds);
    std::vector<double> fit_weight(bonds);
    std::vector<QuadraticBasis> phi(bonds), a;
    for (int b = off[i]; b < off[i + 1]; ++b) {
      xi(b, members[b - off[i]].data());
      phi[b - off[i]] = quadratic_basis(members[b - off[i]], delta);
      fit_weight[b - off[i]] = delta / length[b] * volume[member[b]];
    }
    if (!quadratic_fit(members, fit_weight, delta, a))
      throw std::invalid_argument("second order: a family does not determine a quadratic");
    // coefficients q_m,a as rows over the nodes: q(3m + a)
    Eigen::MatrixXd q = Eigen::MatrixXd::Zero(27, columns);
    for (int r = 0; r < bonds; ++r)
      for (int m = 0; m < 9; ++m)
        for (int c = 0; c < 3; ++c) q.row(3 * m + c) += a[r](m) * difference.row(3 * r + c);
    // e_ij − ξ̂·Q(ξ)
    for (int r = 0; r < bonds; ++r) {
      double v[3];
      xi(off[i] + r, v);
      for (int m = 3; m < 9; ++m)
        for (int c = 0; c < 3; ++c)
          extension.row(r) -= phi[r](m) * v[c] / length[off[i] + r] * q.row(3 * m + c);
    }
    // ∂²u_c/∂x_k∂x_l over δ²: the coefficient of ½d_k² (m = 3 + k) or of d_kd_l
    auto second = [&](int c, int k, int l) -> Eigen::RowVectorXd {
      return q.row(3 * kSecondDerivative[k][l] + c) / (delta * delta);
    };
    // ∂_k ε_ab = ½(∂_k∂_b u_a + ∂_k∂_a u_b) and ½ Σ_kl M_kl (λ tr ∂_kε tr ∂_lε + 2μ ∂_kε:∂_lε)
    const auto& M = (*lps.cell_moment)[i];
    const double moment[3][3] = {{M[0], M[3], M[4]}, {M[3], M[1], M[5]}, {M[4], M[5], M[2]}};
    const double lame = lps.bulk - 2 * lps.shear / 3;
    std::array<std::array<Eigen::RowVectorXd, 9>, 3> strain_gradient;
    std::array<Eigen::RowVectorXd, 3> trace;
    for (int k = 0; k < 3; ++k) {
      trace[k] = Eigen::RowVectorXd::Zero(columns);
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
          strain_gradient[k][3 * a + b] = 0.5 * (second(a, k, b) + second(b, k, a));
          if (a == b) trace[k] += strain_gradient[k][3 * a + b];
        }
    }
    gradient_energy = Eigen::MatrixXd::Zero(columns, columns);
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 3; ++l) {
        if (moment[k][l] == 0) continue;
        gradient_energy += moment[k][l] * lame * trace[k].transpose() * trace[l];
        for (int ab = 0; ab < 9; ++ab)
          gradient_energy += moment[k][l] * 2 * lps.shear * strain_gradient[k][ab].transpose() *
                             strain_gradient[l][ab];
      }
  }
  Eigen::RowVectorXd dilatation = Eigen::RowVectorXd::Zero(columns);  // θ_i
  for (int b = off[i]; b < off[i + 1]; ++b)
    dilatation += double(lps.dilatation_weight[b]) * volume[member[b]] * extension.row(b - off[i]);
  Eigen::VectorXd weight(bonds);
  for (int b = off[i]; b < off[i + 1]; ++b) {
    extension.row(b - off[i]) -= length[b] / 3 * dilatation;  // ê_ij
    weight(b - off[i]) = double(lps.deviatoric_weight[b]) * volume[member[b]];
  }
  const double B = lps.weighted_volume[i] > 0 ? 15 * lps.shear / lps.weighted_volume[i] : 0;
  Eigen::MatrixXd H = lps.bulk * dilatation.transpose() * dilatation;
  H.noalias() += B * extension.transpose() * weight.asDiagonal() * extension;
  H *= volume[i];
  if (lps.cell_moment) H += gradient_energy;
  return H;
}

}  // namespace

double linear_lps_energy(const LinearLps& lps, const std::vector<double>& u) {
  double energy = 0;
#pragma omp parallel reduction(+ : energy)
  {
    std::vector<int> local_of(lps.particles.count(), -1), nodes;
#pragma omp for schedule(dynamic, 16)
    for (int i = 0; i < lps.real; ++i) {
      const Eigen::MatrixXd H = row_hessian(lps, nullptr, i, nodes, local_of);
      Eigen::VectorXd v(3 * nodes.size());
      for (std::size_t p = 0; p < nodes.size(); ++p)
        for (int a = 0; a < 3; ++a) v(3 * p + a) = u[3 * nodes[p] + a];
      energy += 0.5 * v.dot(H * v);
      for (int k : nodes) local_of[k] = -1;
    }
  }
  return energy;
}

Eigen::MatrixXd linear_lps_stiffness(const LinearLps& lps, const FictitiousParticles* images,
                                     const std::vector<int>& dof, int dofs) {
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(dofs, dofs);
#pragma omp parallel
  {
    std::vector<int> local_of(lps.particles.count(), -1), nodes;
#pragma omp for schedule(dynamic, 8)
    for (int i = 0; i < lps.real; ++i) {
      const Eigen::MatrixXd H = row_hessian(lps, images, i, nodes, local_of);
#pragma omp critical
      for (std::size_t p = 0; p < nodes.size(); ++p) {
        if (dof[nodes[p]] < 0) continue;
        for (std::size_t q = 0; q < nodes.size(); ++q)
          if (dof[nodes[q]] >= 0)
            K.block<3, 3>(3 * dof[nodes[p]], 3 * dof[nodes[q]]) += H.block<3, 3>(3 * p, 3 * q);
      }
      for (int k : nodes) local_of[k] = -1;
    }
  }
  return K;
}

}  // namespace fissure::bench
