// Forces over several ranks, at a perturbed state bitwise equal to one rank's: each rank evaluates
// its own rows from its rows' and its ghosts' positions alone, and gets the bits one rank gets for
// them, with broken bonds and with both surface corrections. The reference is the whole scene
// evaluated on each rank by an undistributed model.
#include <gtest/gtest.h>
#include <petscsys.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "model/model.hpp"
#include "model/plastic_flow.hpp"
#include "ranks.hpp"
#include "support/scenes.hpp"

namespace fissure {
namespace {

TEST(DistributedForces, EqualOneRankBitwise) {
  for (const test::ModelCase& c : test::model_cases()) {
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

// The return map over several ranks, which changes the plastic extension: each
// rank maps its own rows' bonds and takes e^p_ji of the pairs it shares from row j's rank. Two
// return maps at two states, each followed by the forces at a third: the own rows' forces, yield
// counts and e^p (the own bonds' and the shared pairs' reverses) are one rank's bits.
TEST(DistributedForces, PlasticReturnMapEqualsOneRankBitwise) {
  const Scene scene = test::slab(", plasticity: {yield_stress: 1.0e4}");
  const Families& f = scene.families;
  const int n = scene.particles.count();
  const std::vector<double> first = test::perturbed(scene.particles);
  std::vector<double> second = first, third = first;
  for (std::size_t k = 0; k < first.size(); ++k) {
    second[k] += 2e-4 * std::sin(7.31 * double(k));
    third[k] -= 1e-4 * std::cos(3.17 * double(k));
  }
  auto whole = make_model(scene);
  auto part = make_model(scene);
  const Halo halo = test::split_halo(scene);
  part->distribute(halo);
  const std::vector<double>* const states[2][2] = {{&first, &second}, {&second, &third}};
  for (const auto& [flow, at] : states) {
    std::vector<double> expected(3 * std::size_t(n)), force(3 * std::size_t(n), 0.0);
    const std::size_t yielded = whole->plastic_flow()->update_plasticity(flow->data());
    whole->forces(at->data(), expected.data());
    EXPECT_EQ(part->plastic_flow()->update_plasticity(test::known_positions(*flow, halo).data()),
              yielded);
    EXPECT_GT(yielded, 100u);
    part->forces(test::known_positions(*at, halo).data(), force.data());
    const std::vector<double>& ep = whole->plastic_flow()->plastic_extension();
    const std::vector<double>& ep_part = part->plastic_flow()->plastic_extension();
    // counted, not asserted: a rank that left early would leave the others in a collective call
    int differing_rows = 0, differing_bonds = 0, flowed_across = 0;
    for (int i = halo.begin(); i < halo.end(); ++i) {
      differing_rows += std::memcmp(&force[3 * i], &expected[3 * i], 3 * sizeof(double)) != 0;
      for (int b = f.offsets[i]; b < f.offsets[i + 1]; ++b) {
        const int j = f.neighbors[b], r = f.reverse[b];
        differing_bonds += std::memcmp(&ep_part[b], &ep[b], sizeof(double)) != 0;
        if (j >= halo.begin() && j < halo.end()) continue;
        differing_bonds += std::memcmp(&ep_part[r], &ep[r], sizeof(double)) != 0;
        flowed_across += ep[r] != 0;
      }
    }
    EXPECT_EQ(differing_rows, 0);
    EXPECT_EQ(differing_bonds, 0);
    // pairs cut by the ranks flowed on the other rank's side: their exchange is tested
    if (test::ranks() > 1) {
      EXPECT_GT(flowed_across, 0);
    }
  }
}

TEST(DistributedForces, ModelsThatCannotBeDistributedSaySo) {
  const Scene elastic = test::slab();
  const Halo halo = test::split_halo(elastic);
  const Scene paper = test::slab("", "", "paper");
  auto paper_model = make_model(paper);
  EXPECT_EQ(test::refusal([&] { paper_model->distribute(halo); }),
            "material.model paper cannot be evaluated over several ranks yet (docs/mpi.md)");
}

}  // namespace
}  // namespace fissure
