#pragma once
// Stable explicit step from Gershgorin's bound on the bond-wise majoriser of the stiffness
// (notes model.md §3–4, Silling–Askari form): Δt ≤ min_i sqrt(2ρ_i / Σ_j C_ij V_j).
#include <vector>

#include "model/model.hpp"

namespace fissure {

// The model's bond constants: b_i per particle, and per directed bond ω_ij and c_ij, with
// θ_i = Σ_j c_ij e_ij V_j (c_ji is read through Families::reverse).
struct BondConstants {
  const std::vector<double>& b;
  const std::vector<double>& omega;
  const std::vector<double>& c;
};

double gershgorin_time_step(const Particles& particles, const Families& families,
                            const MaterialPoints& materials, const BondConstants& constants);

}  // namespace fissure
