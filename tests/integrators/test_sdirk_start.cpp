// Where an SDIRK stage's Newton solve starts (ImplicitScheme::guess): a stage after another starts
// from its stage equation with the previous stage's acceleration held, an O(h³) distance from the
// stage's solution. On the undamped oscillator y'' = −ω²y every stage equation A(Y − ỹ) = −ω²Y is
// solved exactly, Y = Aỹ/(A + ω²), so the distance from the start to each stage's solution is
// known; halving h must divide it by about 8 (measured 7.97–7.99). Starting from the previous
// stage's solution (the start before) is O(h) away (ratio 2), and from ỹ alone O(h²) (measured
// 4.19): both fail the bound of 6.5.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "integrators/implicit_scheme.hpp"

namespace fissure {
namespace {

// The largest distance, over the stages that follow another, between the start of a stage and
// its solution, in one step of size h from y = 0.2, v = 1 (one unknown).
double largest_start_distance(PetscNewtonSettings::Scheme which, double h) {
  const double omega = 2.0;
  ImplicitScheme scheme(which, 0.5);
  State state;
  state.position = {0.2};
  state.velocity = {1.0};
  const std::vector<double> acceleration = {-omega * omega * state.position[0]};
  double largest = 0;
  for (int stage = 0; stage < scheme.stages(); ++stage) {
    scheme.predict(state, acceleration, 0.0, h, stage);
    if (scheme.explicit_stage()) continue;
    const double a = scheme.inertia();
    const double solution = a * scheme.target()[0] / (a + omega * omega);
    if (stage > 0) largest = std::max(largest, std::abs(scheme.guess(state, h)[0] - solution));
    scheme.finish_stage({solution}, {}, h);
  }
  return largest;
}

TEST(SdirkStart, LaterStagesStartThirdOrderCloseToTheirSolution) {
  using S = PetscNewtonSettings::Scheme;
  for (S which : {S::sdirk3, S::sdirk4, S::esdirk4}) {
    const double coarse = largest_start_distance(which, 0.02);
    const double fine = largest_start_distance(which, 0.01);
    std::printf("%s: start distance %.3e at h = 0.02, %.3e at h = 0.01 (ratio %.2f)\n",
                scheme_name(which).c_str(), coarse, fine, coarse / fine);
    EXPECT_GT(coarse, 0) << scheme_name(which);
    EXPECT_GT(coarse / fine, 6.5) << scheme_name(which);
  }
}

}  // namespace
}  // namespace fissure
