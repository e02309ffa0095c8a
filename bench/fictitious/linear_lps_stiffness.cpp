#include "fictitious/linear_lps_stiffness.hpp"

#include <algorithm>
#include <stdexcept>

#include "model/quadratic_fit.hpp"
#include "model/second_order_row.hpp"

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
  if (lps.cell_moment) {
    // the model's own row (model/second_order_row.hpp), whose Hessian at the reference is the
    // linearised energy's over the bond vectors d_b = u_j − u_i + ξ_b
    std::vector<double> bond_xi(3 * bonds), c(bonds), w(bonds), member_volume(bonds);
    std::vector<Eigen::Vector3d> members(bonds);
    std::vector<double> fit_weight(bonds);
    double delta = 0;
    for (int b = off[i]; b < off[i + 1]; ++b) delta = std::max(delta, length[b]);
    for (int b = off[i]; b < off[i + 1]; ++b) {
      const int r = b - off[i];
      xi(b, &bond_xi[3 * r]);
      members[r] = Eigen::Vector3d(&bond_xi[3 * r]);
      c[r] = lps.dilatation_weight[b], w[r] = lps.deviatoric_weight[b];
      member_volume[r] = volume[member[b]];
      fit_weight[r] = delta / length[b] * volume[member[b]];
    }
    std::vector<QuadraticBasis> fit;
    if (!quadratic_fit(members, fit_weight, delta, fit))
      throw std::invalid_argument("second order: a family does not determine a quadratic");
    const SecondOrderRow row{.bonds = bonds,
                             .xi = bond_xi.data(),
                             .length = length.data() + off[i],
                             .dilatation_weight = c.data(),
                             .deviatoric_weight = w.data(),
                             .member_volume = member_volume.data(),
                             .fit = fit.data(),
                             .scale = delta,
                             .volume = volume[i],
                             .bulk = lps.bulk,
                             .shear = lps.shear,
                             .deviatoric_modulus = lps.weighted_volume[i] > 0
                                                       ? 15 * lps.shear / lps.weighted_volume[i]
                                                       : 0,
                             .cell_moment = (*lps.cell_moment)[i],
                             .stabilization = lps.stabilization};
    Eigen::MatrixXd hessian;
    second_order_row_hessian(row, bond_xi.data(), hessian);
    return difference.transpose() * hessian * difference;
  }
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
