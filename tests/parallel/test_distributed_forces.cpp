// Forces over several ranks (issue 18, acceptance: "forces at a perturbed state bitwise equal to
// one rank"): each rank evaluates its own rows from its rows' and its ghosts' positions alone,
// and gets the bits one rank gets for them, with broken bonds and with both surface
// corrections. The reference is the whole scene evaluated on each rank by an undistributed model.
#include <gtest/gtest.h>
#include <petscsys.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "model/model.hpp"
#include "ranks.hpp"
#include "support/scenes.hpp"

namespace fissure {
namespace {

struct Case {
  std::string name, material;
  bool cracked;
};

TEST(DistributedForces, EqualOneRankBitwise) {
  for (const Case& c :
       {Case{"intact", "", false}, Case{"pre-cracked", "", true},
        Case{"full surface correction, pre-cracked", ", surface_correction: full", true},
        Case{"no surface correction", ", surface_correction: none", false}}) {
    SCOPED_TRACE(c.name);
    const Scene scene = test::slab(c.material);
    const int n = scene.particles.count();
    const std::vector<double> y = test::perturbed(scene.particles);
    auto whole = make_model(scene);
    auto part = make_model(scene);
    if (c.cracked) {
      test::break_crack_bonds(scene, *whole, 0, scene.particles.count());
      test::break_crack_bonds(scene, *part, 0, scene.particles.count());
    }
    std::vector<double> expected(3 * std::size_t(n));
    const double energy = whole->forces_and_energy(y.data(), expected.data());

    const Halo halo = test::split_halo(scene);
    part->distribute(halo);
    // this rank knows its own rows' positions only; the halo brings the ghosts'
    const std::vector<double> known = test::known_positions(y, halo);
    std::vector<double> force(y.size(), 0.0);
    const double share = part->forces_and_energy(known.data(), force.data());
    // on several ranks, rows that read ghosts' positions and terms (a missing exchange of either
    // changes their forces)
    int boundary_rows = 0;
    for (int i = halo.begin(); i < halo.end(); ++i) {
      bool reads_ghost = false;
      for (int b = scene.families.offsets[i]; b < scene.families.offsets[i + 1]; ++b)
        reads_ghost |=
            scene.families.neighbors[b] < halo.begin() || scene.families.neighbors[b] >= halo.end();
      boundary_rows += reads_ghost;
    }
    if (test::ranks() > 1) {
      EXPECT_GT(boundary_rows, 0);
    }
    // counted, not asserted: a rank that left early would leave the others in a collective call
    int differing = 0;
    for (int i = halo.begin(); i < halo.end(); ++i)
      differing += std::memcmp(&force[3 * i], &expected[3 * i], 3 * sizeof(double)) != 0;
    EXPECT_EQ(differing, 0);
    // forces() gives the same bits as forces_and_energy()
    std::vector<double> plain(y.size(), 0.0);
    part->forces(known.data(), plain.data());
    EXPECT_EQ(plain, force);
    // the ranks' shares of Π add up to one rank's Π (summed in another order: to round-off)
    double total = 0;
    MPI_Allreduce(&share, &total, 1, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
    EXPECT_NEAR(total, energy, 1e-12 * std::abs(energy));
    EXPECT_GT(std::abs(energy), 0.0);
  }
}

TEST(DistributedForces, ModelsThatCannotBeDistributedSaySo) {
  const Scene elastic = test::slab();
  const Halo halo = test::split_halo(elastic);
  const Scene plastic = test::slab(", plasticity: {yield_stress: 1.0e4}");
  auto model = make_model(plastic);
  EXPECT_EQ(test::refusal([&] { model->distribute(halo); }),
            "material.plasticity cannot be evaluated over several ranks yet (docs/mpi.md)");
  const Scene paper = test::slab("", "", "paper");
  auto paper_model = make_model(paper);
  EXPECT_EQ(test::refusal([&] { paper_model->distribute(halo); }),
            "material.model paper cannot be evaluated over several ranks yet (docs/mpi.md)");
}

}  // namespace
}  // namespace fissure
