#pragma once
// Short-range repulsion between particles that are not bonded (separate bodies, and fragments
// once their bonds broke), so bodies and fragments collide instead of passing through each
// other (contact.self). Pairs are found on a uniform cell grid rebuilt at every evaluation.
#include <vector>

#include "model/model.hpp"
#include "scene/scene.hpp"

namespace fissure {

class SelfContact {
 public:
  SelfContact(const Scene& scene, const Model& model);
  // Adds the repulsion k (d_c − d) n between every unbonded pair closer than d_c = r_i + r_j to
  // f (3N), with r = ½V^(1/3) and k the mean of the two particles' contact stiffness.
  void add_forces(const double* y, double* f);

 private:
  void build_grid(const double* y);

  const Families& families_;
  const Model& model_;
  std::vector<double> radius_, stiffness_;
  double cell_ = 0;  // the largest contact reach, 2 max r
  double size_ = 0;  // cell edge of the current grid (≥ cell_)
  // Cell grid over the current bounding box: particles sorted by cell (CSR).
  double origin_[3] = {0, 0, 0};
  int dims_[3] = {1, 1, 1};
  std::vector<int> cell_start_, cell_particles_, cell_of_;
};

}  // namespace fissure
