#pragma once
// The stiffness matrix of the linearised LPS energy (docs/model.md), dense, for
// bench_fictitious_particles: Π = Σ_i V_i W_i over the rows of the real particles i < real,
//   W_i = ½κθ_i² + ½B_i Σ_j w_ij ê_ij² V_j,  θ_i = Σ_j c_ij e_ij V_j,  ê_ij = e_ij − θ_i|ξ|/3,
//   e_ij = ξ̂·(u_j − u_i),  B_i = 15μ/m_i,
// where members j ≥ real are the fictitious particles `images`, moved by their stencils (none:
// no such members). Rows and columns are the degrees of freedom dof[i] ≥ 0 of the real particles
// (−1: held at zero).
//
// With cell_moment (second order): each row's energy is the second-order model's
// (model/second_order_row.hpp: the bonds less their fitted curvature, plus the cell's share of
// the strain gradient), its Hessian at the reference state; a quadratic displacement then stores
// exactly the continuum's energy of the cells.
#include <Eigen/Dense>
#include <array>
#include <vector>

#include "model/fictitious_particles.hpp"
#include "scene/particles.hpp"

namespace fissure::bench {

struct LinearLps {
  const Particles& particles;  // the real particles first, then the fictitious ones
  const Families& families;
  int real;
  const std::vector<float>& dilatation_weight;  // c_ij
  const std::vector<float>& deviatoric_weight;  // w_ij
  const std::vector<double>& weighted_volume;   // m_i
  double bulk, shear;
  // M_i per real particle (xx, yy, zz, xy, xz, yz); null: first order (the model's energy)
  const std::vector<std::array<double, 6>>* cell_moment = nullptr;
  double stabilization = 0;  // α of the second-order rows (model/second_order_row.hpp)
};

// The same energy Π at displacements u of every particle, real and fictitious (3 each): what a
// field the stencils reproduce exactly (a quadratic one) stores, without the stencils.
double linear_lps_energy(const LinearLps& lps, const std::vector<double>& u);

Eigen::MatrixXd linear_lps_stiffness(const LinearLps& lps, const FictitiousParticles* images,
                                     const std::vector<int>& dof, int dofs);

}  // namespace fissure::bench
