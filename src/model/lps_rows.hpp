#pragma once
// The LPS model's passes over one row of bonds (lps_model.hpp): the dilatation pass and the force
// pass, and the matrix-free tangent product's two passes (lps_tangent_product.cpp), as plain
// functions over the bond arrays. Each row is summed in eight lanes (bond k
// of the row in lane k mod 8, a lane left untouched past the row's end) and the lanes reduced as
// (l + l+4), then (l + l+2), then (0 + 1). Two implementations give the same bits: a portable one
// and one with AVX-512 intrinsics; the model picks at load which one runs (row_kernels()).
#include <cstddef>

namespace fissure::lps {

// A bond no longer than this times |ξ| is collapsed: it has no deformed direction.
constexpr double kCollapsedBond = 1e-12;

// One row's bond arrays, each indexed by the directed bond b ∈ [begin, end).
struct BondRow {
  int begin, end;
  const int* neighbor;
  const double* reference_length;  // |ξ|
  const float* deviatoric;  // w_ij: the deviatoric stiffness of the bond in row i is B_i w_ij
  const float* reverse_deviatoric;  // w_ji, the same bond's in j's row (= deviatoric when w = ω)
  const float* weight;              // c_ij
  const float* reverse_weight;      // c_ji
};

// What the force pass gathers from each neighbour (LpsModel's NeighbourTerms, the same layout).
struct NeighbourTerms {
  double pressure, deviatoric, shift, volume;
};

// The pair's deviatoric bond force density t^d_ij + t^d_ji = w_ij B_i ê_ij + w_ji B_j ê_ji (Eqs 8,
// 12; notes §6) with B ê = e B − |ξ| S − B e^p: w_ij (e B_i − |ξ| S_i − B_i e^p_ij) + w_ji (…), or,
// where the pair has one weight (not Separate: w_ji = w_ij), w (e (B_i + B_j) − |ξ| (S_i + S_j) −
// (B_i e^p_ij + B_j e^p_ji)), two multiplications fewer. e^p = +0 subtracts +0, which leaves the
// bits of the same term without it (the AVX-512 kernel's).
template <bool Separate>
inline double pair_deviatoric(double e, double xi, double w_ij, double w_ji,
                              const NeighbourTerms& ti, const NeighbourTerms& tj, double ep_ij,
                              double ep_ji) {
  if constexpr (Separate)
    return w_ij * (e * ti.deviatoric - xi * ti.shift - ti.deviatoric * ep_ij) +
           w_ji * (e * tj.deviatoric - xi * tj.shift - tj.deviatoric * ep_ji);
  else
    return w_ij * (e * (ti.deviatoric + tj.deviatoric) - xi * (ti.shift + tj.shift) -
                   (ti.deviatoric * ep_ij + tj.deviatoric * ep_ji));
}

struct DilatationSums {
  double theta;   // θ_i = Σ_j c_ij e_ij V_j (Eq 6)
  double moment;  // Σ_j w_ij |ξ| (e_ij − e^p_ij) V_j
};

// The dilatation pass of row i at positions y: e_ij = |y_j − y_i| − |ξ|; with plastic_extension
// (e^p per bond, or null for a row that never flowed: e^p = +0 gives the same bits), the moment
// of e − e^p. With extension non-null, also e_ij into extension[b − begin].
using DilatationRow = DilatationSums (*)(const BondRow& row, int i, const double* y,
                                         const double* volume, const double* plastic_extension,
                                         double* extension);

// The moment of the return map (LpsModel::update_plasticity): Σ_j w|ξ| (e_ij V_j − e^p_ij V_j)
// from the extensions the dilatation pass left (e^p null: +0), the bits of that pass's moment.
using MomentRow = double (*)(const BondRow& row, const double* extension, const double* volume,
                             const double* plastic_extension);

// The force pass of an elastic row (no e^p on its bonds in either direction): the force density
// sum Σ_j (t_ij + t_ji) V_j n_ij into force[0..2] (Eqs 2–3), and with squares non-null also
// Σ_j w ê² V_j with ê = e − θ_e |ξ|/3, θ_e = elastic_theta (energy_density's sum).
struct ForceRowInput {
  const BondRow* row;
  int i;
  const double* y;
  const NeighbourTerms* terms;
  double elastic_theta;
};
using ForceRow = void (*)(const ForceRowInput& in, double force[3], double* squares);

// The return map's test on a row that never flowed (e^p = +0): whether any bond's trial
// deviatoric force 2wB (e − θ|ξ|/3) exceeds the yield force A^c (Eqs 12, 14), the same test in
// the same arithmetic as LpsModel::update_plasticity's.
using YieldRow = bool (*)(const BondRow& row, const double* extension, double deviatoric,
                          double trial_theta, double yield_force);

// The matrix-free tangent's two passes (lps_tangent_product.cpp) over row i, for a direction v at
// the linearization point y. Each bond's unit direction n = (y_j − y_i)(1/ℓ) is recomputed, not
// stored (bond_geometry's (y_j − y_i)/ℓ to round-off): a collapsed bond (ℓ ≤ 1e-12 |ξ|) takes
// its reference direction (x_j − x_i)(1/|ξ|). s_b = n·(v_j − v_i). The terms are those of the
// LPS tangent (notes §3, §6), derived in lps_tangent_product.cpp.
struct TangentTerms {
  double x, y, gamma, volume;  // X_i = α_i P_i − γ_i Q_i, Y_i = γ_i P_i, γ_i = V_i B_i/3, V_i
};
struct TangentRowInput {
  const BondRow* row;
  int i;
  const double* y;          // the linearization point
  const double* reference;  // x, for collapsed bonds
  const double* v;
  const double* volume;       // V (the first pass)
  const TangentTerms* terms;  // per particle (the second pass)
  const double* geometric;    // g_b = p_b/ℓ_b per bond (the second pass)
};
struct TangentSums {
  double P, Q;  // Σ_b c_ij s_b V_j and Σ_b w_ij |ξ_b| s_b V_j
};
using TangentSumsRow = TangentSums (*)(const TangentRowInput& in);
// (K v)_i = Σ_b [(g_b s_b − t_ib − t_jb) n_b + g_b (v_i − v_j)] with t_ib = V_j [c_ij X_i + w_ij
// (3γ_i s_b − |ξ_b| Y_i)] and t_jb = V_i [c_ji X_j + w_ji (3γ_j s_b − |ξ_b| Y_j)] into out[0..2].
using TangentRow = void (*)(const TangentRowInput& in, double out[3]);

struct RowKernels {
  const char* name;  // "avx512" or "portable"
  DilatationRow dilatation;
  MomentRow moment;
  ForceRow force;
  YieldRow yields;
  TangentSumsRow tangent_sums;
  TangentRow tangent;
};

RowKernels portable_row_kernels();
// Null members where this build or this CPU has no AVX-512 (F, VL and DQ).
RowKernels avx512_row_kernels();
// AVX-512 where the CPU has it, else portable.
RowKernels row_kernels();

}  // namespace fissure::lps
