#pragma once
// Fragments: the connected components of the graph whose edges are the intact bonds. A particle
// that lost every bond is a fragment of its own; separate bodies are separate fragments.
#include "model/model.hpp"
#include "scene/particles.hpp"

namespace fissure {

long count_fragments(const Families& families, const Model& model);

}  // namespace fissure
