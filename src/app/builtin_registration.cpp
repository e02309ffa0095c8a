// Linked into every program that links fissure_app (an INTERFACE source of it, CMakeLists.txt):
// registers the built-in outputs before main, so that config parsing sees every output's keys.
#include "app/output_registry.hpp"

namespace {

[[maybe_unused]] const bool registered = !fissure::output_kinds().empty();

}  // namespace
