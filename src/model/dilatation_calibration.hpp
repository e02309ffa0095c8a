#pragma once
// Calibrated dilatation weights (a deviation from the paper, docs/model.md).
//
// The LPS dilatation θ_i = 3/m_i Σ_j ω|ξ| e V_j equals tr ε under a homogeneous strain ε only if
// the family's moment tensor Σ_j ω|ξ|² V_j ξ̂⊗ξ̂ is isotropic. Near a surface or on an irregular
// family it is not, so θ picks up the wrong strain components and thin parts come out too stiff.
// With per-bond weights c_ij = ω_ij |ξ_ij| ξ̂ᵀK_i ξ̂, θ_i = Σ_j c_ij e_ij V_j is exact for every
// small homogeneous strain when K_i solves the 6×6 system
//   Σ_j ω|ξ|²V_j (φ_j·K_i) φ_j = (1, 1, 1, 0, 0, 0),  φ = (u1², u2², u3², 2u1u2, 2u1u3, 2u2u3),
// K_i in the order (K11, K22, K33, K12, K13, K23). On a full isotropic family K_i = 3/m_i I, the
// plain LPS weight.
#include <vector>

#include "scene/particles.hpp"

namespace fissure {

// c_ij per bond (CSR order), rounded to single precision as the model keeps them, from the
// model's single-precision ω. Falls back to 3ω|ξ|/m_i for a family too small or too flat to
// determine K_i. Over several ranks the own rows only (Families::first_own_row): the ghosts' come
// from their ranks (LpsModel::distribute), 0 until then.
std::vector<float> dilatation_weights(const Particles& particles, const Families& families,
                                      const std::vector<float>& omega,
                                      const std::vector<double>& weighted_volume);

// An isotropic body's plain influence ω = δ/|ξ| (Eq 5, single precision as the model keeps it),
// m_i = Σ_j ω |ξ|² V_j, and the dilatation weights c over them, for every row of `families`.
struct FamilyWeights {
  std::vector<float> omega, dilatation;
  std::vector<double> weighted_volume;
};
FamilyWeights isotropic_family_weights(const Particles& particles, const Families& families,
                                       const std::vector<double>& horizon_of_body);

}  // namespace fissure
