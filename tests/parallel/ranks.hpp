#pragma once
// What the MPI tests share: this rank and their number, sums over the ranks, the slab they cut,
// and what a rank knows of the positions (its own rows and, through the halo, its ghosts).
#include <gtest/gtest.h>
#include <petscsys.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "model/model.hpp"
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

// MPI_Barrier on `comm`, sleeping between polls: OpenMPI's blocking barrier spins, and on a
// machine with fewer cores than ranks the spinning ranks halve the speed of a rank that computes
// alone (a one-rank reference run), where a sleeping one leaves it the core.
inline void idle_barrier(MPI_Comm comm = PETSC_COMM_WORLD) {
  MPI_Request request;
  ASSERT_EQ(MPI_Ibarrier(comm, &request), MPI_SUCCESS);
  for (int done = 0;; std::this_thread::sleep_for(std::chrono::milliseconds(1))) {
    ASSERT_EQ(MPI_Test(&request, &done, MPI_STATUS_IGNORE), MPI_SUCCESS);
    if (done) return;
  }
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

// A general deformation of the slab plus a different small displacement on every particle.
inline std::vector<double> perturbed(const Particles& p) {
  const double F[9] = {1.02, 0.03, -0.01, 0.01, 0.97, 0.02, -0.02, 0.01, 1.01};
  std::vector<double> y = deform(p, F);
  for (std::size_t k = 0; k < y.size(); ++k) y[k] += 1e-4 * std::sin(12.9898 * double(k));
  return y;
}

// A slab's material and whether its crack is broken (break_crack_bonds), for the tests that
// compare a distributed model with one rank's.
struct ModelCase {
  std::string name, material;
  bool cracked;
};

// The models those tests compare: intact, pre-cracked, with either surface correction.
inline std::vector<ModelCase> model_cases() {
  return {{"intact", "", false},
          {"pre-cracked", "", true},
          {"full surface correction, pre-cracked", ", surface_correction: full", true},
          {"no surface correction", ", surface_correction: none", false}};
}

// Every bond of rows [first, end) crossing x = 0.15 below mid-height (a crack across the
// ranks' cuts).
inline void break_crack_bonds(const Scene& scene, Model& model, int first, int end) {
  const auto& x = scene.particles.reference;
  const Families& f = scene.families;
  for (int i = first; i < end; ++i)
    for (int b = f.offsets[i]; b < f.offsets[i + 1]; ++b) {
      const int j = f.neighbors[b];
      if ((x[3 * i] - 0.15) * (x[3 * j] - 0.15) < 0 && x[3 * i + 1] + x[3 * j + 1] < 0.1)
        model.break_bond(i, b);
    }
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
