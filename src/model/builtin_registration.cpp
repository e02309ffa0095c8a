// Linked into every program that links fissure_model (an INTERFACE source of it,
// CMakeLists.txt): registers the built-in models' option parsers before main, so that a config
// names them even where nothing else of this layer is linked.
#include "model/model_registry.hpp"

namespace {

[[maybe_unused]] const bool registered = !fissure::model_names().empty();

}  // namespace
