#include "fictitious/linear_lps_stiffness.hpp"

namespace fissure::bench {

double linear_lps_energy(const LinearLps& lps, const std::vector<double>& u) {
  const auto& off = lps.families.offsets;
  const auto& member = lps.families.neighbors;
  const auto& length = lps.families.reference_length;
  const auto& x = lps.particles.reference;
  const auto& volume = lps.particles.volume;
  double energy = 0;
#pragma omp parallel reduction(+ : energy)
  {
    std::vector<double> e;  // e_ij of one row, reused
#pragma omp for schedule(dynamic, 64)
    for (int i = 0; i < lps.real; ++i) {
      e.resize(off[i + 1] - off[i]);
      double theta = 0;  // θ_i = Σ_j c_ij e_ij V_j
      for (int b = off[i]; b < off[i + 1]; ++b) {
        const int j = member[b];
        double s = 0;  // e_ij = ξ̂·(u_j − u_i)
        for (int a = 0; a < 3; ++a)
          s += (x[3 * j + a] - x[3 * i + a]) * (u[3 * j + a] - u[3 * i + a]);
        e[b - off[i]] = s / length[b];
        theta += double(lps.dilatation_weight[b]) * e[b - off[i]] * volume[j];
      }
      double deviatoric = 0;  // Σ_j w_ij ê_ij² V_j, ê = e − θ|ξ|/3
      for (int b = off[i]; b < off[i + 1]; ++b) {
        const double hat = e[b - off[i]] - theta * length[b] / 3;
        deviatoric += double(lps.deviatoric_weight[b]) * hat * hat * volume[member[b]];
      }
      const double B = lps.weighted_volume[i] > 0 ? 15 * lps.shear / lps.weighted_volume[i] : 0;
      energy += volume[i] * (0.5 * lps.bulk * theta * theta + 0.5 * B * deviatoric);
    }
  }
  return energy;
}

Eigen::MatrixXd linear_lps_stiffness(const LinearLps& lps, const FictitiousParticles* images,
                                     const std::vector<int>& dof, int dofs) {
  const auto& off = lps.families.offsets;
  const auto& member = lps.families.neighbors;
  const auto& length = lps.families.reference_length;
  const auto& x = lps.particles.reference;
  const auto& volume = lps.particles.volume;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(dofs, dofs);
#pragma omp parallel
  {
    std::vector<int> local_of(lps.real, -1);
    std::vector<int> nodes;
#pragma omp for schedule(dynamic, 8)
    for (int i = 0; i < lps.real; ++i) {
      // the real particles row i depends on: i, its real members, its images' stencils
      nodes.clear();
      auto touch = [&](int k) {
        if (local_of[k] < 0) local_of[k] = static_cast<int>(nodes.size()), nodes.push_back(k);
      };
      touch(i);
      for (int b = off[i]; b < off[i + 1]; ++b) {
        const int j = member[b];
        if (j < lps.real) {
          touch(j);
        } else {
          const int g = j - lps.real;
          for (int s = images->offsets[g]; s < images->offsets[g + 1]; ++s)
            touch(images->particle[s]);
        }
      }
      const int columns = 3 * static_cast<int>(nodes.size()), bonds = off[i + 1] - off[i];
      // e_ij = ξ̂·(u_j − u_i) as rows over the nodes' displacements
      Eigen::MatrixXd extension = Eigen::MatrixXd::Zero(bonds, columns);
      for (int b = off[i]; b < off[i + 1]; ++b) {
        const int j = member[b], r = b - off[i];
        double n[3];
        for (int a = 0; a < 3; ++a) n[a] = (x[3 * j + a] - x[3 * i + a]) / length[b];
        for (int a = 0; a < 3; ++a) extension(r, 3 * local_of[i] + a) -= n[a];
        if (j < lps.real) {
          for (int a = 0; a < 3; ++a) extension(r, 3 * local_of[j] + a) += n[a];
          continue;
        }
        const int g = j - lps.real;
        for (int s = images->offsets[g]; s < images->offsets[g + 1]; ++s)
          for (int a = 0; a < 3; ++a)
            extension(r, 3 * local_of[images->particle[s]] + a) += images->weight[s] * n[a];
      }
      Eigen::RowVectorXd dilatation = Eigen::RowVectorXd::Zero(columns);  // θ_i
      for (int b = off[i]; b < off[i + 1]; ++b)
        dilatation +=
            double(lps.dilatation_weight[b]) * volume[member[b]] * extension.row(b - off[i]);
      Eigen::VectorXd weight(bonds);
      for (int b = off[i]; b < off[i + 1]; ++b) {
        extension.row(b - off[i]) -= length[b] / 3 * dilatation;  // ê_ij
        weight(b - off[i]) = double(lps.deviatoric_weight[b]) * volume[member[b]];
      }
      const double B = lps.weighted_volume[i] > 0 ? 15 * lps.shear / lps.weighted_volume[i] : 0;
      Eigen::MatrixXd H = lps.bulk * dilatation.transpose() * dilatation;
      H.noalias() += B * extension.transpose() * weight.asDiagonal() * extension;
      H *= volume[i];
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
