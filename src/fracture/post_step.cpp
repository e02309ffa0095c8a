#include "fracture/post_step.hpp"

#include <stdexcept>

#include "core/error.hpp"
#include "model/plastic_flow.hpp"
#include "parallel/collective.hpp"

namespace fissure {

PostStep::PostStep(const Scene& scene, Model& model, bool measure_energy)
    : model_(model), measure_energy_(measure_energy) {
  if (scene.config.fracture_enabled())
    bond_breaking_ = std::make_unique<BondBreaking>(scene, model);
  if (scene.config.output.embedded_mesh())
    embedded_mesh_ =
        std::make_unique<EmbeddedMesh>(scene, bond_breaking_ ? &bond_breaking_->broken() : nullptr);
}

bool PostStep::run(const double* y, const double* velocity, double dt) {
  ++calls_;
  // a rank's share of an energy change, summed over the ranks when distributed (collective)
  const auto over_ranks = [&](double share) {
    return halo_ ? sum_over_ranks(halo_->comm(), share) : share;
  };
  if (PlasticFlow* plastic_flow = model_.plastic_flow()) {
    const double stored = measure_energy_ ? model_.elastic_energy(y) : 0;
    // yielded over all ranks (LpsModel::distribute)
    if (plastic_flow->update_plasticity(y) > 0 && measure_energy_)
      released_.plastic += over_ranks(stored - model_.elastic_energy(y));
  }
  bool changed = false;
  if (bond_breaking_) {
    // breaking changes only the energy of the broken bonds' rows
    const bool found = bond_breaking_->find(y) > 0;
    const std::vector<int>& rows = bond_breaking_->rows_to_change();
    const bool measure = measure_energy_ && found;
    const double before = measure ? model_.rows_energy(y, rows) : 0;
    changed = bond_breaking_->apply() > 0;  // over all ranks (BondBreaking::distribute)
    const double released = measure ? before - model_.rows_energy(y, rows) : 0;
    if (changed && measure_energy_) released_.fracture += over_ranks(released);
  }
  if (embedded_mesh_) {
    if (changed) embedded_mesh_->crack(bond_breaking_->broken(), bond_breaking_->changed());
    if (velocity) embedded_mesh_->advance(velocity, dt);
  }
  return changed;
}

void PostStep::distribute(const Halo& halo) {
  if (embedded_mesh_)
    throw std::invalid_argument(
        "output.surface and output.tets cannot be written over several ranks yet (docs/mpi.md)");
  if (bond_breaking_) bond_breaking_->distribute(halo);
  halo_ = &halo;
}

const std::vector<double>* PostStep::damage() const {
  return bond_breaking_ ? &bond_breaking_->damage() : nullptr;
}

std::size_t PostStep::broken_bonds() const {
  return bond_breaking_ ? bond_breaking_->broken_bonds() : 0;
}

NamedArrays PostStep::saved_state() const {
  NamedArrays state = model_.saved_state();
  state.emplace_back("post_step.calls", std::vector<double>{double(calls_)});
  state.emplace_back("post_step.released",
                     std::vector<double>{released_.plastic, released_.fracture});
  return state;
}

std::vector<std::uint8_t> PostStep::broken() const {
  return bond_breaking_ ? bond_breaking_->broken() : std::vector<std::uint8_t>{};
}

void PostStep::restore_state(const Scene& scene, const NamedArrays& state,
                             const std::vector<std::uint8_t>& broken) {
  if (bond_breaking_) {
    if (broken.size() != scene.families.total_directed_bonds())
      throw InputError("", "post_step.broken", "the checkpoint holds another number of bonds");
    bond_breaking_->restore(broken);
    if (embedded_mesh_)
      embedded_mesh_ = std::make_unique<EmbeddedMesh>(scene, &bond_breaking_->broken());
  }
  model_.restore_state(state);
  const std::vector<double>* calls = find_array(state, "post_step.calls");
  const std::vector<double>* released = find_array(state, "post_step.released");
  if (!calls || !released || released->size() != 2)
    throw InputError("", "post_step", "missing from the checkpoint");
  calls_ = static_cast<std::size_t>(calls->at(0));
  released_ = {released->at(0), released->at(1)};
}

}  // namespace fissure
