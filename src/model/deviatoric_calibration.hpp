#pragma once
// Calibrated deviatoric weights (a deviation from the paper, like the calibrated
// dilatation of dilatation_calibration.hpp), used by the LPS model with
// material.surface_correction: full (docs/model.md).
//
// With θ exact, a small homogeneous strain ε gives ê_ij = |ξ| a_jᵀx, x_k = D_k:ε, where a_j ∈ R⁵
// holds the coordinates of dev(ξ̂ξ̂ᵀ) in an orthonormal basis D_1..D_5 of the deviatoric tensors
// (xy, xz, yz, (xx − yy)/√2, (xx + yy − 2zz)/√6), a_k = ξ̂ᵀD_kξ̂. The deviatoric energy of row i,
// ½ Σ_j g_ij ê_ij² V_j, is then ½ xᵀA_i x with
//   A_i = Σ_j g_ij |ξ|² V_j a_j a_jᵀ   (5×5),
// and equals the continuum's μ|dev ε|² for every ε iff A_i = 2μ_i I₅ (15 conditions). Today's
// weight g_ij = ω_ij B_i, B_i = 15μ_i/m_i, gets only the trace right (the mode average). As the
// position-aware LPS of Mitchell, Silling and Littlewood (J. Mech. Mater. Struct. 2015), which
// imposes 6 of these conditions, but on all 15 and with bounds: g_ij = ρ_ij ω_ij B_i with
//   ρ_ij = clip(1 + s_jᵀλ_i, ρ_min, ρ_max),   s_j = the upper triangle of a_j a_jᵀ,
// the minimum change ½ Σ_j ω B_i|ξ|²V_j (ρ_j − 1)² that gives A_i = T_i (the target, 2μ_i I₅
// for an isotropic body), λ_i ∈ R¹⁵ its Lagrange multipliers. ρ ≥ ρ_min > 0 keeps every bond's
// stiffness positive, so W_i stays a sum of squares (as the majoriser's proof needs). Where no
// bounded weights reach T_i (a particle on an edge or at a corner of a body, where no g ≥ 0 is
// exact) the result is the bounded compromise of the proximal solve, and its residual is
// reported.
#include <array>
#include <cstdint>
#include <vector>

#include "scene/particles.hpp"

namespace fissure {

// The bounds of ρ_ij: ρ_min > 0 keeps every bond stiff (W_i positive semidefinite); ρ_max = 2
// makes faces and once-removed edges of a lattice exact, while stiffer bonds shorten the stable
// step: by 3.6% on a jittered 7³ cube that is all surface, 21% with ρ_max = 4.
constexpr double kMinimumDeviatoricFactor = 0.1;
constexpr double kMaximumDeviatoricFactor = 2.0;
// A row is exact when no deviatoric strain's energy is off by more than this relative amount:
// well above the single-precision rounding of g (2⁻²⁴ = 6e-8 per bond), far below any surface
// effect (0.1 and more).
constexpr double kExactDeviatoricResidual = 1e-6;

// The target T_i/(2μ_i) of a body: a symmetric positive definite 5×5 matrix in the basis D_k,
// row major. I₅ for an isotropic body; an anisotropic one (Eq 17) may pass its own average.
using DeviatoricShape = std::array<double, 25>;
DeviatoricShape isotropic_deviatoric_shape();
// The target of an anisotropic body whose influence function is ω = δ/|Gξ| (Eq 17, G row major):
// the continuum limit of its uncalibrated A_i/2μ_i, so that calibrated surface particles answer
// as the body's inside does.
DeviatoricShape anisotropic_deviatoric_shape(const std::array<double, 9>& G);

// What a row got: calibrated weights, or ρ ≡ 1 (w_ij = ω_ij) because its family has fewer
// than 15 bonds, its Gram matrix Σ_j s_j s_jᵀ (weighted) is singular (or a Newton matrix could
// not be factorised), or the calibrated weights would leave a larger residual than ρ ≡ 1.
enum class DeviatoricRow : std::uint8_t { calibrated, too_few_bonds, singular, not_better };

struct DeviatoricCalibration {
  std::vector<float> weights;       // w_ij = ρ_ij ω_ij per bond (CSR order): g_ij = B_i w_ij
  std::vector<double> residual;     // per particle: max |eig(T_i^-½ A_i T_i^-½) − 1|
  std::vector<DeviatoricRow> rows;  // per particle
  int exact_rows = 0;               // residual ≤ kExactDeviatoricResidual
  int fallback_rows = 0;            // rows with ρ ≡ 1
  double largest_residual = 0;
};

// w_ij = fl(ρ_ij ω_ij) for every bond from the model's single-precision ω, with B_i = 15μ_i/m_i (0
// where m_i = 0) and the target T_i = 2μ_i shape_of_body[particles.body[i]] (μ_i > 0). The residual
// is the largest relative error of the deviatoric energy over all small homogeneous strains,
// computed from the rounded w (g = B_i w). Throws std::invalid_argument if a body has no shape or
// its shape is not symmetric positive definite. Over several ranks the own rows only
// (Families::first_own_row), and the counts are theirs: the ghosts' w come from their ranks.
DeviatoricCalibration deviatoric_weights(const Particles& particles, const Families& families,
                                         const std::vector<float>& omega,
                                         const std::vector<double>& shear_modulus,
                                         const std::vector<double>& weighted_volume,
                                         const std::vector<DeviatoricShape>& shape_of_body);

}  // namespace fissure
