#include "fracture/bond_breaking.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "fracture/initial_cracks.hpp"
#include "model/plastic_flow.hpp"

namespace fissure {

BondBreaking::BondBreaking(const Scene& scene, Model& model)
    : families_(scene.families), model_(model) {
  const Particles& p = scene.particles;
  const int n = p.count();
  critical_stretch_.resize(n);
  alpha_.resize(n);
  horizon_.resize(n);
  intact_.resize(n);
  damage_.assign(n, 0.0);
  row_end_ = n;
  for (int i = 0; i < n; ++i) {
    const FractureSettings& f = scene.config.bodies[p.body[i]].material.fracture;
    critical_stretch_[i] = f.enabled ? f.critical_stretch : std::numeric_limits<double>::infinity();
    alpha_[i] = f.alpha;
    horizon_[i] = scene.horizon_of_body[p.body[i]];
    intact_[i] = families_.offsets[i + 1] - families_.offsets[i];
  }
  if (scene.config.anisotropy_enabled()) {
    reach_.resize(families_.directed_bonds());
    for (int i = 0; i < n; ++i) {
      const auto& G = scene.config.bodies[p.body[i]].material.anisotropy.G;
      for (int b = families_.offsets[i]; b < families_.offsets[i + 1]; ++b) {
        double g[3] = {0, 0, 0};
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c)
            g[r] += G[3 * r + c] *
                    (p.reference[3 * families_.neighbors[b] + c] - p.reference[3 * i + c]);
        reach_[b] = static_cast<float>(horizon_[i] * families_.reference_length[b] /
                                       std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]));
      }
    }
  }
  broken_.assign(families_.directed_bonds(), 0);
  exceeded_.assign(families_.directed_bonds(), 0);
  // Each pair is tested once, from its lower index, and removed from both rows together.
  std::size_t removed = 0;
  for (int i = 0; i < n; ++i)
    for (int b = families_.offsets[i]; b < families_.offsets[i + 1]; ++b) {
      const int j = families_.neighbors[b];
      if (j < i) continue;
      for (const Crack& crack : scene.config.initial_cracks)
        if (crosses(crack, &p.reference[3 * i], &p.reference[3 * j])) {
          remove(i, b);
          remove(j, families_.reverse[b]);
          removed += 2;
          break;
        }
    }
  for (int i = 0; i < n; ++i) update_damage(i);
  broken_pairs_ = removed / 2;
  if (!model_.plastic_flow()) {
    prefilter_.resize(families_.directed_bonds());
    slack_.assign(n, 0.0);
    drift_.assign(n, 0.0);
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; ++i) update_prefilter(i);
  }
}

// The criterion e − e^p > s_c(1 + αφ_i)ω|ξ| of find_exact is |y_j − y_i| > ℓ_c with e^p = 0;
// the bound is ℓ_c(1 − 1e-6) rounded down to single precision (the largest float where ℓ_c is
// past that range), so that every bond the exact test (rounded in double) would break passes it.
void BondBreaking::update_prefilter(int i) {
  const double scale = critical_stretch_[i] * (1.0 + alpha_[i] * damage_[i]);
  const bool anisotropic = !reach_.empty();
  for (int b = families_.offsets[i]; b < families_.offsets[i + 1]; ++b) {
    if (broken_[b] || scale == std::numeric_limits<double>::infinity()) {
      prefilter_[b] = std::numeric_limits<float>::infinity();
      continue;
    }
    const double bound = (1.0 - 1e-6) * (families_.reference_length[b] +
                                         scale * (anisotropic ? reach_[b] : horizon_[i]));
    const float rounded = static_cast<float>(std::min<double>(bound, FLT_MAX));
    prefilter_[b] = std::min(rounded, std::nextafter(rounded, -FLT_MAX));
  }
}

void BondBreaking::remove(int i, int b) {
  broken_[b] = 1;
  model_.break_bond(i, b);
  --intact_[i];
}

void BondBreaking::update_damage(int i) {
  const int total = families_.offsets[i + 1] - families_.offsets[i];
  damage_[i] = total > 0 ? 1.0 - static_cast<double>(intact_[i]) / total : 0.0;
}

std::size_t BondBreaking::run(const double* y) {
  find(y);
  return apply();
}

// s^ω_ij = s^e/ω_ij with s^e = (e − e^p)/|ξ| (Eqs 18–19), against a threshold that grows with
// damage as the paper's text asks ("continuously increasing the crack threshold as the material
// gets damaged", docs/model.md): the bond breaks when e − e^p exceeds s_c (1 + αφ_i) ω|ξ|,
// with ω|ξ| = δ (Eq 5) or δ|ξ|/|Gξ| (Eq 17). Tension only: a compressed bond never breaks.
// Marks row i's exceeded bonds and returns how many.
std::size_t BondBreaking::find_exact(const double* y, int i) {
  const auto& off = families_.offsets;
  const auto& nbr = families_.neighbors;
  const auto& xi = families_.reference_length;
  const PlasticFlow* plastic_flow = model_.plastic_flow();
  const double* plastic = plastic_flow ? plastic_flow->plastic_extension().data() : nullptr;
  const bool anisotropic = !reach_.empty();
  const double scale = critical_stretch_[i] * (1.0 + alpha_[i] * damage_[i]);
  std::size_t exceeded = 0;
  for (int b = off[i]; b < off[i + 1]; ++b) {
    if (broken_[b]) continue;
    const double* yi = y + 3 * i;
    const double* yj = y + 3 * nbr[b];
    const double e =
        std::sqrt((yj[0] - yi[0]) * (yj[0] - yi[0]) + (yj[1] - yi[1]) * (yj[1] - yi[1]) +
                  (yj[2] - yi[2]) * (yj[2] - yi[2])) -
        xi[b] - (plastic ? plastic[b] : 0.0);
    exceeded_[b] = e > scale * (anisotropic ? reach_[b] : horizon_[i]);
    exceeded += exceeded_[b];
  }
  if (exceeded > 0) {
#pragma omp critical(fissure_exceeding_rows)
    exceeding_.push_back(i);
  }
  return exceeded;
}

// d_k = |Δy_k − c| for every particle, with Δy_k = y_k − y_k(last full check) and c the mean
// of Δy (any common c bounds a bond's change, |Δ(y_j − y_i)| ≤ d_i + d_j, and the mean removes
// a common translation); returns D = max d_k (NaN where y is not finite).
double BondBreaking::update_drift(const double* y) {
  const int begin = row_begin_, end = row_end_;
  const double* snapshot = snapshot_.data();
  double c0 = 0, c1 = 0, c2 = 0;
#pragma omp parallel for reduction(+ : c0, c1, c2) schedule(static)
  for (int k = begin; k < end; ++k) {
    c0 += y[3 * k] - snapshot[3 * k];
    c1 += y[3 * k + 1] - snapshot[3 * k + 1];
    c2 += y[3 * k + 2] - snapshot[3 * k + 2];
  }
  const int count = std::max(end - begin, 1);
  c0 /= count;
  c1 /= count;
  c2 /= count;
  const auto drift = [&](int k) {
    const double d0 = y[3 * k] - snapshot[3 * k] - c0, d1 = y[3 * k + 1] - snapshot[3 * k + 1] - c1,
                 d2 = y[3 * k + 2] - snapshot[3 * k + 2] - c2;
    return drift_[k] = std::sqrt(d0 * d0 + d1 * d1 + d2 * d2);
  };
  double largest = 0;
  bool finite = true;
#pragma omp parallel for reduction(max : largest) reduction(&& : finite) schedule(static)
  for (int k = begin; k < end; ++k) {
    const double d = drift(k);
    finite = finite && std::isfinite(d);
    largest = std::max(largest, d);
  }
  // a bond to a ghost j changes by at most d_i + d_j: D bounds the ghosts' d_j too
  if (halo_)
    for (const int j : halo_->ghosts()) {
      const double d = drift(j);
      finite = finite && std::isfinite(d);
      largest = std::max(largest, d);
    }
  return finite ? largest : std::numeric_limits<double>::quiet_NaN();
}

// Row i against the prefilter; returns whether some bond passes it, and sets slack_[i] to how
// far every bond's length may still grow before it reaches its bound, less what the row's
// particles may already have moved since the last full check (d_i + D: see find()).
bool BondBreaking::prefilter_row(const double* y, int i, double drift_bound) {
  const double room = prefilter_room_(families_.offsets[i], families_.offsets[i + 1],
                                      families_.neighbors.data(), prefilter_.data(), y, i);
  slack_[i] = room - drift_bound;
  return room < 0;  // some bond past its bound
}

// Every row with plasticity. Without, a row is tested exactly only where some bond passes the
// prefilter, and the prefilter runs only on rows that may have come near it: between full checks
// a bond's length changes by at most d_i + d_j ≤ d_i + D (update_drift), so a row whose slack
// at its last check, less d_i + D then, exceeds d_i + D now cannot break. The others cannot
// break either: their exceeded_ stay 0, as apply() leaves them. A full check, with new
// snapshot, when more than a quarter of the rows would need the prefilter.
std::size_t BondBreaking::find(const double* y) {
  const int begin = row_begin_, end = row_end_, n = end - begin;
  std::size_t exceeded = 0;
  exceeding_.clear();
  if (prefilter_.empty()) {
#pragma omp parallel for reduction(+ : exceeded) schedule(static)
    for (int i = begin; i < end; ++i) exceeded += find_exact(y, i);
    return found(exceeded);
  }
  double largest = 0;
  bool full = full_check_due_;
  if (!full) {
    largest = update_drift(y);
    int near = 0;
#pragma omp parallel for reduction(+ : near) schedule(static)
    for (int i = begin; i < end; ++i) near += !(slack_[i] > drift_[i] + largest);
    full = !(near <= n / 4);
  }
  if (full) {
    snapshot_.assign(y, y + 3 * intact_.size());
    std::fill(drift_.begin(), drift_.end(), 0.0);
    largest = 0;
    full_check_due_ = false;
  }
#pragma omp parallel for reduction(+ : exceeded) schedule(dynamic, 256)
  for (int i = begin; i < end; ++i) {
    if (!full && slack_[i] > drift_[i] + largest) continue;
    if (prefilter_row(y, i, drift_[i] + largest)) exceeded += find_exact(y, i);
  }
  return found(exceeded);
}

// After find()'s passes: the rows apply() will change, from the rows find_exact() recorded.
std::size_t BondBreaking::found(std::size_t exceeded) {
  changed_.clear();
  changing_.clear();
  std::sort(exceeding_.begin(), exceeding_.end());
  for (const int i : exceeding_) {
    changing_.push_back(i);
    for (int b = families_.offsets[i]; b < families_.offsets[i + 1]; ++b)
      if (exceeded_[b] && owned(families_.neighbors[b]))
        changing_.push_back(families_.neighbors[b]);
  }
  // the rows sharing a pair with a ghost's row whose criterion was exceeded there
  if (shared_) {
    shared_->reverses->fill(exceeded_.data(), 1);
    for (std::size_t k = 0; k < shared_->bonds.size(); ++k)
      if (exceeded_[families_.reverse[shared_->bonds[k]]]) {
        changing_.push_back(shared_->rows[k]);
        ++exceeded;  // apply() must run here even where no own row exceeded its criterion
      }
  }
  std::sort(changing_.begin(), changing_.end());
  changing_.erase(std::unique(changing_.begin(), changing_.end()), changing_.end());
  return exceeded;
}

std::size_t BondBreaking::apply() {
  const auto& off = families_.offsets;
  // A bond breaks in both rows when either row's criterion is exceeded; each row updates only
  // its own entries, so the rows can run in parallel. Only find()'s rows can change.
  std::size_t removed = 0, directed = 0;
  const int rows = static_cast<int>(changing_.size());
#pragma omp parallel for reduction(+ : removed, directed) schedule(static)
  for (int k = 0; k < rows; ++k) {
    const int i = changing_[k];
    bool changed = false;
    for (int b = off[i]; b < off[i + 1]; ++b)
      if (!broken_[b] && (exceeded_[b] || exceeded_[families_.reverse[b]])) {
        remove(i, b);
        removed += owned(families_.neighbors[b]) ? 1 : 2;  // a pair shared: counted here whole
        ++directed;
        changed = true;
      }
    if (changed) {
      update_damage(i);
      if (!prefilter_.empty()) update_prefilter(i);
#pragma omp critical(fissure_changed_rows)
      changed_.push_back(i);
    }
  }
  std::sort(changed_.begin(), changed_.end());
  for (const int i : exceeding_)
    std::fill(exceeded_.begin() + off[i], exceeded_.begin() + off[i + 1], std::uint8_t{0});
  if (shared_)
    for (const int b : shared_->bonds) exceeded_[families_.reverse[b]] = 0;
  exceeding_.clear();
  broken_pairs_ += removed / 2;
  if (!halo_) return removed / 2;
  // whether any rank's rows changed decides collective work (an integrator's new forces): every
  // rank must return the same; the directed bonds over all ranks count each pair twice
  unsigned long mine = directed, total = 0;
  if (MPI_Allreduce(&mine, &total, 1, MPI_UNSIGNED_LONG, MPI_SUM, halo_->comm()) != MPI_SUCCESS)
    throw std::runtime_error("MPI_Allreduce failed");
  return total / 2;
}

void BondBreaking::restore(const std::vector<std::uint8_t>& whole_broken) {
  const std::vector<std::uint8_t> broken = families_.localize(whole_broken);
  std::size_t total = 0;
  for (int i = row_begin_; i < row_end_; ++i) {
    for (int b = families_.offsets[i]; b < families_.offsets[i + 1]; ++b) {
      if (broken[b] && !broken_[b]) remove(i, b);
      total += broken_[b] ? (owned(families_.neighbors[b]) ? 1 : 2) : 0;
    }
    update_damage(i);
    if (!prefilter_.empty()) update_prefilter(i);
  }
  full_check_due_ = true;
  changed_.clear();
  broken_pairs_ = total / 2;
}

void BondBreaking::distribute(const Halo& halo) {
  if (halo.end() > static_cast<int>(intact_.size()) || halo.begin() > halo.end())
    throw std::invalid_argument("the halo's rows are not this scene's");
  halo_ = &halo;
  row_begin_ = halo.begin();
  row_end_ = halo.end();
  shared_ = &halo.shared_bonds(families_);
  full_check_due_ = true;
  std::size_t total = 0;
  for (int i = row_begin_; i < row_end_; ++i)
    for (int b = families_.offsets[i]; b < families_.offsets[i + 1]; ++b)
      total += broken_[b] ? (owned(families_.neighbors[b]) ? 1 : 2) : 0;
  broken_pairs_ = total / 2;
}

}  // namespace fissure
