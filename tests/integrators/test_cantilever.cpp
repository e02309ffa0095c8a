// Quasi-static cantilever under its own weight (petsc_newton, scheme static) against
// Euler–Bernoulli beam theory: w(x) = q x²(6L² − 4Lx + x²) / (24 E I), tip w(L) = qL⁴/(8EI).
#include <gtest/gtest.h>

#include <cmath>

#include "model/model.hpp"
#include "support/beam.hpp"
#include "support/static_equilibrium.hpp"

namespace fissure {
namespace {

// The cantilever of support/beam.hpp (1.0 × 0.1 × 0.1 m, κ = 500 MPa, μ = 300 MPa, so
// E = 750 MPa) at resolution 0.025 (four tets through the thickness). Under its own weight its
// tip deflects 1.9e-3 m, 0.2% of the length: linear bending, where Euler–Bernoulli holds.
constexpr double kResolution = 0.025, kGravity = 9.81;

// Tip deflection (the mean vertical displacement of the particles within one resolution of the
// free end) within 5% of Euler–Bernoulli at their mean x. Shear deformation (Timoshenko) adds
// about (E/G)(b/L)²/(3 κ_s) ≈ 1% at L/b = 10, inside the bound. Measured: 7,784 particles,
// ratio 0.973.
TEST(Cantilever, StaticDeflectionMatchesEulerBernoulli) {
  using C = test::Cantilever;
  const Scene scene = test::cantilever_scene(kResolution, kGravity);
  auto model = make_model(scene);
  Dynamics dynamics(scene, *model);
  const Particles& p = scene.particles;
  const State s = test::static_equilibrium(dynamics, test::at_rest(p));

  ASSERT_FALSE(test::tip_particles(p, kResolution).empty());
  const auto [x, w] = test::tip_deflection(p, s.position, kResolution);
  const double q = C::density * kGravity * C::side * C::side;
  const double theory =
      test::euler_bernoulli_deflection(q, test::youngs_modulus(C::bulk, C::shear), x);
  std::printf(
      "%d particles; tip (x = %.4f m) deflection %.4e m, Euler-Bernoulli %.4e m, ratio %.4f\n",
      p.count(), x, w, theory, w / theory);
  EXPECT_NEAR(w / theory, 1.0, 0.05);
}

}  // namespace
}  // namespace fissure
