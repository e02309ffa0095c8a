#pragma once
// One row of the second-order LPS energy (docs/model.md, deviation 8): the LPS energy
// of particle i with each bond's curvature removed, plus its cell's share of the strain gradient.
// With its family complete (fictitious particles beyond the surface) and the weights of both
// calibrations, every displacement quadratic in x gives the continuum's energy of the cell:
// homogeneous strains exactly (the calibrations), and strain gradients through the cell term
// instead of the bonds, whose midpoints would sample them (an excess of about 0.28 (δ/b)² in
// bending, docs/model.md).
//
// With d_b = y_j − y_i for the bonds b of row i and the fit of quadratic_fit.hpp over them,
//   q_m = Σ_b a_bm d_b,  F = [q_0 q_1 q_2]/s,  ∂_kF column l = q_{(kl)}/s²,
//   r_b = d_b − Σ_{m≥3} φ_m(ξ_b/s) q_m,  ẽ_b = |r_b| − |ξ_b|          (the bond, less its
//   curvature) θ = Σ_b c_b ẽ_b V_b,  ê_b = ẽ_b − θ|ξ_b|/3                          (Eqs 4, 6 with ẽ
//   for e) V_i W_i = V_i (½κθ² + ½B Σ_b w_b ê_b² V_b),  B = 15μ/m_i            (Eq 8, linear solid)
//   W_cell = ½ Σ_kl M_kl (λ tr ∂_kE tr ∂_lE + 2μ ∂_kE : ∂_lE),  ∂_kE = sym(Fᵀ ∂_kF),
//   W_stab = ½ αμ V_i Σ_b ω_b V_b |z_b|²/|ξ_b|² / Σ_b ω_b V_b,  z_b = d_b − Σ_m φ_m(ξ_b/s) q_m,
// M = ∫_cell (x − x_i)(x − x_i)ᵀ, λ = κ − 2μ/3 and ω_b = s/|ξ_b|. W_stab, the stabilisation,
// prices what the fit leaves of each bond (z_b, zero for every quadratic y): without it the
// particles relax away from a quadratic field under load, about 1% softer than its energy says
// (docs/model.md, deviation 8). Objective: a rotation of y rotates every d_b, q_m, r_b and z_b and
// leaves |r_b|, |z_b| and Fᵀ∂_kF as they are.
#include <Eigen/Core>
#include <array>

#include "model/quadratic_fit.hpp"

namespace fissure {

// The stabilisation α the second-order model uses unless told otherwise: docs/model.md,
// deviation 8, has what α does to the cantilever and to a free bar's equilibrium.
inline constexpr double kSecondOrderStabilization = 10;

struct SecondOrderRow {
  int bonds = 0;
  const double* xi;                   // ξ_b, 3 per bond
  const double* length;               // |ξ_b|
  const double* dilatation_weight;    // c_b
  const double* deviatoric_weight;    // w_b
  const double* member_volume;        // V_j of each bond
  const QuadraticBasis* fit;          // a_b (quadratic_fit over the same bonds, scale s)
  double scale;                       // s
  double volume;                      // V_i
  double bulk, shear;                 // κ, μ
  double deviatoric_modulus;          // B = 15μ/m_i
  std::array<double, 6> cell_moment;  // M: xx, yy, zz, xy, xz, yz
  double stabilization = 0;           // α
};

// V_i W_i + W_cell at bond vectors d (3 per bond); with gradient, also ∂/∂d_b (3 per bond),
// overwritten, and with dilatation θ. The force on member j is −gradient_b, on i the sum of
// the gradients.
double second_order_row_energy(const SecondOrderRow& row, const double* d, double* gradient,
                               double* dilatation = nullptr);

// G s_b per bond into weight (bonds entries), the stabilisation's W_stab = ½ Σ_b G s_b |z_b|²
// with s_b = ω_b V_b/|ξ_b|² and G = αμ V_i / Σ_b ω_b V_b; zeros when α = 0.
void stabilization_weights(const SecondOrderRow& row, double* weight);

// ∂²/∂d² of the same at d, 3·bonds square, into hessian (resized): the material part (the
// squared derivatives of θ and ê), the bonds' geometric part (each stretch's curvature times its
// force), the cell term's and the stabilisation's (second_order_row_hessian.cpp).
void second_order_row_hessian(const SecondOrderRow& row, const double* d, Eigen::MatrixXd& hessian);

}  // namespace fissure
