#include "contact/collider_registry.hpp"

#include "scene/kind_list.hpp"

namespace fissure {

namespace {

std::vector<ColliderKind>& kinds() {
  static std::vector<ColliderKind> registered = [] {
    std::vector<ColliderKind> builtin;
    add_kind(builtin, sphere_collider_kind(), "collider shape");
    add_kind(builtin, plane_collider_kind(), "collider shape");
    add_kind(builtin, box_collider_kind(), "collider shape");
    return builtin;
  }();
  return registered;
}

}  // namespace

void register_collider(ColliderKind kind) { add_kind(kinds(), std::move(kind), "collider shape"); }

std::vector<std::string> collider_names() { return kind_names(kinds()); }

std::unique_ptr<ColliderShape> make_collider_shape(const Collider& collider) {
  for (const auto& kind : kinds())
    if (kind.name == collider.shape) return kind.make(*collider.options);
  throw std::logic_error("the collider shape '" + collider.shape + "' is not registered");
}

}  // namespace fissure
