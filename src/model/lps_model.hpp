#pragma once
// The default elastic model: the paper's §4.1 with Λ dropped from Eqs 4, 6, 8, the weighted
// volume m_i summed over each particle's actual family (linear peridynamic solid; notes §6), and
// optionally (material.surface_correction) the dilatation calibrated per particle so that it is
// exact near surfaces (dilatation_calibration.hpp), and the deviatoric weights so that every
// small homogeneous strain gives the continuum's energy (deviatoric_calibration.hpp). Energy (per
// particle i, ê = e − e^p − (θ_i − θ^p_i)|ξ|/3):
//   W_i = ½κθ_i² + ½B_i Σ_j w_ij ê_ij² V_j,   B_i = 15μ_i/m_i,   θ_i = Σ_j c_ij e_ij V_j,
// with w_ij = ρ_ij ω_ij (ρ ≡ 1 without the deviatoric calibration) and the plastic extensions
// e^p (§4.2) held fixed between steps.
#include <cstdint>
#include <utility>

#include "model/lps_rows.hpp"
#include "model/model_registry.hpp"
#include "model/plastic_flow.hpp"
#include "model/stiffness.hpp"
#include "parallel/halo.hpp"
#include "scene/config.hpp"

namespace fissure {

class LpsModel final : public Model, public Stiffness, public PlasticFlow {
 public:
  LpsModel(const Particles& particles, const Families& families, MaterialPoints materials,
           SurfaceCorrection surface_correction, const PlasticPoints* plasticity);
  std::string name() const override { return "lps"; }
  void forces(const double* y, double* f) override;
  void energy_density(const double* y, double* w) override;
  void dilatation(const double* y, double* theta) const override;
  double stable_time_step() const override;
  std::size_t bytes_per_bond() const override;
  std::size_t bytes_read_per_bond() const override;
  void break_bond(int i, std::size_t b) override;
  bool bond_intact(std::size_t b) const override { return bond_deviatoric_[b] != 0; }
  Stiffness* stiffness() override { return this; }
  const Stiffness* stiffness() const override { return this; }
  PlasticFlow* plastic_flow() override { return plastic_ ? this : nullptr; }
  const PlasticFlow* plastic_flow() const override { return plastic_ ? this : nullptr; }
  std::size_t update_plasticity(const double* y) override;
  const std::vector<double>& plastic_extension() const override { return plastic_extension_; }
  NamedArrays saved_state() const override;
  void restore_state(const NamedArrays& state) override;
  bool per_bond_state(const std::string& name) const override {
    return name == "model.plastic_extension";
  }
  void assemble_majoriser(const double* y, SparseSymmetric& K) override;
  void assemble_tangent(const double* y, SparseSymmetric& K, bool clamp_compression) override;
  void assemble_nearest_stiffness(const double* y, const std::vector<char>& kept,
                                  SparseSymmetric& K) override;
  void linearize(const double* y, bool clamp_compression) override;
  void apply_tangent(const double* v, double* out) const override;
  void assemble_scalar_stiffness(SparseSymmetric& L) const override;
  double forces_and_energy(const double* y, double* f) override;
  double rows_energy(const double* y, const std::vector<int>& rows) override;
  // With surface_correction: full, what the deviatoric calibration reached; else empty.
  std::vector<std::pair<std::string, double>> statistics() const override { return statistics_; }
  void distribute(const Halo& halo) override;

 private:
  // Rows [begin, end) of θ and of the force terms.
  template <bool Plastic>
  void compute_dilatation(const double* y, int begin, int end);
  // θ_i and row i's force terms from θ_i, θ_i − θ^p_i and Σ_j w (e − e^p)|ξ| V_j.
  void set_terms(int i, double theta, double elastic_theta, double moment);
  // With plasticity: whether dilatation_ and terms_ hold compute_dilatation<true>(y) at this
  // revision (the return map leaves them so for the positions it ran at), and remembering that.
  bool plastic_terms_current(const double* y) const;
  void remember_plastic_terms(const double* y);
  // With Energy, also V_i W_i into energy[i] (as energy_density); without, energy is not read and
  // the force kernel is the plain one.
  template <bool Plastic, bool Energy>
  void compute_forces(const double* y, double* f, double* energy);
  // The force pass of a row with plastic extensions: force[0..2] and, with squares, Σ w ê² V_j.
  void plastic_force_row(const lps::BondRow& row, int i, const double* y, double elastic_theta,
                         double force[3], double* squares) const;
  void update_dilatation(const double* y);
  // assemble_majoriser (kept == nullptr) and assemble_nearest_stiffness (lps_stiffness.cpp).
  void assemble_bond_blocks(const double* y, const std::vector<char>* kept, SparseSymmetric& K);
  // The majoriser stiffness h_ij row i gives bond b (lps_stiffness.cpp), a bond's stiffness being
  // h_ij + h_ji: from row i's factors a_i Σ|c̄| and q_i Σ|r| (majoriser_rows(), per particle, so
  // that no per-bond array is needed) and the bond's c̄_ij and r_ij (majoriser_weights()).
  struct MajoriserRow {
    double a_sum_c, q_sum_r;
  };
  std::vector<MajoriserRow> majoriser_rows() const;
  std::pair<double, double> majoriser_weights(int i, int b) const;
  double majoriser_bond_row(const std::vector<MajoriserRow>& rows, int i, int b) const;
  // h_ji of the same bond from row i's copies of row j's weights (lps_stiffness.cpp).
  double majoriser_reverse_row(const std::vector<MajoriserRow>& rows, int i, int b) const;
  // W_i at y with row i's dilatation θ_i (energy_density's sum).
  double row_energy(const double* y, int i, double theta) const;
  double pair_force(int i, std::size_t b, double length) const;
  void set_up_plasticity(const PlasticPoints& plasticity);
  // surface_correction: full: w = ρω from deviatoric_weights() and M_i over them.
  void calibrate_deviatoric_weights();
  // w_ji in row i's order: its own array with the deviatoric calibration, else w itself (ω is
  // the same in both rows of a pair).
  const float* reverse_deviatoric() const {
    return bond_reverse_deviatoric_.empty() ? bond_deviatoric_.data()
                                            : bond_reverse_deviatoric_.data();
  }

  // Per bond, single precision: the same rounded value serves both rows of a pair, so
  // action equals reaction exactly; V_j is applied in double precision in the kernels.
  std::vector<float> bond_deviatoric_;          // w_ij = ρ_ij ω_ij (ω of Eq 5, 17)
  std::vector<float> bond_reverse_deviatoric_;  // w_ji in row i's order; only when w ≠ ω
  std::vector<float> bond_weight_;              // c_ij
  std::vector<float> bond_reverse_weight_;      // c_ji, the weight of the same bond in j's row
  // M_i = Σ_j w_ij |ξ_ij|² V_j over the intact bonds (m_i of notes §6 while w = ω)
  std::vector<double> weighted_volume_;
  std::vector<std::pair<std::string, double>> statistics_;
  std::vector<double> dilatation_;  // θ_i, scratch of each evaluation at its y
  // What the force pass gathers from each neighbour j: pressure D_j = κθ_j − (B_j/3) Σ_k w ê |ξ|
  // V_k and shift B_j (θ_j − θ^p_j)/3 per force call, deviatoric B_j and volume V_j.
  using NeighbourTerms = lps::NeighbourTerms;
  std::vector<NeighbourTerms> terms_;
  // The rows forces() evaluates: all, or this rank's (distribute()), whose ghosts' terms the
  // halo fills between the two passes.
  int row_begin_ = 0, row_end_ = 0;
  const Halo* halo_ = nullptr;
  // The row passes this CPU runs (lps_rows.hpp), chosen at load.
  lps::RowKernels kernels_ = lps::row_kernels();
  lps::BondRow bond_row(int i) const;
  // Plasticity, allocated only when the scene asks for it (the elastic kernel never reads them).
  bool plastic_ = false;
  std::vector<double> plastic_extension_;          // e^p_ij per bond (Eq 11)
  std::vector<double> reverse_plastic_extension_;  // e^p_ji in row i's order, for the force pass
  // 1 where a bond of row i, in either direction, has flowed (e^p_ij or e^p_ji not +0): the force
  // pass reads e^p only there, elsewhere both are +0 and the elastic terms are the same bits.
  std::vector<std::uint8_t> plastic_row_;
  std::vector<double> plastic_dilatation_;   // θ^p_i = Σ_j c_ij e^p_ij V_j
  // Over several ranks: the pairs shared with other ranks, whose e^p_ji the return map brings
  // from row j's rank (share_plastic_extensions()).
  const SharedBonds* shared_ = nullptr;
  std::size_t share_plastic_extensions(std::size_t yielded);
  // Over several ranks with split families: the ghosts' set-up values from their ranks.
  void take_ghosts_set_up();
  std::vector<double> yield_force_;          // A^c_i = √(2Ψ0) (Eq 14)
  std::vector<double> max_plastic_stretch_;  // γ / |ξ| (Eq 16, Table 1)
  std::vector<double> energy_;               // V_i W_i, scratch of forces_and_energy
  // The positions and model revision dilatation_ and terms_ were last computed at, with
  // plasticity: the return map computes them for the state the next evaluation starts from.
  std::vector<double> plastic_terms_y_;
  std::size_t plastic_terms_revision_ = 0;
  // Matrix-free tangent (lps_tangent_product.cpp), recorded by linearize(): the linearization
  // point y (the row kernels recompute each bond's direction from it) and per directed bond the
  // geometric stiffness g = p/ℓ (p⁺/ℓ with clamp_compression).
  std::vector<double> tangent_y_, tangent_geometric_;
  std::vector<double> tangent_alpha_;  // V_i (κ_i + B_i m_i/9), per particle
  // What the product's second pass gathers from each neighbour: X_i = α_i P_i − γ_i Q_i and
  // Y_i = γ_i P_i per product, γ_i = V_i B_i/3 and V_i from linearize().
  mutable std::vector<lps::TangentTerms> tangent_terms_;
};

// material.model: lps (the default), no options of its own; plastic with material.plasticity.
ModelKind lps_model_kind();

}  // namespace fissure
