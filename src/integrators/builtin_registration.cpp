// Linked into every program that links fissure_integrators (an INTERFACE source of it,
// CMakeLists.txt): registers the built-in integrators' option parsers before main, so that a
// config names them even where nothing else of this layer is linked.
#include "integrators/integrator.hpp"

namespace {

[[maybe_unused]] const bool registered = !fissure::integrator_names().empty();

}  // namespace
