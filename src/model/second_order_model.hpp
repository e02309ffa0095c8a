#pragma once
// The second-order LPS model with fictitious particles (docs/model.md, deviation 8):
// every family near a surface completed by mirror images of the particles across it
// (fictitious_particles.hpp), both calibrations run over the completed families, and each row's
// energy that of second_order_row.hpp: the LPS energy of its bonds less their fitted curvature,
// plus its cell's share of the strain gradient, plus a stabilisation of what the row's fit
// leaves of each bond. Every displacement quadratic in x then stores the continuum's energy of
// the cells, so that a beam's bending stiffness is exact at any resolution
// (bench_fictitious_particles: 1.0000 in pure bending at 2, 3 and 4 tets through the
// thickness), and the stabilisation keeps the particles from relaxing away from such fields
// under load (`equilibrium` in the same bench).
//
// material.surface_correction: fictitious. A clamp is a clamped face (constraints: {clamp: ...}),
// whose images continue the field through it: a held block behind the clamp face makes the
// clamp soft (+9% tip deflection at 2 tets; docs/model.md). Elastic and isotropic, on one rank;
// its stiffness is the tangent alone (second_order_stiffness.cpp), no fracture, no plasticity.
#include <array>
#include <memory>
#include <vector>

#include "model/fictitious_particles.hpp"
#include "model/model.hpp"
#include "model/quadratic_fit.hpp"
#include "model/second_order_row.hpp"
#include "model/stiffness.hpp"

namespace fissure {

class SecondOrderModel final : public Model, public Stiffness {
 public:
  // `images` with their stencils (fit_stencils), cell_moment M_i per particle (xx, yy, zz, xy,
  // xz, yz; tet_geometry.hpp), the rows' stabilisation α (second_order_row.hpp). Throws
  // std::invalid_argument naming the particle whose family does not determine a quadratic.
  SecondOrderModel(const Particles& particles, const Families& families, MaterialPoints materials,
                   const std::vector<double>& horizon_of_body, FictitiousParticles images,
                   std::vector<std::array<double, 6>> cell_moment,
                   double stabilization = kSecondOrderStabilization);
  std::string name() const override { return "lps"; }
  void forces(const double* y, double* f) override { forces_and_energy(y, f); }
  double forces_and_energy(const double* y, double* f) override;
  void energy_density(const double* y, double* w) override;
  void dilatation(const double* y, double* theta) const override;
  double stable_time_step() const override { return stable_time_step_; }
  // Fracture is not available with this model: nothing calls these with a bond to break.
  void break_bond(int i, std::size_t b) override;
  bool bond_intact(std::size_t) const override { return true; }
  std::size_t bytes_per_bond() const override;
  std::size_t bytes_read_per_bond() const override;
  std::vector<std::pair<std::string, double>> statistics() const override { return statistics_; }
  void distribute(const Halo& halo) override;

  // The stiffness (second_order_stiffness.cpp): the tangent folded onto the particles,
  // K = Σ_i P_iᵀ H_i P_i over each row's Hessian H_i and the map P_i from the particles'
  // displacements to its bonds (an image's bond through its stencil). The tangent is exact at y;
  // clamp_compression changes nothing (its material and cell parts are PSD, its geometric part
  // is left in). No one-hop matrices: their calls throw std::logic_error.
  Stiffness* stiffness() override { return this; }
  const Stiffness* stiffness() const override { return this; }
  void assemble_tangent(const double* y, SparseSymmetric& K, bool clamp_compression) override;
  void linearize(const double* y, bool clamp_compression) override;
  void apply_tangent(const double* v, double* out) const override;
  SparseSymmetric tangent_pattern(const Families& families) const override;
  bool one_hop_matrices() const override { return false; }
  void assemble_majoriser(const double* y, SparseSymmetric& K) override;
  void assemble_nearest_stiffness(const double* y, const std::vector<char>& kept,
                                  SparseSymmetric& K) override;
  void assemble_scalar_stiffness(SparseSymmetric& L) const override;

  // The particles followed by the images, and the families over them (rows of the images last).
  const Particles& extended_particles() const { return extended_; }
  const Families& extended_families() const { return extended_families_; }
  const FictitiousParticles& images() const { return images_; }
  // The images' positions y_g = x_g + Σ_s w_gs (y_s − x_s) after the particles' y: 3 per
  // particle of extended_particles().
  void extended_positions(const double* y, std::vector<double>& extended) const;

 private:
  SecondOrderRow row(int i) const;
  // Row i's bond vectors d_b = y_j − y_i at the extended positions y, 3 per bond, into d.
  void bond_vectors(int i, const double* y, double* d) const;
  // Row i's energy (and its gradient over d_b = y_j − y_i, with dilatation θ_i) at the extended
  // positions; d and gradient are scratch of 3 × its bonds.
  double row_energy(int i, const double* y, double* d, double* gradient, double* theta) const;
  // 2/√λ with λ ≥ λmax(M⁻¹K) at the reference state: Gershgorin's row sums bounded through
  // |Pᵀ H P| ≤ |P|ᵀ|H||P| over each row's Hessian H and its map P from the particles'
  // displacements to its bonds (stencils included), so that nothing is assembled.
  double reference_time_step() const;
  // Row i's bonds as maps of the particles' displacements: bond b's d_b moves by
  // Σ_k coefficient[k] u_{touched[local[k]]} over k in [bond_offsets[b], bond_offsets[b + 1]),
  // `touched` sorted, i among them.
  struct FoldedRow {
    std::vector<int> touched, bond_offsets, local;
    std::vector<double> coefficient;
  };
  void fold_row(int i, FoldedRow& row) const;

  FictitiousParticles images_;
  Particles extended_;
  Families extended_families_;
  // per bond of the particles' rows (the first rows of extended_families_), in CSR order
  std::vector<double> xi_, dilatation_weight_, deviatoric_weight_, member_volume_;
  std::vector<QuadraticBasis> fit_;
  std::vector<double> scale_, deviatoric_modulus_;  // s = δ and B_i = 15μ_i/m_i per particle
  std::vector<std::array<double, 6>> cell_moment_;
  double stabilization_;
  double stable_time_step_ = 0;
  std::vector<std::pair<std::string, double>> statistics_;
  // scratch: the extended positions, and per thread the forces on every extended particle
  mutable std::vector<double> positions_;
  std::vector<double> linearized_at_;  // linearize()'s extended positions
  std::vector<std::vector<double>> thread_forces_;
  int largest_row_ = 0;
};

// The model for a scene whose bodies are all tet-sampled and keep their tet meshes
// (Scene::tet_meshes): images of each body's particles across its boundary triangles, their
// stencils fitted within fit_radius horizons (clamp_stencils behind each clamped face of the
// scene's constraints), and each particle's tet as its cell. Throws std::invalid_argument when a
// body has no tet mesh.
std::unique_ptr<SecondOrderModel> make_second_order_model(
    const Scene& scene, MaterialPoints m, double fit_radius = 1.5,
    double stabilization = kSecondOrderStabilization);

}  // namespace fissure
