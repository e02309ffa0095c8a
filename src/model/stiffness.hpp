#pragma once
// An optional capability of a model (Model::stiffness()): its stiffness for implicit
// integrators (notes §3), with e^p frozen. A model without it gives no implicit step.
#include <vector>

namespace fissure {

struct Families;
struct SparseSymmetric;  // linear/sparse_symmetric.hpp

class Stiffness {
 public:
  virtual ~Stiffness() = default;
  // Into a matrix of the pattern linear/sparse_symmetric.hpp names: the PSD bond-wise majoriser
  // K^bw ⪰ K (bond_pattern) and the exact tangent K = ∂²Π/∂y² (two_hop_pattern). The tangent's
  // material part is PSD (the energy is a sum of squares of extensions); only the geometric term
  // of compressed bonds is indefinite, so with clamp_compression it is dropped, which gives a
  // PSD matrix K⁺ ⪰ K on the tangent's pattern.
  virtual void assemble_majoriser(const double* y, SparseSymmetric& K) = 0;
  virtual void assemble_tangent(const double* y, SparseSymmetric& K, bool clamp_compression) = 0;
  // The majoriser's bond terms on the bonds `kept` flags (linear/nearest_bonds.hpp) only, into
  // nearest_bond_pattern(families, kept): each kept bond's block scaled by the mean over its two
  // ends of s_i = Σ_j h_ij |ξ_ij|² / Σ_kept h_ij |ξ_ij|² (h a bond's majoriser stiffness), so
  // that each row keeps its family's second moment of stiffness, which sets the moduli that
  // long waves and bending see. PSD, but not a bound on K: for preconditioners only. With every
  // bond kept it is the majoriser.
  virtual void assemble_nearest_stiffness(const double* y, const std::vector<char>& kept,
                                          SparseSymmetric& K) = 0;
  // The same tangent without assembly (matrix-free): linearize() records what K (or K⁺ with
  // clamp_compression) at y needs, apply_tangent() then returns out = K v for any v (3N each),
  // equal to assemble_tangent's matrix times v up to round-off, at about the cost of one force
  // evaluation per product. What linearize() records is the only state between the two.
  virtual void linearize(const double* y, bool clamp_compression) = 0;
  virtual void apply_tangent(const double* v, double* out) const = 0;
  // A one-hop scalar stiffness at the reference state, N×N on scalar_bond_pattern: a graph
  // Laplacian whose bond weights are a third of the majoriser's bond stiffness (so that L ⊗ I₃
  // has the majoriser's trace at rest), for preconditioners that scale to large scenes.
  virtual void assemble_scalar_stiffness(SparseSymmetric& L) const = 0;
  // The pattern assemble_tangent fills: two_hop_pattern(families) where each row's energy reads
  // its family's members only, wider where it reads more (the second-order model's images move
  // with their stencils' particles).
  virtual SparseSymmetric tangent_pattern(const Families& families) const;
  // Whether the one-hop matrices (assemble_majoriser, assemble_nearest_stiffness,
  // assemble_scalar_stiffness) exist; without them implicit steps factor the tangent only.
  virtual bool one_hop_matrices() const { return true; }
  // Over several ranks (Model::distribute) the majoriser, the nearest stiffness and the
  // matrix-free tangent are evaluated on this rank's rows only (the matrix's other rows zero,
  // out's left as they are), y's and v's ghosts must be current, and each call is
  // collective; the two-hop tangent, whose rows reach two families, is not available.
};

}  // namespace fissure
