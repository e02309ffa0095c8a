#pragma once
// Fragments: the connected components of the graph whose edges are the intact bonds. A particle
// that lost every bond is a fragment of its own; separate bodies are separate fragments.
#include <mpi.h>

#include <cstdint>
#include <vector>

#include "model/model.hpp"
#include "scene/particles.hpp"

namespace fissure {

long count_fragments(const Families& families, const Model& model);
// The same from the broken flags (1 per broken directed bond, CSR order): a run over several
// ranks gathers them on one rank, whose model knows only its own rows. Empty: none broken.
long count_fragments(const Families& families, const std::vector<std::uint8_t>& broken);
// Over the ranks of comm, each with its own rows of the families (Families::first_own_row) and
// their broken flags in its CSR (empty: none broken): the whole scene's fragments on rank 0, 0
// on the others. Each rank joins the particles its rows' intact bonds connect and sends rank 0
// each joined particle's representative. Collective.
long count_fragments(MPI_Comm comm, const Families& families,
                     const std::vector<std::uint8_t>& broken);

}  // namespace fissure
