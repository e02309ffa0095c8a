#pragma once
// The collider shapes a scene can name (the shape's key in a colliders entry: sphere, plane,
// box), each registered in one place next to its code: its name, its own keys and their parser
// (scene/option_parsers.hpp) and its constructor. The built-in ones are registered on first use
// of the registry and, through builtin_registration.cpp, at start-up of every program linked to
// this layer, so that config parsing sees them; a test registers its own with register_collider.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "contact/collider_shape.hpp"
#include "scene/config.hpp"

namespace fissure {

struct ColliderKind {
  std::string name;
  std::vector<std::string> keys;  // its own keys under colliders[i].<name>
  // Reads them (null: the shape has none); the result is Collider::options.
  std::function<std::shared_ptr<const ColliderOptions>(const OptionReader&)> parse;
  // Makes the shape from its options.
  std::function<std::unique_ptr<ColliderShape>(const ColliderOptions&)> make;
};

// Adds `kind` and its option parser; throws std::logic_error if the name is taken.
void register_collider(ColliderKind kind);
std::vector<std::string> collider_names();

// The shape of a parsed colliders entry.
std::unique_ptr<ColliderShape> make_collider_shape(const Collider& collider);

// The options a shape's parser made, as the shape's own type.
template <class Options>
const Options& shape_options(const ColliderOptions& options) {
  return dynamic_cast<const Options&>(options);
}

// The built-in shapes, one file each.
ColliderKind sphere_collider_kind();
ColliderKind plane_collider_kind();
ColliderKind box_collider_kind();

}  // namespace fissure
