#include "fracture/post_step.hpp"

namespace fissure {

PostStep::PostStep(const Scene& scene, Model& model) : model_(model) {
  if (scene.config.fracture_enabled())
    bond_breaking_ = std::make_unique<BondBreaking>(scene, model);
  if (scene.config.output.embedded_mesh())
    embedded_mesh_ =
        std::make_unique<EmbeddedMesh>(scene, bond_breaking_ ? &bond_breaking_->broken() : nullptr);
}

bool PostStep::run(const double* y, const double* velocity, double dt) {
  ++calls_;
  model_.update_plasticity(y);
  const bool changed = bond_breaking_ && bond_breaking_->run(y) > 0;
  if (embedded_mesh_) {
    if (changed) embedded_mesh_->crack(bond_breaking_->broken(), bond_breaking_->changed());
    if (velocity) embedded_mesh_->advance(velocity, dt);
  }
  return changed;
}

const std::vector<double>* PostStep::damage() const {
  return bond_breaking_ ? &bond_breaking_->damage() : nullptr;
}

std::size_t PostStep::broken_bonds() const {
  return bond_breaking_ ? bond_breaking_->broken_bonds() : 0;
}

}  // namespace fissure
