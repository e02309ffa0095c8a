#include "contact/collider_registry.hpp"

#include <stdexcept>

namespace fissure {

namespace {

void add(std::vector<ColliderKind>& kinds, ColliderKind kind) {
  for (const auto& k : kinds)
    if (k.name == kind.name)
      throw std::logic_error("the collider shape '" + kind.name + "' is registered twice");
  register_option_parser(ColliderOptionParser{kind.name, kind.keys, kind.parse});
  kinds.push_back(std::move(kind));
}

std::vector<ColliderKind>& kinds() {
  static std::vector<ColliderKind> registered = [] {
    std::vector<ColliderKind> builtin;
    add(builtin, sphere_collider_kind());
    add(builtin, plane_collider_kind());
    add(builtin, box_collider_kind());
    return builtin;
  }();
  return registered;
}

}  // namespace

void register_collider(ColliderKind kind) { add(kinds(), std::move(kind)); }

std::vector<std::string> collider_names() {
  std::vector<std::string> names;
  for (const auto& kind : kinds()) names.push_back(kind.name);
  return names;
}

std::unique_ptr<ColliderShape> make_collider_shape(const Collider& collider) {
  for (const auto& kind : kinds())
    if (kind.name == collider.shape) return kind.make(*collider.options);
  throw std::logic_error("the collider shape '" + collider.shape + "' is not registered");
}

}  // namespace fissure
