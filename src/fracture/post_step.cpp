#include "fracture/post_step.hpp"

namespace fissure {

PostStep::PostStep(const Scene& scene, Model& model) : model_(model) {
  if (scene.config.fracture_enabled())
    bond_breaking_ = std::make_unique<BondBreaking>(scene, model);
}

bool PostStep::run(const double* y) {
  model_.update_plasticity(y);
  return bond_breaking_ && bond_breaking_->run(y) > 0;
}

const std::vector<double>* PostStep::damage() const {
  return bond_breaking_ ? &bond_breaking_->damage() : nullptr;
}

std::size_t PostStep::broken_bonds() const {
  return bond_breaking_ ? bond_breaking_->broken_bonds() : 0;
}

}  // namespace fissure
