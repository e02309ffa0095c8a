#pragma once
// The fracture post-step shared by every integrator (paper §5.1): after a completed step, bonds
// whose stretch criterion (Eq 19) exceeds the critical stretch break for good, and each particle's
// damage φ_i = 1 − n_i/N_i follows. It never runs inside a force evaluation.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "fracture/prefilter_room.hpp"
#include "model/model.hpp"
#include "parallel/halo.hpp"
#include "parallel/index_exchange.hpp"
#include "scene/scene.hpp"

namespace fissure {

class BondBreaking {
 public:
  // Removes the bonds that cross the scene's initial cracks.
  BondBreaking(const Scene& scene, Model& model);
  // From now on find() and apply() test and change only the rows this rank owns (halo.begin()
  // to halo.end()), reading their positions and the ghosts' (docs/mpi.md): a pair
  // whose rows live on two ranks breaks on both in the same call, as each rank learns through
  // the halo's ranks whether the other row's criterion was exceeded. Counts (apply(),
  // broken_bonds()) are then this rank's: its rows' broken bonds, a pair shared with another
  // rank counted on each. Damage is kept for the owned rows only. Collective; the halo must
  // outlive this.
  void distribute(const Halo& halo);
  // Breaks every intact bond whose criterion exceeds s_c in either of its rows; returns how many
  // bonds (pairs) broke, so an integrator can be told that the bond set changed. Over several
  // ranks (distribute()), the pairs broken on all ranks, the same on every rank. Collective.
  std::size_t run(const double* y);
  // run() in two halves: find() marks the bonds whose criterion is exceeded and returns how many
  // (directed; over several ranks also the own bonds whose partner in another rank's row was
  // exceeded there); apply() breaks them and returns how many pairs broke, over several ranks
  // the pairs broken on all ranks (collective: every rank calls it, whatever its find() found).
  std::size_t find(const double* y);
  std::size_t apply();
  // After find(), until the next: the rows apply() changes (those of the exceeded bonds and of
  // their partners), in increasing order; only their energy changes (Model::rows_energy).
  const std::vector<int>& rows_to_change() const { return changing_; }
  // For checkpoints: breaks every bond `broken` marks (1 per directed bond of the whole
  // families, Families::localize) that is intact here, through the model, and recomputes the
  // damage.
  void restore(const std::vector<std::uint8_t>& broken);
  // φ_i = 1 − n_i/N_i (Eq 19), N_i counted before the initial cracks.
  const std::vector<double>& damage() const { return damage_; }
  // 1 for each broken directed bond (CSR order).
  const std::vector<std::uint8_t>& broken() const { return broken_; }
  // Broken bonds, each pair counted once.
  std::size_t broken_bonds() const { return broken_pairs_; }
  // The particles that lost bonds in the last run, in increasing order.
  const std::vector<int>& changed() const { return changed_; }

 private:
  void remove(int i, int b);
  void update_damage(int i);
  // Row i's lower bounds of the deformed length at which a bond can break, after its damage
  // changed (elastic scenes only: with plasticity e^p moves every step).
  void update_prefilter(int i);
  double update_drift(const double* y);
  bool prefilter_row(const double* y, int i, double drift_bound);
  std::size_t find_exact(const double* y, int i);
  std::size_t found(std::size_t exceeded);
  bool owned(int i) const { return i >= row_begin_ && i < row_end_; }

  const Families& families_;
  Model& model_;
  std::vector<double> critical_stretch_;  // s_c per particle (infinite: never breaks)
  std::vector<double> alpha_;             // α per particle
  std::vector<double> horizon_;           // δ per particle
  std::vector<float> reach_;  // ω_ij |ξ| = δ|ξ|/|Gξ| per bond; empty if isotropic (= δ)
  std::vector<std::uint8_t> broken_;    // per directed bond
  std::vector<std::uint8_t> exceeded_;  // per directed bond, this step
  // Per directed bond, below ℓ_c = |ξ| + s_c(1 + αφ_i)ω|ξ|, the deformed length past which the
  // criterion holds: a bond with |y_j − y_i| at or under it cannot break, so find() tests a row
  // exactly only where some bond passes it. +∞ for broken bonds and rows that never break;
  // empty with plasticity.
  std::vector<float> prefilter_;
  PrefilterRoom prefilter_room_ = fissure::prefilter_room();  // the row pass this CPU runs
  // Where rows stand against the prefilter (elastic scenes): the positions of the last full
  // check, each row's slack left at its last check, each particle's drift since (find()).
  std::vector<double> snapshot_, slack_, drift_;
  bool full_check_due_ = true;
  std::vector<int> intact_;     // n_i
  std::vector<double> damage_;  // φ_i
  std::vector<int> changed_;    // rows that lost bonds in the last run
  std::vector<int> exceeding_;  // rows with an exceeded bond, from find() to apply()
  std::vector<int> changing_;   // rows_to_change()
  std::size_t broken_pairs_ = 0;
  // The rows this rank tests and changes: all, or its own (distribute()) with the ghosts whose
  // drift bounds its bonds' changes, the exchange of the criterion's flags of the bonds in the
  // ghosts' rows that pair with its own, and those own bonds.
  int row_begin_ = 0, row_end_ = 0;
  const Halo* halo_ = nullptr;
  // the pairs shared with other ranks, for exceeded_ (distribute(); the halo's)
  const SharedBonds* shared_ = nullptr;
};

}  // namespace fissure
