#pragma once
// Fragments: the connected components of the graph whose edges are the intact bonds. A particle
// that lost every bond is a fragment of its own; separate bodies are separate fragments.
#include <cstdint>
#include <vector>

#include "model/model.hpp"
#include "scene/particles.hpp"

namespace fissure {

long count_fragments(const Families& families, const Model& model);
// The same from the broken flags (1 per broken directed bond, CSR order): a run over several
// ranks gathers them on one rank, whose model knows only its own rows. Empty: none broken.
long count_fragments(const Families& families, const std::vector<std::uint8_t>& broken);

}  // namespace fissure
