#pragma once
// The default elastic model: the paper's §4.1 with Λ dropped from Eqs 4, 6, 8, the weighted
// volume m_i summed over each particle's actual family (linear peridynamic solid; notes §6), and
// optionally the dilatation calibrated per particle so that it is exact near surfaces
// (dilatation_calibration.hpp). Energy (per particle i, ê = e − θ_i|ξ|/3):
//   W_i = ½κθ_i² + 15μ/(2m_i) Σ_j ω_ij ê_ij² V_j,   θ_i = Σ_j c_ij e_ij V_j.
#include "model/model.hpp"

namespace fissure {

class LpsModel final : public Model {
 public:
  LpsModel(const Particles& particles, const Families& families, MaterialPoints materials,
           bool surface_correction);
  std::string name() const override { return "lps"; }
  void forces(const double* y, double* f) override;
  void energy_density(const double* y, double* w) override;
  double stable_time_step() const override;
  std::size_t bytes_per_bond() const override;
  std::size_t bytes_read_per_bond() const override;
  void break_bond(std::size_t b) override;

 private:
  void compute_dilatation(const double* y);

  // Per bond, single precision: the same rounded value serves both rows of a pair, so
  // action equals reaction exactly; V_j is applied in double precision in the kernels.
  std::vector<float> bond_omega_;           // ω_ij (Eq 5)
  std::vector<float> bond_weight_;          // c_ij
  std::vector<float> bond_reverse_weight_;  // c_ji, the weight of the same bond in j's row
  std::vector<double> weighted_volume_;     // m_i = Σ_j ω_ij |ξ_ij|² V_j
  std::vector<double> deviatoric_coef_;     // B_i = 15μ_i / m_i
  std::vector<double> pressure_term_;  // D_i = κθ_i − (B_i/3) Σ_j ω ê |ξ| V_j, per force call
  std::vector<double> shift_term_;     // B_i θ_i / 3, per force call
};

}  // namespace fissure
