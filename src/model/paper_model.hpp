#pragma once
// The paper's literal isotropic model, Eqs 3–10, with Λ = n·ξ/|ξ| in Eqs 4, 6 and 8 and the
// continuum constants a, b, 9/(4πδ⁴). Kept to show why the default model deviates (docs/model.md):
// it is neither objective nor conservative, and its moduli depend on the particle set.
#include "model/model_registry.hpp"

namespace fissure {

class PaperModel final : public Model {
 public:
  PaperModel(const Particles& particles, const Families& families, MaterialPoints materials);
  std::string name() const override { return "paper"; }
  void forces(const double* y, double* f) override;
  // The energy whose gradient the forces are when Λ = 1 (notes §3): W_i = αθ_i² +
  // b Σ_j ω_ij e_ij² V_j with θ_i = 9/(4πδ⁴) Σ_j ω_ij e_ij V_j and α = ½(κ − 5μ/3).
  void energy_density(const double* y, double* w) override;
  // θ_i = 9/(4πδ⁴) Σ_k ω_ik s_ik (n·ξ) V_k (Eq 6), s = ℓ/|ξ| − 1 (Eq 7).
  void dilatation(const double* y, double* theta) const override;
  double stable_time_step() const override;
  std::size_t bytes_per_bond() const override;
  std::size_t bytes_read_per_bond() const override;
  void break_bond(int i, std::size_t b) override;
  bool bond_intact(std::size_t b) const override { return omega_[b] != 0; }

 private:
  std::vector<double> omega_;       // ω_ij = δ/|ξ| (Eq 5)
  std::vector<double> a_, b_;       // a and b of Eq 10 per particle
  std::vector<double> dilatation_;  // θ_i, scratch of forces()
};

// material.model: paper; it refuses material.plasticity.
ModelKind paper_model_kind();

}  // namespace fissure
