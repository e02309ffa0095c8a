// Linked into every program that links fissure_contact (an INTERFACE source of it,
// CMakeLists.txt): registers the built-in collider shapes' option parsers before main, so that a
// config names them even where nothing else of this layer is linked.
#include "contact/collider_registry.hpp"

namespace {

[[maybe_unused]] const bool registered = !fissure::collider_names().empty();

}  // namespace
