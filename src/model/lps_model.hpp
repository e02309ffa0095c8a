#pragma once
// The default elastic model: the paper's §4.1 with Λ dropped from Eqs 4, 6, 8 and the weighted
// volume m_i calibrated on each particle's actual family (linear peridynamic solid; notes §6).
#include "model/model.hpp"

namespace fissure {

class LpsModel final : public Model {
 public:
  LpsModel(const Particles& particles, const Families& families, MaterialPoints materials);
  std::string name() const override { return "lps"; }
  void forces(const double* y, double* f) override;
  void energy_density(const double* y, double* w) override;
  double stable_time_step() const override;
  std::size_t bytes_per_bond() const override;

  const std::vector<double>& weighted_volume() const { return weighted_volume_; }

 private:
  void compute_dilatation(const double* y);

  std::vector<double> omega_volume_;     // ω_ij V_j per bond (Eq 5 times V_j)
  std::vector<double> weighted_volume_;  // m_i = Σ_j ω_ij |ξ_ij|² V_j
  std::vector<double> deviatoric_coef_;  // 15μ_i / m_i
  std::vector<double> dilatation_coef_;  // (3κ_i − 5μ_i) / m_i
  std::vector<double> dilatation_term_;  // θ_i (3κ_i − 5μ_i) / m_i, per force call
};

}  // namespace fissure
