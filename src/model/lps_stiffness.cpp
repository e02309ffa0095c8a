// Bond-wise stiffness of the LPS model (notes §3, §6): the exact tangent K = ∂²Π/∂y² with e^p
// frozen, and a positive semidefinite bond-wise majoriser K^bw ⪰ K for Newton's matrix.
//
// With ê = u − θ̃|ξ|/3, u = e − e^p, θ̃ = c̄ᵀu (c̄_j = c_ij V_j) and w_j = w_ij V_j |ξ_ij| (w_ij the
// row's deviatoric weight, ω_ij uncalibrated), the energy of particle i is a quadratic form in its
// bond extensions, W_i = ½ uᵀH_i u + …, with (M_i = Σ_j w_ij |ξ|² V_j, m_i while w = ω)
//   H_i = κ c̄c̄ᵀ + B_i [D − (c̄wᵀ + wc̄ᵀ)/3 + (M_i/9) c̄c̄ᵀ],   D = diag(w_ij V_j),
// and Π = Σ V_i W_i. The extension e_ij = |y_j − y_i| − |ξ| has gradient ±n and Hessian
// (I − nnᵀ)/ℓ, which gives the geometric term p (I − nnᵀ)/ℓ with p = V_i V_j (t_ij + t_ji).
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "linear/sparse_symmetric.hpp"
#include "model/lps_bond_geometry.hpp"
#include "model/lps_model.hpp"
#include "parallel/collective.hpp"
#include "parallel/halo.hpp"

namespace fissure {

namespace {

using Vec = std::array<double, 3>;

// K_b = k nnᵀ + g (I − nnᵀ): added to the diagonal block of row i, subtracted from block (i, j).
void scatter_bond(SparseSymmetric& K, int i, int self_block, int other_block, const Vec& n,
                  double k, double g) {
  for (int r = 0; r < 3; ++r) {
    const int row = K.offsets[3 * i + r];
    for (int c = 0; c < 3; ++c) {
      const double value = (k - g) * n[r] * n[c] + (r == c ? g : 0.0);
      K.values[row + 3 * self_block + c] += value;
      K.values[row + 3 * other_block + c] -= value;
    }
  }
}

}  // namespace

// p_ij = V_i V_j (t_ij + t_ji), the pair force scalar of compute_forces (after compute_dilatation).
double LpsModel::pair_force(int i, std::size_t b, double length) const {
  const int j = families_.neighbors[b];
  const NeighbourTerms& ti = terms_[i];
  const NeighbourTerms& tj = terms_[j];
  const double xi = families_.reference_length[b];
  const double e = length - xi, w_ij = bond_deviatoric_[b], w_ji = reverse_deviatoric()[b];
  const double ep_ij = plastic_ ? plastic_extension_[b] : 0.0;
  const double ep_ji = plastic_ ? plastic_extension_[families_.reverse[b]] : 0.0;
  const double deviatoric =
      bond_reverse_deviatoric_.empty()
          ? lps::pair_deviatoric<false>(e, xi, w_ij, w_ji, ti, tj, ep_ij, ep_ji)
          : lps::pair_deviatoric<true>(e, xi, w_ij, w_ji, ti, tj, ep_ij, ep_ji);
  const double t =
      bond_weight_[b] * ti.pressure + bond_reverse_weight_[b] * tj.pressure + deviatoric;
  return ti.volume * tj.volume * t;
}

// Notes §3, adapted to the calibrated weights: with r = c̄ − 3w/M_i (zero without calibration),
//   H_i = B_i D + (κ − B_i M_i/9) c̄c̄ᵀ + (B_i M_i/9)(c̄rᵀ + rc̄ᵀ)
//       ⪯ B_i D + a_i c̄c̄ᵀ + q_i rrᵀ,   a_i = max(0, κ − (1 − ε) B_i M_i/9),  q_i = B_i M_i/(9ε),
// for any ε in (0, 1] (c̄rᵀ + rc̄ᵀ ⪯ ε c̄c̄ᵀ + rrᵀ/ε; ε = |r|/|c̄| balances the two), and a rank-one
// aaᵀ ⪯ diag(Σ_k|a_k| |a_j|) by Cauchy–Schwarz. So each bond gets a stiffness along n, and the
// geometric term is clamped at max(p, 0): K^bw ⪰ K and K^bw ⪰ 0 (D ⪰ 0 as w ≥ 0: the deviatoric
// calibration keeps ρ ≥ ρ_min > 0).
// h_ij = V_i [B_i w_ij V_j + a_i S_c |c̄_ij| + q_i S_r |r_ij|], the stiffness row i gives bond b,
// for every directed bond: a bond's stiffness is h_ij + h_ji. A broken bond (w = c = 0) has
// c̄ = r = 0, so h = 0; it is set so explicitly, so that no 0·∞ of a degenerate family can give it
// a stiffness.
// Over several ranks the own rows, and the ghosts' from their ranks (another rank's row reflects
// the bonds broken there).
std::vector<LpsModel::MajoriserRow> LpsModel::majoriser_rows() const {
  const int n = particles_.count();
  const auto& off = families_.offsets;
  std::vector<MajoriserRow> rows(n);
#pragma omp parallel for schedule(static)
  for (int i = row_begin_; i < row_end_; ++i) {
    const double m = weighted_volume_[i], B = terms_[i].deviatoric;
    double sum_c = 0, sum_r = 0, norm_c = 0, norm_r = 0;
    for (int b = off[i]; b < off[i + 1]; ++b) {
      const auto [c, r] = majoriser_weights(i, b);
      sum_c += std::abs(c);
      sum_r += std::abs(r);
      norm_c += c * c;
      norm_r += r * r;
    }
    const double eps = norm_c > 0 ? std::min(1.0, std::sqrt(norm_r / norm_c)) : 1.0;
    const double a = std::max(0.0, materials_.bulk_modulus[i] - (1.0 - eps) * B * m / 9.0);
    const double q = eps > 0 ? B * m / (9.0 * eps) : 0.0;
    rows[i] = {a * sum_c, q * sum_r};
  }
  static_assert(sizeof(MajoriserRow) == 2 * sizeof(double));
  if (halo_) halo_->fill(reinterpret_cast<double*>(rows.data()), 2);
  return rows;
}

// c̄_ij and r_ij = c̄_ij − 3 w_ij |ξ_ij| V_j / M_i
std::pair<double, double> LpsModel::majoriser_weights(int i, int b) const {
  const double Vj = particles_.volume[families_.neighbors[b]], m = weighted_volume_[i];
  const double c = bond_weight_[b] * Vj;
  return {c, m > 0 ? c - 3.0 * bond_deviatoric_[b] * families_.reference_length[b] * Vj / m : 0.0};
}

// h_ji of bond b (in row i, to member j): majoriser_bond_row(rows, j, reverse[b]) from row i's
// copies of the pair's weights in row j (c_ji, w_ji, the same floats) and j's per-particle
// terms, without reading row j's bonds (over several ranks another rank's, stale there once
// bonds break). M_j must be current (the halo's, over several ranks).
double LpsModel::majoriser_reverse_row(const std::vector<MajoriserRow>& rows, int i, int b) const {
  const float w = reverse_deviatoric()[b];
  if (w == 0) return 0.0;
  const int j = families_.neighbors[b];
  const auto& V = particles_.volume;
  const double m = weighted_volume_[j];
  const double c = bond_reverse_weight_[b] * V[i];
  const double r = m > 0 ? c - 3.0 * w * families_.reference_length[b] * V[i] / m : 0.0;
  return V[j] * (terms_[j].deviatoric * w * V[i] + rows[j].a_sum_c * std::abs(c) +
                 rows[j].q_sum_r * std::abs(r));
}

double LpsModel::majoriser_bond_row(const std::vector<MajoriserRow>& rows, int i, int b) const {
  if (bond_deviatoric_[b] == 0) return 0.0;
  const auto [c, r] = majoriser_weights(i, b);
  const auto& V = particles_.volume;
  return V[i] * (terms_[i].deviatoric * bond_deviatoric_[b] * V[families_.neighbors[b]] +
                 rows[i].a_sum_c * std::abs(c) + rows[i].q_sum_r * std::abs(r));
}

// L(i, j) = −k_ij, L(i, i) = Σ_j k_ij with k_ij = (h_ij + h_ji)/3: the majoriser at rest, whose
// bond puts ±3k_ij n nᵀ in its blocks, with n nᵀ replaced by I₃/3 (the same trace), so that
// 3 tr L = tr K^bw. k is symmetric in the pair, so L is; a broken bond has h = 0 both ways.
void LpsModel::assemble_scalar_stiffness(SparseSymmetric& L) const {
  const std::vector<MajoriserRow> rows = majoriser_rows();
  const auto& off = families_.offsets;
#pragma omp parallel for schedule(static)
  for (int i = 0; i < particles_.count(); ++i) {
    // Row i of scalar_bond_pattern is {i} ∪ H_i sorted, H_i sorted: bond k of the row is entry
    // k, or k + 1 past i's own.
    const int first = L.offsets[i], self = self_position(families_, i);
    double diagonal = 0;
    for (int b = off[i]; b < off[i + 1]; ++b) {
      const double k = (majoriser_bond_row(rows, i, b) + majoriser_reverse_row(rows, i, b)) / 3.0;
      const int k_index = b - off[i];
      L.values[first + k_index + (k_index >= self ? 1 : 0)] = -k;
      diagonal += k;
    }
    L.values[first + self] = diagonal;
  }
}

// Gershgorin on S = M^-1/2 K^bw M^-1/2 at the reference state (no bond force, so no geometric
// term). A bond of stiffness k and direction n puts k n nᵀ in the blocks (i,i) and (j,j) and
// −k n nᵀ in (i,j). Two bounds on λ_max(S), both valid, the smaller taken: by blocks (norms
// ‖k n nᵀ‖ = k), Σ_j k_ij w_ij; by scalar rows (i, d), Σ_j k_ij w_ij |n_d| ‖n‖₁; with
// w_ij = 1/m_i + 1/√(m_i m_j). K ⪯ K^bw makes it a bound for the exact tangent too; symplectic
// Euler and Verlet are stable for dt < 2/√λ_max (notes §4). Over several ranks each rank bounds
// its own rows and the largest bounds over the ranks are taken: every rank gets one rank's value
// (collective there).
double LpsModel::stable_time_step() const {
  const std::vector<MajoriserRow> rows = majoriser_rows();
  const auto& off = families_.offsets;
  const auto& nbr = families_.neighbors;
  const auto& x = particles_.reference;
  const auto& mass = particles_.mass;
  double by_blocks = 0, by_rows = 0;
#pragma omp parallel for reduction(max : by_blocks, by_rows) schedule(static)
  for (int i = row_begin_; i < row_end_; ++i) {
    double block = 0, row[3] = {0, 0, 0};
    for (int b = off[i]; b < off[i + 1]; ++b) {
      const int j = nbr[b];
      const double xi = families_.reference_length[b];
      const double n[3] = {std::abs(x[3 * j] - x[3 * i]) / xi,
                           std::abs(x[3 * j + 1] - x[3 * i + 1]) / xi,
                           std::abs(x[3 * j + 2] - x[3 * i + 2]) / xi};
      const double k = (majoriser_bond_row(rows, i, b) + majoriser_reverse_row(rows, i, b)) *
                       (1.0 / mass[i] + 1.0 / std::sqrt(mass[i] * mass[j]));
      block += k;
      for (int d = 0; d < 3; ++d) row[d] += k * n[d] * (n[0] + n[1] + n[2]);
    }
    by_blocks = std::max(by_blocks, block);
    by_rows = std::max({by_rows, row[0], row[1], row[2]});
  }
  if (halo_) {
    by_blocks = max_over_ranks(halo_->comm(), by_blocks);
    by_rows = max_over_ranks(halo_->comm(), by_rows);
  }
  const double lambda_max = std::min(by_blocks, by_rows);
  return lambda_max > 0 ? 2.0 / std::sqrt(lambda_max) : std::numeric_limits<double>::infinity();
}

void LpsModel::assemble_majoriser(const double* y, SparseSymmetric& K) {
  assemble_bond_blocks(y, nullptr, K);
}

void LpsModel::assemble_nearest_stiffness(const double* y, const std::vector<char>& kept,
                                          SparseSymmetric& K) {
  assemble_bond_blocks(y, &kept, K);
}

// Each bond's block k nnᵀ + g (I − nnᵀ), k = h_ij + h_ji the majoriser's bond stiffness and
// g = max(p, 0)/ℓ; with `kept`, only the kept bonds, each scaled by the mean of its ends' s_i
// (stiffness.hpp), into nearest_bond_pattern's layout.
void LpsModel::assemble_bond_blocks(const double* y, const std::vector<char>* kept,
                                    SparseSymmetric& K) {
  update_dilatation(y);
  const int n = particles_.count();
  const auto& off = families_.offsets;
  const auto& nbr = families_.neighbors;
  const auto& xi = families_.reference_length;
  if (halo_) halo_->fill(weighted_volume_.data(), 1);  // M_j of the ghosts, for h_ji
  const std::vector<MajoriserRow> rows = majoriser_rows();
  const auto bond_stiffness = [&](int i, int b) {
    return majoriser_bond_row(rows, i, b) + majoriser_reverse_row(rows, i, b);
  };
  const auto is_kept = [&](int b) { return !kept || (*kept)[b]; };
  std::vector<double> scale(kept ? n : 0);
#pragma omp parallel for schedule(static)
  for (int i = kept ? row_begin_ : 0; i < (kept ? row_end_ : 0); ++i) {
    double family = 0, near = 0;
    for (int b = off[i]; b < off[i + 1]; ++b) {
      const double moment = bond_stiffness(i, b) * xi[b] * xi[b];
      family += moment;
      if (is_kept(b)) near += moment;
    }
    scale[i] = near > 0 ? family / near : 1.0;
  }
  if (kept && halo_) halo_->fill(scale.data(), 1);  // s_j of the ghosts
  std::fill(K.values.begin(), K.values.end(), 0.0);
  // over several ranks the own rows only (their members' terms are the halo's)
#pragma omp parallel for schedule(static)
  for (int i = row_begin_; i < row_end_; ++i) {
    // Row i: the kept members in increasing order, i's own block among them.
    int self = 0;
    for (int b = off[i]; b < off[i + 1] && nbr[b] < i; ++b) self += is_kept(b);
    int index = 0;
    for (int b = off[i]; b < off[i + 1]; ++b) {
      if (!is_kept(b)) continue;
      const int j = nbr[b];
      const auto g = bond_geometry(y, particles_, i, j, xi[b]);
      const double s = kept ? 0.5 * (scale[i] + scale[j]) : 1.0;
      const double p = g.length > 0 ? pair_force(i, b, g.length) : 0.0;
      scatter_bond(K, i, self, index + (index >= self ? 1 : 0), g.n, s * bond_stiffness(i, b),
                   s * std::max(p, 0.0) / std::max(g.length, 1e-300));
      ++index;
    }
  }
}

// The exact tangent (notes §3): per family, K_i = V_i J_iᵀ H_i J_i with J_iᵀ a = Σ_j a_j n_ij at j
// and −Σ_j a_j n_ij at i, plus the geometric term. Rows are assembled one particle at a time, each
// from the families that contain it, so no two threads write to the same row. With
// clamp_compression the geometric term of compressed bonds (p < 0) is left out: K⁺ ⪰ K, K⁺ ⪰ 0.
void LpsModel::assemble_tangent(const double* y, SparseSymmetric& K, bool clamp_compression) {
  // a row couples two family hops, beyond the halo's one
  if (halo_) throw std::logic_error("the two-hop tangent cannot be assembled over several ranks");
  update_dilatation(y);
  const int n = particles_.count();
  const auto& off = families_.offsets;
  const auto& nbr = families_.neighbors;
  const auto& rev = families_.reverse;
  const auto& xi = families_.reference_length;
  const auto& V = particles_.volume;
  const float* w_reverse = reverse_deviatoric();
  // Per family: Σ_j c̄_ij n_ij and Σ_j w_ij n_ij; per bond: n and ℓ.
  std::vector<Vec> sum_c(n), sum_w(n);
  std::vector<BondGeometry> geometry(families_.directed_bonds());
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    Vec sc{}, sw{};
    for (int b = off[i]; b < off[i + 1]; ++b) {
      const int j = nbr[b];
      geometry[b] = bond_geometry(y, particles_, i, j, xi[b]);
      for (int d = 0; d < 3; ++d) {
        sc[d] += bond_weight_[b] * V[j] * geometry[b].n[d];
        sw[d] += bond_deviatoric_[b] * V[j] * xi[b] * geometry[b].n[d];
      }
    }
    sum_c[i] = sc;
    sum_w[i] = sw;
  }
  std::fill(K.values.begin(), K.values.end(), 0.0);
#pragma omp parallel
  {
    std::vector<int> block_of(n, -1);
#pragma omp for schedule(dynamic, 16)
    for (int r = 0; r < n; ++r) {
      const int first = K.offsets[3 * r], blocks = (K.offsets[3 * r + 1] - first) / 3;
      for (int k = 0; k < blocks; ++k) block_of[K.columns[first + 3 * k] / 3] = k;
      const int stride = K.offsets[3 * r + 1] - first;  // values per scalar row
      // Bond terms of row r: V_r B_r w_rs V_s + V_s B_s w_sr V_r along n, geometric p/ℓ across.
      for (int b = off[r]; b < off[r + 1]; ++b) {
        const int s = nbr[b];
        const BondGeometry& g = geometry[b];
        const double k =
            V[r] * V[s] *
            (terms_[r].deviatoric * bond_deviatoric_[b] + terms_[s].deviatoric * w_reverse[b]);
        const double p = g.length > 0 ? pair_force(r, b, g.length) : 0.0;
        scatter_bond(K, r, block_of[r], block_of[s], g.n, k,
                     (clamp_compression ? std::max(p, 0.0) : p) / std::max(g.length, 1e-300));
      }
      // Family terms of every family containing r: its own (i = r) and its members'.
      for (int q = off[r] - 1; q < off[r + 1]; ++q) {
        const int i = q < off[r] ? r : nbr[q];
        // G_c and G_w of family i at node r
        Vec gc_r, gw_r;
        if (i == r) {
          for (int d = 0; d < 3; ++d) gc_r[d] = -sum_c[i][d], gw_r[d] = -sum_w[i][d];
        } else {
          const int b = rev[q];  // bond i → r in row i
          for (int d = 0; d < 3; ++d) {
            gc_r[d] = bond_weight_[b] * V[r] * geometry[b].n[d];
            gw_r[d] = bond_deviatoric_[b] * V[r] * xi[b] * geometry[b].n[d];
          }
        }
        const double B = terms_[i].deviatoric;
        const double cc = V[i] * (materials_.bulk_modulus[i] + B * weighted_volume_[i] / 9.0);
        const double cw = -V[i] * B / 3.0;
        Vec gc_s, gw_s;
        for (int d = 0; d < 3; ++d) gc_s[d] = -sum_c[i][d], gw_s[d] = -sum_w[i][d];
        // block (r, s) += gc_r (cc gc_s + cw gw_s)ᵀ + cw gw_r gc_sᵀ
        auto add_family_block = [&](int s, const Vec& gc_s, const Vec& gw_s) {
          const int k = block_of[s];
          for (int e = 0; e < 3; ++e) {
            double* row = &K.values[first + e * stride + 3 * k];
            const double a = gc_r[e], w = cw * gw_r[e];
            for (int f = 0; f < 3; ++f) row[f] += a * (cc * gc_s[f] + cw * gw_s[f]) + w * gc_s[f];
          }
        };
        add_family_block(i, gc_s, gw_s);
        for (int b = off[i]; b < off[i + 1]; ++b) {
          const int s = nbr[b];
          const double c = bond_weight_[b] * V[s], w = bond_deviatoric_[b] * V[s] * xi[b];
          for (int d = 0; d < 3; ++d) {
            gc_s[d] = c * geometry[b].n[d];
            gw_s[d] = w * geometry[b].n[d];
          }
          add_family_block(s, gc_s, gw_s);
        }
      }
      for (int k = 0; k < blocks; ++k) block_of[K.columns[first + 3 * k] / 3] = -1;
    }
  }
}

}  // namespace fissure
