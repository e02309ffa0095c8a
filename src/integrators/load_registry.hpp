#pragma once
// The loads a run may have, in the order of their energy-ledger entries (probes.csv's ledger
// columns, summary.json's energy block): gravity_work, constraint_work, collider_work,
// damping_loss, contact_loss, then those added by register_load(). A scene without a load books
// 0 in its entry.
#include <memory>
#include <string>
#include <vector>

#include "integrators/load.hpp"
#include "model/model.hpp"
#include "scene/scene.hpp"

namespace fissure {

struct LoadKind {
  std::string entry;  // its ledger entry
  Booking booking;
  // The load of `scene`, or nullptr when the scene asks for none. Empty for constraint_work,
  // which the kinematic constraints book (integrators/constraints.hpp).
  std::function<std::unique_ptr<Load>(const Scene&, const Model&)> make;
};

// Adds a kind after every earlier one: a new load is a file that registers itself.
void register_load(LoadKind kind);
// The built-in kinds, then the registered ones.
std::vector<LoadKind> load_kinds();

// The built-in loads (one file each).
std::unique_ptr<Load> make_gravity_load(const Scene& scene);
std::unique_ptr<Load> make_damping_load(const Scene& scene);
std::unique_ptr<Load> make_collider_load(const Scene& scene);
std::unique_ptr<Load> make_self_contact_load(const Scene& scene, const Model& model);

}  // namespace fissure
