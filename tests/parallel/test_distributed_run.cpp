// The explicit integrators over several ranks (a velocity Verlet fracture run with a pre-crack
// crossing rank boundaries gives positions, damage and broken bonds bitwise equal to one rank's):
// a slab with a pre-crack across the ranks' cuts, pulled apart at both ends under
// gravity, stepped with the fracture search after every step; at every step each rank's rows
// hold one rank's bits. The step loop is the run loop's (integrator step, then bond breaking);
// the whole run loop over ranks is DistributedRunLoop's (test_distributed_run_loop.cpp).
#include <gtest/gtest.h>
#include <petscsys.h>

#include <cstring>
#include <string>
#include <vector>

#include "fracture/bond_breaking.hpp"
#include "integrators/integrator.hpp"
#include "ranks.hpp"

namespace fissure {
namespace {

Scene pulled_slab() {
  return test::slab(", fracture: {critical_stretch: 0.01, alpha: 1.0}",
                    "gravity: [0, -9.81, 0]\n"
                    "initial_cracks:\n"
                    "  - {plane: {point: [0.15, 0, 0], normal: [1, 0, 0], region: {box: {min: "
                    "[-1, -1, -1], max: [1, 0.04, 1]}}}}\n"
                    "constraints:\n"
                    "  - {region: {box: {min: [-1, -1, -1], max: [0.03, 1, 1]}}, velocity: [-2, "
                    "0, 0]}\n"
                    "  - {region: {box: {min: [0.27, -1, -1], max: [1, 1, 1]}}, velocity: [2, 0, "
                    "0]}\n");
}

struct Stepper {
  std::unique_ptr<Model> model;
  std::unique_ptr<Dynamics> dynamics;
  std::unique_ptr<BondBreaking> fracture;
  std::unique_ptr<Integrator> integrator;
  State state;
  Stepper(const Scene& scene, const std::string& integrator_type)
      : model(make_model(scene)),
        dynamics(std::make_unique<Dynamics>(scene, *model)),
        fracture(std::make_unique<BondBreaking>(scene, *model)),
        integrator(make_integrator(integrator_type, "test")),
        state{scene.particles.reference, scene.particles.velocity, 0.0} {}
  void step(double dt) {
    integrator->step(*dynamics, state, dt);
    dynamics->end_step(dt);
    if (fracture->run(state.position.data()) > 0) integrator->bonds_changed();
  }
};

TEST(DistributedRun, ExplicitFractureRunsEqualOneRankAtEveryStep) {
  for (const std::string type : {"velocity_verlet", "symplectic_euler"}) {
    SCOPED_TRACE(type);
    const Scene scene = pulled_slab();
    const Families& families = scene.families;
    Stepper whole(scene, type), part(scene, type);
    ASSERT_TRUE(part.integrator->distributable());
    const Halo halo = test::split_halo(scene);
    part.dynamics->distribute(halo);
    part.fracture->distribute(halo);
    const double dt = 0.5 * whole.model->stable_time_step();
    const long initial = static_cast<long>(whole.fracture->broken_bonds());
    // counted, not asserted: a rank that left early would leave the others in a collective call.
    // 100 steps: most bonds break in the first 25, the pairs across the cuts within the first 75
    // (on 2 and 3 ranks)
    long differing = 0;
    for (int s = 0; s < 100; ++s) {
      whole.step(dt);
      part.step(dt);
      for (int i = halo.begin(); i < halo.end(); ++i) {
        differing += std::memcmp(&part.state.position[3 * i], &whole.state.position[3 * i],
                                 3 * sizeof(double)) != 0;
        differing += std::memcmp(&part.state.velocity[3 * i], &whole.state.velocity[3 * i],
                                 3 * sizeof(double)) != 0;
        differing += part.fracture->damage()[i] != whole.fracture->damage()[i];
        for (int b = families.offsets[i]; b < families.offsets[i + 1]; ++b)
          differing += part.fracture->broken()[b] != whole.fracture->broken()[b];
      }
    }
    EXPECT_EQ(differing, 0);
    long shared_broken = 0;
    for (int i = halo.begin(); i < halo.end(); ++i)
      for (int b = families.offsets[i]; b < families.offsets[i + 1]; ++b)
        shared_broken += part.fracture->broken()[b] && (families.neighbors[b] < halo.begin() ||
                                                        families.neighbors[b] >= halo.end());
    const long broken = static_cast<long>(whole.fracture->broken_bonds());
    EXPECT_GT(broken, initial + 10);  // the pull broke bonds beyond the pre-crack
    if (test::ranks() > 1) {
      EXPECT_GT(test::sum_over_ranks(shared_broken), 0);  // and pairs across the cuts
    }
    RecordProperty("broken_bonds", static_cast<int>(broken));
  }
}

TEST(DistributedRun, LoadsThatReadOtherParticlesSaySo) {
  const Scene scene = test::slab("", "contact: {self: true}\n");
  auto model = make_model(scene);
  Dynamics dynamics(scene, *model);
  const Halo halo = test::split_halo(scene);
  EXPECT_EQ(test::refusal([&] { dynamics.distribute(halo); }),
            "contact.self cannot run over several ranks yet (docs/mpi.md)");
  EXPECT_TRUE(make_integrator("petsc_newton", "test")->distributable());  // auto: gamg
}

}  // namespace
}  // namespace fissure
