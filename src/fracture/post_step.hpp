#pragma once
// The post-step every integrator hands over to after a completed step (never inside a force
// evaluation): the plastic return map (paper §4.2), then bond breaking (§5.1). Only the effects
// the scene asks for run.
#include <memory>

#include "fracture/bond_breaking.hpp"
#include "model/model.hpp"
#include "scene/scene.hpp"

namespace fissure {

class PostStep {
 public:
  PostStep(const Scene& scene, Model& model);
  // Returns true if the bond set changed, so the integrator must drop what it derived from it.
  bool run(const double* y);
  // φ per particle, or nullptr without fracture.
  const std::vector<double>* damage() const;
  std::size_t broken_bonds() const;

 private:
  Model& model_;
  std::unique_ptr<BondBreaking> bond_breaking_;
};

}  // namespace fissure
