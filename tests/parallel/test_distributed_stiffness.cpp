// The stiffness the implicit integrators need, over several ranks: the
// matrix-free tangent product, the majoriser's rows and the nearest members' rows, evaluated on
// each rank's own rows from its rows' and its ghosts' values alone, equal one rank's bit for
// bit, intact and with a crack broken as fracture breaks it over ranks: each rank breaks its own
// rows' bonds only, so its copies of other ranks' rows keep their bonds. A product that skipped
// the exchange of the ghosts' terms between its two passes, or read a ghost's stale v, or a
// majoriser that took a ghost's bond stiffness from its copy of that ghost's row, would differ
// on the rows next to the cuts.
#include <gtest/gtest.h>
#include <petscsys.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "linear/nearest_bonds.hpp"
#include "linear/sparse_symmetric.hpp"
#include "model/model.hpp"
#include "model/stiffness.hpp"
#include "ranks.hpp"
#include "support/scenes.hpp"

namespace fissure {
namespace {

TEST(DistributedStiffness, TangentProductMajoriserAndNearestRowsEqualOneRankBitwise) {
  for (const bool cracked : {false, true}) {
    SCOPED_TRACE(cracked ? "cracked, each rank its own rows" : "intact");
    const Scene scene = test::slab();
    const std::vector<double> y = test::perturbed(scene.particles);
    std::vector<double> v(y.size());
    for (std::size_t k = 0; k < v.size(); ++k) v[k] = std::cos(3.7 * double(k));
    auto whole = make_model(scene);
    auto part = make_model(scene);
    const Halo halo = test::split_halo(scene);
    if (cracked) {
      test::break_crack_bonds(scene, *whole, 0, scene.particles.count());
      test::break_crack_bonds(scene, *part, halo.begin(), halo.end());
    }
    Stiffness& K = *whole->stiffness();
    std::vector<double> expected(y.size());
    K.linearize(y.data(), false);
    K.apply_tangent(v.data(), expected.data());
    SparseSymmetric majoriser = bond_pattern(scene.families);
    K.assemble_majoriser(y.data(), majoriser);
    const std::vector<char> kept = nearest_bonds(scene.families, kNearestMembers);
    SparseSymmetric nearest = nearest_bond_pattern(scene.families, kept);
    K.assemble_nearest_stiffness(y.data(), kept, nearest);

    part->distribute(halo);
    Stiffness& P = *part->stiffness();
    // this rank knows its own rows' y and v only; the halo brings the ghosts'
    const std::vector<double> known_y = test::known_positions(y, halo);
    const std::vector<double> known_v = test::known_positions(v, halo);
    std::vector<double> product(y.size(), 0.0);
    P.linearize(known_y.data(), false);
    P.apply_tangent(known_v.data(), product.data());
    // the rank's rows of the pattern only, as petsc_newton keeps it over several ranks
    SparseSymmetric rows = bond_pattern(scene.families, halo.begin(), halo.end());
    P.assemble_majoriser(known_y.data(), rows);
    SparseSymmetric nearest_rows =
        nearest_bond_pattern(scene.families, kept, halo.begin(), halo.end());
    P.assemble_nearest_stiffness(known_y.data(), kept, nearest_rows);
    // the rows of `a` of particle i against those of `b`: 1 where they differ
    const auto differ = [](const SparseSymmetric& a, const SparseSymmetric& b, int i) {
      int count = 0;
      for (int r = 3 * i; r < 3 * i + 3; ++r) {
        const int length = a.offsets[r + 1] - a.offsets[r];
        count += length != b.offsets[r + 1] - b.offsets[r] ||
                 std::memcmp(&a.values[a.offsets[r]], &b.values[b.offsets[r]],
                             length * sizeof(double)) != 0;
      }
      return count;
    };
    // counted, not asserted: a rank that left early would leave the others in a collective call
    int differing = 0, differing_matrix = 0, differing_nearest = 0;
    for (int i = halo.begin(); i < halo.end(); ++i) {
      differing += std::memcmp(&product[3 * i], &expected[3 * i], 3 * sizeof(double)) != 0;
      differing_matrix += differ(rows, majoriser, i);
      differing_nearest += differ(nearest_rows, nearest, i);
    }
    EXPECT_EQ(differing, 0);
    EXPECT_EQ(differing_matrix, 0);
    EXPECT_EQ(differing_nearest, 0);
    // the product is not trivially zero where it is compared
    double norm = 0;
    for (int k = 3 * halo.begin(); k < 3 * halo.end(); ++k) norm += product[k] * product[k];
    EXPECT_GT(norm, 0.0);
  }
}

}  // namespace
}  // namespace fissure
