#pragma once
// What the MPI tests share: this rank and their number, sums over the ranks, the slab they cut,
// and what a rank knows of the positions (its own rows and, through the halo, its ghosts).
#include <petscsys.h>

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "parallel/halo.hpp"
#include "parallel/ownership.hpp"
#include "support/scenes.hpp"

namespace fissure::test {

inline int rank() {
  int r = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &r);
  return r;
}

inline int ranks() {
  int size = 0;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  return size;
}

inline long sum_over_ranks(long value) {
  long total = 0;
  MPI_Allreduce(&value, &total, 1, MPI_LONG, MPI_SUM, PETSC_COMM_WORLD);
  return total;
}

// A 0.3 × 0.1 × 0.05 m slab at λ = 0.02 (about 2,100 particles): cut across its length by the
// ranks' Morton ranges. `material` and `scene` are appended as in Block.
inline Scene slab(const std::string& material = "", const std::string& scene = "",
                  const std::string& model = "lps") {
  return block_scene({.size = {0.3, 0.1, 0.05},
                      .resolution = 0.02,
                      .bulk = 2.0e6,
                      .shear = 1.0e6,
                      .model = model,
                      .material = material,
                      .scene = scene});
}

// The rows of a scene split over the ranks by bonds.
inline Halo split_halo(const Scene& scene) {
  return Halo(PETSC_COMM_WORLD, scene.families,
              split_rows_by_bonds(scene.families.offsets, ranks()));
}

// y as this rank knows it: its own rows' positions, the ghosts' filled by the halo, NaN
// elsewhere (so that reading another particle shows).
inline std::vector<double> known_positions(const std::vector<double>& y, const Halo& halo) {
  std::vector<double> known(y.size(), std::numeric_limits<double>::quiet_NaN());
  std::copy(y.begin() + 3 * halo.begin(), y.begin() + 3 * halo.end(),
            known.begin() + 3 * halo.begin());
  halo.fill(known.data(), 3);
  return known;
}

// The message of the std::invalid_argument `call` throws, or "" if it returns: what a part that
// cannot run over several ranks says.
template <class Call>
std::string refusal(Call&& call) {
  try {
    call();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

}  // namespace fissure::test
