#include "integrators/load_registry.hpp"

namespace fissure {

namespace {

std::vector<LoadKind>& registered() {
  static std::vector<LoadKind> kinds;
  return kinds;
}

}  // namespace

void register_load(LoadKind kind) { registered().push_back(std::move(kind)); }

std::vector<LoadKind> load_kinds() {
  std::vector<LoadKind> kinds = {
      {"gravity_work", Booking::work,
       [](const Scene& s, const Model&) { return make_gravity_load(s); }},
      {"constraint_work", Booking::work, nullptr},
      {"collider_work", Booking::work,
       [](const Scene& s, const Model&) { return make_collider_load(s); }},
      {"damping_loss", Booking::loss,
       [](const Scene& s, const Model&) { return make_damping_load(s); }},
      {"contact_loss", Booking::loss,
       [](const Scene& s, const Model& m) { return make_self_contact_load(s, m); }},
  };
  for (const LoadKind& kind : registered()) kinds.push_back(kind);
  return kinds;
}

}  // namespace fissure
