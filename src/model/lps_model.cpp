#include "model/lps_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "core/error.hpp"
#include "model/deviatoric_calibration.hpp"
#include "model/dilatation_calibration.hpp"
#include "model/second_order_model.hpp"
#include "parallel/collective.hpp"
#include "parallel/halo.hpp"
#include "scene/scene.hpp"

namespace fissure {

LpsModel::LpsModel(const Particles& particles, const Families& families, MaterialPoints materials,
                   SurfaceCorrection surface_correction, const PlasticPoints* plasticity)
    : Model(particles, families, std::move(materials)), plastic_(plasticity != nullptr) {
  const int n = particles.count();
  row_end_ = n;
  const auto& off = families.offsets;
  const auto& nbr = families.neighbors;
  const auto& xi = families.reference_length;
  const std::size_t bonds = families.directed_bonds();
  bond_deviatoric_.resize(bonds);
  weighted_volume_.resize(n);
  terms_.resize(n);
  dilatation_.assign(n, 0.0);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    double m = 0;
    for (int b = off[i]; b < off[i + 1]; ++b) {
      const auto xi_vector = reference_vector(particles, i, nbr[b]);
      bond_deviatoric_[b] =
          static_cast<float>(influence(materials_, i, xi_vector.data(), xi[b]));  // Eq 5, 17
      m += double(bond_deviatoric_[b]) * xi[b] * xi[b] *
           particles.volume[nbr[b]];  // m_i = Σ ω|ξ|²V_j (notes §6)
    }
    weighted_volume_[i] = m;
    // B_i = 15μ_i/m_i, with m_i of the whole family: breaking bonds does not change it.
    terms_[i] = {0.0, m > 0 ? 15.0 * materials_.shear_modulus[i] / m : 0.0, 0.0,
                 particles.volume[i]};
  }
  if (surface_correction != SurfaceCorrection::none) {
    bond_weight_ = dilatation_weights(particles, families, bond_deviatoric_, weighted_volume_);
  } else {
    bond_weight_.resize(bonds);
    for (int i = 0; i < n; ++i)
      for (int b = off[i]; b < off[i + 1]; ++b)
        bond_weight_[b] = static_cast<float>(
            weighted_volume_[i] > 0 ? 3.0 * bond_deviatoric_[b] * xi[b] / weighted_volume_[i]
                                    : 0.0);
  }
  bond_reverse_weight_.resize(bonds);
#pragma omp parallel for schedule(static)
  for (std::size_t b = 0; b < bonds; ++b)
    bond_reverse_weight_[b] = bond_weight_[families.reverse[b]];
  if (plastic_) set_up_plasticity(*plasticity);  // from m_i
  if (surface_correction == SurfaceCorrection::full) calibrate_deviatoric_weights();
}

// The deviatoric calibration's target per body: T/2μ = I₅ for an isotropic body, and for an
// anisotropic one (Eq 17) the continuum limit of its own ω (deviatoric_calibration.hpp), so that
// a particle at a surface answers as one inside the body.
void LpsModel::calibrate_deviatoric_weights() {
  const int n = particles_.count();
  int bodies = 0;
  for (int i = 0; i < n; ++i) bodies = std::max(bodies, particles_.body[i] + 1);
  std::vector<DeviatoricShape> shape_of_body(bodies, isotropic_deviatoric_shape());
  if (!materials_.anisotropy.empty()) {
    std::vector<char> done(bodies, 0);
    for (int i = 0; i < n; ++i)
      if (!done[particles_.body[i]]++)
        shape_of_body[particles_.body[i]] = anisotropic_deviatoric_shape(materials_.anisotropy[i]);
  }
  DeviatoricCalibration calibration =
      deviatoric_weights(particles_, families_, bond_deviatoric_, materials_.shear_modulus,
                         weighted_volume_, shape_of_body);
  bond_deviatoric_ = std::move(calibration.weights);
  // over the rows this rank owns (all on one rank); distribute() sums them over the ranks
  statistics_ = {{"deviatoric_rows", families_.end_own_row() - families_.first_own_row()},
                 {"deviatoric_exact_rows", calibration.exact_rows},
                 {"deviatoric_fallback_rows", calibration.fallback_rows},
                 {"deviatoric_largest_residual", calibration.largest_residual}};
  const auto& off = families_.offsets;
  const auto& xi = families_.reference_length;
  bond_reverse_deviatoric_.resize(bond_deviatoric_.size());
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    double M = 0;
    for (int b = off[i]; b < off[i + 1]; ++b) {
      bond_reverse_deviatoric_[b] = bond_deviatoric_[families_.reverse[b]];
      M += double(bond_deviatoric_[b]) * xi[b] * xi[b] *
           particles_.volume[families_.neighbors[b]];  // M_i = Σ w|ξ|²V_j
    }
    weighted_volume_[i] = M;
  }
}

// A^c_i = √(2Ψ0) (Eq 14), or from a yield stress: the per-bond criterion |A_dev| ≤ A^c is a
// maximum deviatoric stress criterion whose uniaxial yield stress is 1.5 τ_y with
// A^c = 15 δ τ_y / m_i (notes §6), so A^c_i = 10 δ σ_y / m_i.
void LpsModel::set_up_plasticity(const PlasticPoints& plasticity) {
  const int n = particles_.count();
  plastic_extension_.assign(families_.directed_bonds(), 0.0);
  reverse_plastic_extension_.assign(families_.directed_bonds(), 0.0);
  plastic_row_.assign(n, 0);
  plastic_dilatation_.assign(n, 0.0);
  yield_force_.resize(n);
  max_plastic_stretch_ = plasticity.max_plastic_stretch;
  for (int i = 0; i < n; ++i)
    yield_force_[i] =
        std::isnan(plasticity.yield_potential[i])
            ? 10.0 * materials_.horizon[i] * plasticity.yield_stress[i] / weighted_volume_[i]
            : std::sqrt(2.0 * plasticity.yield_potential[i]);
}

// θ_i = Σ_j c_ij e_ij V_j (Eq 6 with Λ dropped and calibrated weights; c = 3ω|ξ|/m_i uncorrected),
// and the per-particle terms of the force: D_i = κθ_i − (B_i/3) Σ_j ω ê_ij |ξ| V_j and
// S_i = B_i (θ_i − θ^p_i)/3, with ê_ij = e_ij − e^p_ij − (θ_i − θ^p_i)|ξ|/3 (notes §6).
template <bool Plastic>
void LpsModel::compute_dilatation(const double* y, int begin, int end) {
  if constexpr (Plastic)
    if (plastic_terms_current(y)) return;
  const double* V = particles_.volume.data();
  const double* ep = plastic_extension_.data();
#pragma omp parallel for schedule(static)
  for (int i = begin; i < end; ++i) {
    // a row that never flowed has e^p = +0 on its bonds: the same bits without reading them
    const lps::DilatationSums sums = kernels_.dilatation(
        bond_row(i), i, y, V, Plastic && plastic_row_[i] ? ep : nullptr, nullptr);
    set_terms(i, sums.theta, Plastic ? sums.theta - plastic_dilatation_[i] : sums.theta,
              sums.moment);
  }
  if constexpr (Plastic) remember_plastic_terms(y);
}

lps::BondRow LpsModel::bond_row(int i) const {
  return {families_.offsets[i],       families_.offsets[i + 1],
          families_.neighbors.data(), families_.reference_length.data(),
          bond_deviatoric_.data(),    reverse_deviatoric(),
          bond_weight_.data(),        bond_reverse_weight_.data()};
}

// θ_i and the per-particle force terms from θ_i, θ_i − θ^p_i and Σ_j w (e − e^p)|ξ| V_j:
// Σ_j w ê |ξ| V_j = Σ_j w (e − e^p)|ξ| V_j − (θ − θ^p) M_i/3, with M_i over the intact bonds (zero
// for an intact family without the calibrations); D_i = κθ_i − (B_i/3) Σ_j w ê |ξ| V_j and
// S_i = B_i (θ_i − θ^p_i)/3 (notes §6).
void LpsModel::set_terms(int i, double theta, double elastic_theta, double moment) {
  const double B = terms_[i].deviatoric;
  const double deviatoric_moment = moment - elastic_theta * weighted_volume_[i] / 3.0;
  dilatation_[i] = theta;
  terms_[i].pressure = materials_.bulk_modulus[i] * theta - B / 3.0 * deviatoric_moment;
  terms_[i].shift = B * elastic_theta / 3.0;
}

bool LpsModel::plastic_terms_current(const double* y) const {
  return plastic_terms_revision_ == revision() + 1 &&
         std::equal(plastic_terms_y_.begin(), plastic_terms_y_.end(), y);
}

// Stored as revision + 1, so that the zero it starts at matches no revision.
void LpsModel::remember_plastic_terms(const double* y) {
  plastic_terms_y_.assign(y, y + 3 * particles_.count());
  plastic_terms_revision_ = revision() + 1;
}

// F_i = −∂Π/∂y_i = V_i Σ_j (t_ij + t_ji) n_ij V_j (Eqs 2–3), with the bond force density
// t_ij = ½A_ij = c_ij D_i + w_ij B_i ê_ij (Eqs 4, 8 and 12, corrected: notes §6). With Energy,
// V_i W_i of energy_density from the same pass over row i's bonds.
template <bool Plastic, bool Energy>
void LpsModel::compute_forces(const double* y, double* f, double* energy) {
  compute_dilatation<Plastic>(y, row_begin_, row_end_);
  // the force pass reads D_j, B_j, S_j and V_j of every family member: ghosts' from their ranks
  static_assert(sizeof(NeighbourTerms) == 4 * sizeof(double) &&
                std::is_standard_layout_v<NeighbourTerms>);
  if (halo_) halo_->fill(reinterpret_cast<double*>(terms_.data()), 4);
  const NeighbourTerms* terms = terms_.data();
#pragma omp parallel for schedule(static)
  for (int i = row_begin_; i < row_end_; ++i) {
    const double theta = dilatation_[i];
    const double elastic_theta = Plastic ? theta - plastic_dilatation_[i] : theta;  // θ_i − θ^p_i
    const lps::BondRow row = bond_row(i);
    double force[3], squares = 0;  // Σ_j w ê² V_j
    if (Plastic && plastic_row_[i])
      plastic_force_row(row, i, y, elastic_theta, force, Energy ? &squares : nullptr);
    else
      kernels_.force({&row, i, y, terms, elastic_theta}, force, Energy ? &squares : nullptr);
    const double Vi = terms[i].volume;
    f[3 * i] = Vi * force[0];
    f[3 * i + 1] = Vi * force[1];
    f[3 * i + 2] = Vi * force[2];
    if constexpr (Energy)
      energy[i] = Vi * (0.5 * materials_.bulk_modulus[i] * theta * theta +
                        0.5 * terms[i].deviatoric * squares);  // V_i W_i
  }
}

// The force pass of a row with plastic extensions on its bonds: the elastic row's terms with
// ê = e − e^p − (θ_i − θ^p_i)|ξ|/3 and e^p_ij (w_ij B_i) and e^p_ji (w_ji B_j) taken off (Eq 12).
void LpsModel::plastic_force_row(const lps::BondRow& row, int i, const double* y,
                                 double elastic_theta, double force[3], double* squares) const {
  const NeighbourTerms* terms = terms_.data();
  const double* ep = plastic_extension_.data();
  const double* ep_reverse = reverse_plastic_extension_.data();
  const double yi0 = y[3 * i], yi1 = y[3 * i + 1], yi2 = y[3 * i + 2];
  const NeighbourTerms& ti = terms[i];
  const bool separate = row.reverse_deviatoric != row.deviatoric;
  double f0 = 0, f1 = 0, f2 = 0, w = 0;
  for (int b = row.begin; b < row.end; ++b) {
    const int j = row.neighbor[b];
    const double* yj = y + 3 * j;
    const double d0 = yj[0] - yi0, d1 = yj[1] - yi1, d2 = yj[2] - yi2;
    const double length = std::sqrt(d0 * d0 + d1 * d1 + d2 * d2);
    const double xi = row.reference_length[b];
    const double extension = length - xi;
    const NeighbourTerms& tj = terms[j];
    const double w_ij = row.deviatoric[b], w_ji = row.reverse_deviatoric[b];
    // the elastic kernel's term with e^p taken off: with e^p = +0 the same bits
    const double deviatoric =
        separate
            ? lps::pair_deviatoric<true>(extension, xi, w_ij, w_ji, ti, tj, ep[b], ep_reverse[b])
            : lps::pair_deviatoric<false>(extension, xi, w_ij, w_ji, ti, tj, ep[b], ep_reverse[b]);
    const double t =
        (double(row.weight[b]) * ti.pressure + double(row.reverse_weight[b]) * tj.pressure) +
        deviatoric;
    // n = d / |d|; a collapsed bond (|d| = 0) has no direction and carries no force.
    const double s = length > 0 ? t * tj.volume / length : 0.0;
    f0 += s * d0;
    f1 += s * d1;
    f2 += s * d2;
    if (squares) {
      const double e_hat = extension - ep[b] - elastic_theta * xi / 3.0;  // ê_ij
      w += w_ij * tj.volume * e_hat * e_hat;
    }
  }
  force[0] = f0;
  force[1] = f1;
  force[2] = f2;
  if (squares) *squares = w;
}

void LpsModel::forces(const double* y, double* f) {
  if (plastic_)
    compute_forces<true, false>(y, f, nullptr);
  else
    compute_forces<false, false>(y, f, nullptr);
}

// The forces of forces() (the same kernel, bitwise) and Π = Σ V_i W_i of elastic_energy().
double LpsModel::forces_and_energy(const double* y, double* f) {
  energy_.resize(particles_.count());
  if (plastic_)
    compute_forces<true, true>(y, f, energy_.data());
  else
    compute_forces<false, true>(y, f, energy_.data());
  double total = 0;
#pragma omp parallel for reduction(+ : total) schedule(static)
  for (int i = row_begin_; i < row_end_; ++i) total += energy_[i];
  return total;
}

void LpsModel::distribute(const Halo& halo) {
  if (halo.end() > particles_.count() || halo.begin() > halo.end())
    throw std::invalid_argument("the halo's rows are not this scene's");
  halo_ = &halo;
  row_begin_ = halo.begin();
  row_end_ = halo.end();
  if (plastic_ || !families_.whole()) shared_ = &halo.shared_bonds(families_);
  if (families_.whole()) return;
  take_ghosts_set_up();
  // each rank counted its own rows of the deviatoric calibration
  for (auto& [name, value] : statistics_)
    value = name == "deviatoric_largest_residual" ? max_over_ranks(halo.comm(), value)
                                                  : sum_over_ranks(halo.comm(), value);
}

// A ghost's row here holds only its bonds to this rank's rows (Families), so what the
// constructor computed from it is not the ghost's: its per-particle set-up values (m_j or M_j,
// B_j, V_j) come from its rank through the halo, and its weights of each pair shared with this
// rank (c_ji, w_ji, computed there from its whole family, and zeroed there where pre-cracks
// broke the pair) through the bond star forest. Collective.
void LpsModel::take_ghosts_set_up() {
  shared_->reverses->fill(bond_weight_.data(), 1);
  shared_->reverses->fill(bond_deviatoric_.data(), 1);
  for (const int b : shared_->bonds) {
    const int r = families_.reverse[b];
    bond_reverse_weight_[b] = bond_weight_[r];
    if (!bond_reverse_deviatoric_.empty()) bond_reverse_deviatoric_[b] = bond_deviatoric_[r];
  }
  halo_->fill(weighted_volume_.data(), 1);
  static_assert(sizeof(NeighbourTerms) == 4 * sizeof(double));
  halo_->fill(reinterpret_cast<double*>(terms_.data()), 4);
}

// θ_i = Σ_j c_ij e_ij V_j (Eq 6 with Λ dropped), summed as compute_dilatation sums it.
void LpsModel::dilatation(const double* y, double* theta) const {
  const double* V = particles_.volume.data();
#pragma omp parallel for schedule(static)
  for (int i = row_begin_; i < row_end_; ++i)
    theta[i] = kernels_.dilatation(bond_row(i), i, y, V, nullptr, nullptr).theta;
}

// Over several ranks: the own rows, and the ghosts' terms from their ranks (as forces()).
void LpsModel::update_dilatation(const double* y) {
  if (plastic_)
    compute_dilatation<true>(y, row_begin_, row_end_);
  else
    compute_dilatation<false>(y, row_begin_, row_end_);
  if (halo_) halo_->fill(reinterpret_cast<double*>(terms_.data()), 4);
}

// W_i = ½κθ_i² + ½B_i Σ_j w_ij ê_ij² V_j with ê_ij = e_ij − e^p_ij − (θ_i − θ^p_i)|ξ|/3
// (notes §3, §6).
double LpsModel::row_energy(const double* y, int i, double theta) const {
  const double* yi = y + 3 * i;
  const double elastic_theta = plastic_ ? theta - plastic_dilatation_[i] : theta;
  double sum = 0;
  for (int b = families_.offsets[i]; b < families_.offsets[i + 1]; ++b) {
    const int j = families_.neighbors[b];
    const double* yj = y + 3 * j;
    const double d0 = yj[0] - yi[0], d1 = yj[1] - yi[1], d2 = yj[2] - yi[2];
    const double xi = families_.reference_length[b];
    const double extension = std::sqrt(d0 * d0 + d1 * d1 + d2 * d2) - xi;
    const double deviatoric = plastic_
                                  ? extension - plastic_extension_[b] - elastic_theta * xi / 3.0
                                  : extension - elastic_theta * xi / 3.0;
    sum += bond_deviatoric_[b] * particles_.volume[j] * deviatoric * deviatoric;
  }
  return 0.5 * materials_.bulk_modulus[i] * theta * theta + 0.5 * terms_[i].deviatoric * sum;
}

void LpsModel::energy_density(const double* y, double* w) {
  update_dilatation(y);
#pragma omp parallel for schedule(static)
  for (int i = row_begin_; i < row_end_; ++i) w[i] = row_energy(y, i, dilatation_[i]);
}

// The listed rows' θ_i from the dilatation pass alone (the bits compute_dilatation gives them).
double LpsModel::rows_energy(const double* y, const std::vector<int>& rows) {
  const double* V = particles_.volume.data();
  const std::size_t count = rows.size();
  double total = 0;
#pragma omp parallel for reduction(+ : total) schedule(static)
  for (std::size_t k = 0; k < count; ++k) {
    const int i = rows[k];
    const double theta = kernels_.dilatation(bond_row(i), i, y, V, nullptr, nullptr).theta;
    total += V[i] * row_energy(y, i, theta);
  }
  return total;
}

// Return map after a completed step (Eqs 13–16, corrected: notes §5–6). The trial deviatoric
// force A_dev = 4ωb ê = 2wB_i ê (Eq 12, with the bond's weight w for ω: the force it carries)
// is projected onto the yield surface |A_dev| = A^c (Eq 14) by Δe^p = (A_dev − A^c sign A_dev)
// /(2wB_i), the consistent step (the paper's 1/(2b) over-relaxes by 2ω), and e^p is capped at
// γ = max_plastic_stretch |ξ| (Eq 16).
// One pass over the bonds, row by row: θ_i as compute_dilatation sums it, the row's return map
// on the extensions kept from that sum, then the row's θ^p_i and force terms at y with the new
// e^p, so the next evaluation at y (the next step's first) starts from them.
std::size_t LpsModel::update_plasticity(const double* y) {
  const int* off = families_.offsets.data();
  const int* nbr = families_.neighbors.data();
  const double* xi = families_.reference_length.data();
  const float* w = bond_deviatoric_.data();
  const float* c = bond_weight_.data();
  const double* V = particles_.volume.data();
  double* ep = plastic_extension_.data();
  double* ep_reverse = reverse_plastic_extension_.data();
  const int* reverse = families_.reverse.data();
  std::size_t yielded = 0;
#pragma omp parallel reduction(+ : yielded)
  {
    std::vector<double> row_extension;  // e_ij of the row, reused by every row of this thread
#pragma omp for schedule(static)
    for (int i = row_begin_; i < row_end_; ++i) {
      const int first = off[i], count = off[i + 1] - first;
      if (static_cast<int>(row_extension.size()) < count) row_extension.resize(count);
      const lps::BondRow row = bond_row(i);
      // θ_i = Σ_j c_ij e_ij V_j (Eq 6), and e_ij into row_extension
      const lps::DilatationSums sums =
          kernels_.dilatation(row, i, y, V, nullptr, row_extension.data());
      const double theta = sums.theta;
      const double B = terms_[i].deviatoric, critical = yield_force_[i];
      const double trial_theta = theta - plastic_dilatation_[i];
      // A row that never flowed has e^p = +0 on every bond: it reads none of them, and where no
      // bond yields now either, θ^p_i stays +0 and the moment is the dilatation pass's.
      std::uint8_t flowed;
#pragma omp atomic read
      flowed = plastic_row_[i];
      if (!flowed && !kernels_.yields(row, row_extension.data(), B, trial_theta, critical)) {
        set_terms(i, theta, trial_theta, sums.moment);
        continue;
      }
      double plastic_theta = 0;
      bool row_flowed = flowed;
      for (int k = 0; k < count; ++k) {
        const int b = first + k, j = nbr[b];
        const double stiffness = 2.0 * w[b] * B;  // 4ωb, w for ω
        double plastic = flowed ? ep[b] : 0.0;
        // ê_ij = e − e^p − (θ_i − θ^p_i)|ξ|/3
        const double trial = stiffness * (row_extension[k] - plastic - trial_theta * xi[b] / 3.0);
        if (stiffness > 0 && std::abs(trial) > critical) {
          const double updated = plastic + (trial - std::copysign(critical, trial)) / stiffness;
          const double cap = max_plastic_stretch_[i] * xi[b];
          plastic = ep[b] = std::clamp(updated, -cap, cap);
          row_flowed = true;
          ep_reverse[reverse[b]] = plastic;  // the only write to that entry
          // Flags only go from 0 to 1 during the pass, and row j's may be set by row j too.
#pragma omp atomic write
          plastic_row_[i] = 1;
#pragma omp atomic write
          plastic_row_[j] = 1;
          ++yielded;
        }
        plastic_theta += c[b] * plastic * V[j];  // θ^p_i = Σ_j c_ij e^p_ij V_j
      }
      // the moment of compute_dilatation<true> with the new e^p, in its lanes
      const double moment =
          kernels_.moment(row, row_extension.data(), V, row_flowed ? ep : nullptr);
      plastic_dilatation_[i] = plastic_theta;
      set_terms(i, theta, theta - plastic_theta, moment);  // compute_dilatation<true>'s, new e^p
    }
  }
  if (halo_) yielded = share_plastic_extensions(yielded);
  if (yielded > 0) mark_changed();
  remember_plastic_terms(y);
  return yielded;
}

// Over several ranks, after the own rows' return map: the bonds yielded on all ranks (so that
// every rank marks the same change), and where some did, each shared pair's e^p_ji from row j's
// rank into plastic_extension_'s entry of the reverse bond (which the stiffness reads) and row
// i's copy, flagging the row as the return map of row j flags it on one rank. Collective.
std::size_t LpsModel::share_plastic_extensions(std::size_t yielded) {
  const std::size_t total =
      static_cast<std::size_t>(sum_over_ranks(halo_->comm(), static_cast<double>(yielded)));
  if (total == 0) return 0;
  shared_->reverses->fill(plastic_extension_.data(), 1);
  for (std::size_t k = 0; k < shared_->bonds.size(); ++k) {
    const int b = shared_->bonds[k];
    const double ep = plastic_extension_[families_.reverse[b]];
    reverse_plastic_extension_[b] = ep;
    if (ep != 0 || std::signbit(ep)) plastic_row_[shared_->rows[k]] = 1;
  }
  return total;
}

NamedArrays LpsModel::saved_state() const {
  NamedArrays state = {{"model.weighted_volume", weighted_volume_}};
  if (plastic_) {
    state.emplace_back("model.plastic_extension", plastic_extension_);
    state.emplace_back("model.plastic_dilatation", plastic_dilatation_);
  }
  return state;
}

void LpsModel::restore_state(const NamedArrays& state) {
  // a checkpoint numbers bonds as the whole families do (Families::localize)
  auto take = [&](const char* name, std::vector<double>& into) {
    const std::vector<double>* values = find_array(state, name);
    std::vector<double> local =
        values && per_bond_state(name) ? families_.localize(*values) : std::vector<double>{};
    if (values && !per_bond_state(name)) local = *values;
    if (!values || local.size() != into.size())
      throw InputError("", name, "missing from the checkpoint or of another size");
    into = std::move(local);
  };
  take("model.weighted_volume", weighted_volume_);
  if (plastic_) {
    take("model.plastic_extension", plastic_extension_);
    for (std::size_t b = 0; b < plastic_extension_.size(); ++b)
      reverse_plastic_extension_[families_.reverse[b]] = plastic_extension_[b];
    auto flowed = [](double ep) { return ep != 0 || std::signbit(ep); };
    for (int i = 0; i < particles_.count(); ++i) {
      plastic_row_[i] = 0;
      for (int b = families_.offsets[i]; b < families_.offsets[i + 1]; ++b)
        plastic_row_[i] |= flowed(plastic_extension_[b]) || flowed(reverse_plastic_extension_[b]);
    }
    take("model.plastic_dilatation", plastic_dilatation_);
  }
  mark_changed();
}

void LpsModel::break_bond(int i, std::size_t b) {
  const double xi = families_.reference_length[b];
  // M_i −= w|ξ|²V_j; the other weights of the row keep their calibration (docs/model.md)
  weighted_volume_[i] -= bond_deviatoric_[b] * xi * xi * particles_.volume[families_.neighbors[b]];
  bond_deviatoric_[b] = 0;
  if (!bond_reverse_deviatoric_.empty()) bond_reverse_deviatoric_[b] = 0;
  bond_weight_[b] = 0;
  bond_reverse_weight_[b] = 0;
  mark_changed();
}

std::size_t LpsModel::bytes_per_bond() const {
  // neighbour, |ξ|, reverse index; w_ij, c_ij, c_ji, and w_ji when calibrated
  const std::size_t reverse = bond_reverse_deviatoric_.empty() ? 0 : sizeof(float);
  return 2 * sizeof(int) + sizeof(double) + 3 * sizeof(float) + reverse;
}

std::size_t LpsModel::bytes_read_per_bond() const {
  // dilatation pass: neighbour, |ξ|, w_ij, c_ij; force pass: the same, c_ji and w_ji if its own
  const std::size_t reverse = bond_reverse_deviatoric_.empty() ? 0 : sizeof(float);
  return 2 * (sizeof(int) + sizeof(double) + 2 * sizeof(float)) + sizeof(float) + reverse;
}

ModelKind lps_model_kind() {
  return {"lps", {}, nullptr, [](const Scene& scene, MaterialPoints m) -> std::unique_ptr<Model> {
            const Config& config = scene.config;
            if (config.bodies.front().material.surface_correction == SurfaceCorrection::fictitious)
              try {
                return make_second_order_model(scene, std::move(m));
              } catch (const std::invalid_argument& e) {
                throw InputError(config.file, "bodies[0].material.surface_correction",
                                 fmt::format("fictitious: {}", e.what()));
              }
            const int n = scene.particles.count();
            PlasticPoints plasticity;
            if (config.plasticity_enabled()) {
              plasticity.yield_potential.resize(n);
              plasticity.yield_stress.resize(n);
              plasticity.max_plastic_stretch.resize(n);
              for (int i = 0; i < n; ++i) {
                const PlasticitySettings& p =
                    config.bodies[scene.particles.body[i]].material.plasticity;
                // A body without plasticity in a plastic scene never yields.
                plasticity.yield_potential[i] =
                    p.enabled ? p.yield : std::numeric_limits<double>::infinity();
                plasticity.yield_stress[i] = p.yield_stress;
                plasticity.max_plastic_stretch[i] = p.max_plastic_stretch;
              }
            }
            return std::make_unique<LpsModel>(scene.particles, scene.families, std::move(m),
                                              config.bodies.front().material.surface_correction,
                                              config.plasticity_enabled() ? &plasticity : nullptr);
          }};
}

}  // namespace fissure
