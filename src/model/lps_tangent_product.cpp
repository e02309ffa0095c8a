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
// each parallel over particles without atomics: P, Q per family, then the rows. Over several
// ranks both run over the own rows: v's ghosts must be current, and the ghosts' X, Y, γ and V
// come from their ranks between the passes.
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
  tangent_nx_.resize(bonds);
  tangent_ny_.resize(bonds);
  tangent_nz_.resize(bonds);
  tangent_geometric_.resize(bonds);
  tangent_alpha_.resize(n);
  tangent_terms_.resize(n);
#pragma omp parallel for schedule(static)
  for (int i = row_begin_; i < row_end_; ++i) {
    for (int b = off[i]; b < off[i + 1]; ++b) {
      const auto g = bond_geometry(y, particles_, i, nbr[b], xi[b]);
      const double p = g.length > 0 ? pair_force(i, b, g.length) : 0.0;
      tangent_nx_[b] = g.n[0];
      tangent_ny_[b] = g.n[1];
      tangent_nz_[b] = g.n[2];
      tangent_geometric_[b] =
          (clamp_compression ? std::max(p, 0.0) : p) / std::max(g.length, 1e-300);
    }
    const double B = terms_[i].deviatoric;
    tangent_alpha_[i] = V[i] * (materials_.bulk_modulus[i] + B * weighted_volume_[i] / 9.0);
    tangent_terms_[i] = {0.0, 0.0, V[i] * B / 3.0, V[i]};
  }
}

// After linearize(); one product at a time (the scratch is the model's).
void LpsModel::apply_tangent(const double* v, double* out) const {
  const int* off = families_.offsets.data();
  const int* nbr = families_.neighbors.data();
  const double* xi = families_.reference_length.data();
  const float* w = bond_deviatoric_.data();
  const float* w_reverse = reverse_deviatoric();
  const float* c = bond_weight_.data();
  const float* c_reverse = bond_reverse_weight_.data();
  const double* V = particles_.volume.data();
  const double* nx = tangent_nx_.data();
  const double* ny = tangent_ny_.data();
  const double* nz = tangent_nz_.data();
  const double* g = tangent_geometric_.data();
  const double* alpha = tangent_alpha_.data();
  TangentTerms* terms = tangent_terms_.data();
  // Pass 1: P_i, Q_i into X_i, Y_i.
#pragma omp parallel for schedule(static)
  for (int i = row_begin_; i < row_end_; ++i) {
    const double vi0 = v[3 * i], vi1 = v[3 * i + 1], vi2 = v[3 * i + 2];
    double P = 0, Q = 0;
    for (int b = off[i]; b < off[i + 1]; ++b) {
      const int j = nbr[b];
      const double* vj = v + 3 * j;
      const double s = nx[b] * (vj[0] - vi0) + ny[b] * (vj[1] - vi1) + nz[b] * (vj[2] - vi2);
      const double sV = s * V[j];
      P += c[b] * sV;
      Q += w[b] * xi[b] * sV;
    }
    const double gamma = terms[i].gamma;
    terms[i].x = alpha[i] * P - gamma * Q;
    terms[i].y = gamma * P;
  }
  static_assert(sizeof(TangentTerms) == 4 * sizeof(double));
  if (halo_) halo_->fill(reinterpret_cast<double*>(terms), 4);
  // Pass 2: the rows, s_b recomputed from the members' v it gathers anyway (as in pass 1, so the
  // same bits): cheaper than storing and reading it back, since the product is bandwidth-bound.
#pragma omp parallel for schedule(static)
  for (int r = row_begin_; r < row_end_; ++r) {
    const double vr0 = v[3 * r], vr1 = v[3 * r + 1], vr2 = v[3 * r + 2];
    const TangentTerms tr = terms[r];
    double o0 = 0, o1 = 0, o2 = 0;
    for (int b = off[r]; b < off[r + 1]; ++b) {
      const int i = nbr[b];
      const double* vi = v + 3 * i;
      const TangentTerms& ti = terms[i];
      const double s = nx[b] * (vi[0] - vr0) + ny[b] * (vi[1] - vr1) + nz[b] * (vi[2] - vr2);
      const double t_own = ti.volume * (c[b] * tr.x + w[b] * (3.0 * tr.gamma * s - xi[b] * tr.y));
      const double t_member =
          tr.volume * (c_reverse[b] * ti.x + w_reverse[b] * (3.0 * ti.gamma * s - xi[b] * ti.y));
      const double along = g[b] * s - t_own - t_member;
      o0 += along * nx[b] + g[b] * (vr0 - vi[0]);
      o1 += along * ny[b] + g[b] * (vr1 - vi[1]);
      o2 += along * nz[b] + g[b] * (vr2 - vi[2]);
    }
    out[3 * r] = o0;
    out[3 * r + 1] = o1;
    out[3 * r + 2] = o2;
  }
}

}  // namespace fissure
