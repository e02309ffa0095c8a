// The exact tangent of the LPS model without assembly (notes §3, §6): out = K v, K as in
// assemble_tangent (lps_stiffness.cpp), K⁺ with clamp_compression.
//
// With s_b = n_b·(v_j − v_i) the extension rate of bond b (i → j), the material part of family i
// is V_i J_iᵀ H_i s, whose bond b component is, with c̄_b = c_ij V_j, w_b = w_ij V_j |ξ_b| (w_ij
// the row's deviatoric weight), P_i = Σ_b c̄_b s_b and Q_i = Σ_b w_b s_b,
//   t_b = V_i [(κ_i + B_i M_i/9) c̄_b P_i + B_i w_ij V_j s_b − (B_i/3)(c̄_b Q_i + w_b P_i)]
//       = V_j [c_ij X_i + w_ij (3γ_i s_b − |ξ_b| Y_i)],
//   X_i = α_i P_i − γ_i Q_i,  Y_i = γ_i P_i,  α_i = V_i (κ_i + B_i M_i/9),  γ_i = V_i B_i/3,
// and J_iᵀ puts −t_b n_b on i and +t_b n_b on j. The geometric term of each pair adds
// g_b (I − n nᵀ)(v_i − v_j) to row i, g_b = p_b/ℓ_b (pair_force; p⁺ = max(p, 0) with
// clamp_compression). Row r gathers its own family's t_b and, for each member i (bond q, r → i),
// family i's t for the bond i → r, whose direction is −n_q and rate s_q, with c_ir =
// bond_reverse_weight_[q] and w_ir = reverse_deviatoric()[q]: (K v)_r = Σ_q [(g_q s_q − t_rq −
// t_ir) n_q + g_q (v_r − v_i)]. Two passes over the bonds as compute_dilatation and compute_forces,
// each parallel over particles without atomics: P, Q per family, then the rows, each row by the
// row kernels (lps_rows.hpp) the forces use, which recompute n from the linearization point
// instead of reading it: 56 bytes streamed per bond and product instead of 104. Over several
// ranks both run over the own rows: y's and v's ghosts must be current, and the ghosts' X, Y, γ
// and V come from their ranks between the passes.
#include <algorithm>

#include "model/lps_bond_geometry.hpp"
#include "model/lps_model.hpp"
#include "parallel/halo.hpp"

namespace fissure {

void LpsModel::linearize(const double* y, bool clamp_compression) {
  update_dilatation(y);  // terms_ for pair_force
  const int n = particles_.count();
  const std::size_t bonds = families_.directed_bonds();
  const auto& off = families_.offsets;
  const auto& nbr = families_.neighbors;
  const auto& xi = families_.reference_length;
  const auto& V = particles_.volume;
  tangent_y_.assign(y, y + 3 * static_cast<std::size_t>(n));
  tangent_geometric_.resize(bonds);
  tangent_alpha_.resize(n);
  tangent_terms_.resize(n);
#pragma omp parallel for schedule(static)
  for (int i = row_begin_; i < row_end_; ++i) {
    for (int b = off[i]; b < off[i + 1]; ++b) {
      const double length = bond_geometry(y, particles_, i, nbr[b], xi[b]).length;
      const double p = length > 0 ? pair_force(i, b, length) : 0.0;
      tangent_geometric_[b] = (clamp_compression ? std::max(p, 0.0) : p) / std::max(length, 1e-300);
    }
    const double B = terms_[i].deviatoric;
    tangent_alpha_[i] = V[i] * (materials_.bulk_modulus[i] + B * weighted_volume_[i] / 9.0);
    tangent_terms_[i] = {0.0, 0.0, V[i] * B / 3.0, V[i]};
  }
}

// After linearize(); one product at a time (the scratch is the model's).
void LpsModel::apply_tangent(const double* v, double* out) const {
  const double* alpha = tangent_alpha_.data();
  lps::TangentTerms* terms = tangent_terms_.data();
  const lps::TangentRowInput point{nullptr,
                                   0,
                                   tangent_y_.data(),
                                   particles_.reference.data(),
                                   v,
                                   particles_.volume.data(),
                                   terms,
                                   tangent_geometric_.data()};
  // Pass 1: P_i, Q_i into X_i, Y_i.
#pragma omp parallel for schedule(static)
  for (int i = row_begin_; i < row_end_; ++i) {
    const lps::BondRow row = bond_row(i);
    lps::TangentRowInput in = point;
    in.row = &row;
    in.i = i;
    const lps::TangentSums sums = kernels_.tangent_sums(in);
    const double gamma = terms[i].gamma;
    terms[i].x = alpha[i] * sums.P - gamma * sums.Q;
    terms[i].y = gamma * sums.P;
  }
  static_assert(sizeof(lps::TangentTerms) == 4 * sizeof(double));
  if (halo_) halo_->fill(reinterpret_cast<double*>(terms), 4);
    // Pass 2: the rows, n_b and s_b recomputed as in pass 1 (the same bits): cheaper than storing
    // and reading them back, since the product is bandwidth-bound.
#pragma omp parallel for schedule(static)
  for (int r = row_begin_; r < row_end_; ++r) {
    const lps::BondRow row = bond_row(r);
    lps::TangentRowInput in = point;
    in.row = &row;
    in.i = r;
    kernels_.tangent(in, out + 3 * r);
  }
}

}  // namespace fissure
