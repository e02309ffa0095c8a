#pragma once
// Short-range repulsion between particles that are not bonded (separate bodies, and fragments
// once their bonds broke), so bodies and fragments collide instead of passing through each
// other (contact.self).
//
// Pairs come from a Verlet list with a skin: every pair closer than r_i + r_j + skin, bonded or
// not, found on a uniform cell grid (cells of the largest reach + skin) and kept per particle in
// CSR form with the index of the bond to j in i's family row (−1 if none). The list is rebuilt
// only once the particles have moved more than skin/2 since the last build, not counting what
// they moved together (add_forces): a pair left out was at least r_i + r_j + skin apart then
// and so is still at least r_i + r_j apart, out of reach. Bonded pairs interact through the
// model only, so each row's candidates are split into those that can touch (no bond, or a broken
// one) first, in increasing j, and the pairs of intact bonds after them; evaluations walk the
// first part alone. The split is redone whenever the model's revision changed (a bond broke,
// plastic flow, a restore), so a bond that breaks between builds turns its pair into a contact
// pair at once, with no rebuild.
//
// The forces are those of the former search of the 27 cells at every evaluation to round-off:
// each particle's sum now runs over its partners in increasing j instead of in cell order, which
// changes only the order of summation. That order does not depend on when the list was built,
// so the forces are a function of the positions and the intact bonds alone (a resumed run, which
// builds its list afresh, adds in the same order as an uninterrupted one).
//
// Bodies may start touching as sampled (a block on another): a pair of particles with no bond
// between them (in the families) closer than r_i + r_j at load caps both radii at half its
// distance, so that every pair starts without force and presses only when it moves closer (the
// colliders' rule, contact/colliders.hpp).
#include <cstddef>
#include <vector>

#include "model/model.hpp"
#include "scene/scene.hpp"

namespace fissure {

class SelfContact {
 public:
  SelfContact(const Scene& scene, const Model& model);
  // Adds the repulsion k (d_c − d) n between every unbonded pair closer than d_c = r_i + r_j to
  // f (3N), with r = ½V^(1/3) (capped where the pair started closer, above) and k the mean of the
  // two particles' contact stiffness.
  void add_forces(const double* y, double* f);

  // The same repulsion as a potential, for implicit integrators (docs/integrators.md, "Contact"):
  // B(z) = Σ over unbonded pairs ½ k (d_c − d)² [J], returned; adds ∇B to `gradient` (3N, or
  // null) and, per particle i, the diagonal block Σ_j k n nᵀ of its positive-semidefinite
  // Hessian to `blocks` (9 per particle, or null). The Hessian's pair blocks (−k n nᵀ between i and
  // j) act through add_coupling.
  double potential(const double* z, double* gradient, double* blocks);
  // Adds the off-diagonal part of that Hessian times v to out (3N): −Σ_j k n nᵀ v_j for each i,
  // at z (which potential() was last evaluated at or near: its Verlet list).
  void add_coupling(const double* z, const double* v, double* out) const;
  // The largest fraction α ≤ 1 of the update dz that keeps every particle within skin/2 of a
  // common motion (as the list's rebuild rule measures it), so that pairs move by at most the
  // skin relative to each other and none passes through another's reach within one update.
  double max_step(const double* dz) const;

  // The Verlet list's skin [m] and how many times the list has been built (for tests).
  double skin() const { return skin_; }
  std::size_t builds() const { return builds_; }

 private:
  // Rebuilds the Verlet list if the particles moved more than skin/2 since it was built, or
  // re-splits its rows if bonds changed; false (and nothing done) if y is not finite.
  bool update_list(const double* y);
  // Calls pair(i, j, d, |d|, overlap, k, sum) for every touching pair within reach, row by row
  // in increasing j (each unordered pair twice), d = y_i − y_j, then finish(i, sum)
  // with the row's 3-vector sum (zero at the row's start); rows in parallel.
  template <class Pair, class Finish>
  void for_each_touching(const double* y, Pair&& pair, Finish&& finish) const;
  // Caps the radii of the pairs that overlap at y (the reference positions): see above.
  void start_at_rest(const double* y);
  void build_grid(const double* y);
  void build_list(const double* y);
  void split_rows();

  const Families& families_;
  const Model& model_;
  std::vector<double> radius_, stiffness_;
  double reach_ = 0;  // the largest contact reach, 2 max r
  double skin_ = 0;   // the list holds the pairs within r_i + r_j + skin
  // Cell grid over the bounding box at the last build: particles sorted by cell (CSR).
  double size_ = 0;  // cell edge (≥ reach_ + skin_)
  double origin_[3] = {0, 0, 0};
  int dims_[3] = {1, 1, 1};
  std::vector<int> cell_start_, cell_particles_, cell_of_;
  // The Verlet list: particle i's candidates are candidates_[list_start_[i] .. list_start_[i+1]),
  // in increasing j; bond is the directed bond i → j in the families, or −1.
  struct Candidate {
    int j;
    int bond;
  };
  std::vector<int> list_start_;
  std::vector<Candidate> candidates_;
  // Row i's candidates that can touch are [list_start_[i], touching_end_[i]), in increasing j;
  // split at the model's revision split_revision_.
  std::vector<int> touching_end_;
  std::size_t split_revision_ = 0;
  std::vector<double> built_at_;  // 3N positions at the last build (empty before the first)
  std::size_t builds_ = 0;
};

}  // namespace fissure
