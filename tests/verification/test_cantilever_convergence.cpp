// Static deflection of the cantilever of support/beam.hpp under its own weight (petsc_newton,
// scheme static) as the resolution is refined, against beam theory with the shear correction:
//   w(x) = q x²(6L² − 4Lx + x²) / (24 EI)  +  q (Lx − x²/2) / (k_s μ A),   q = ρ g A,
// Euler–Bernoulli bending plus Timoshenko's shear deflection (k_s Cowper's coefficient;
// at the tip the shear term is (E / (3 k_s μ)) (b/L)² = 1.0% of the bending term).
#include <gtest/gtest.h>

#include <cmath>

#include "integrators/integrator.hpp"
#include "model/model.hpp"
#include "support/beam.hpp"
#include "support/static_equilibrium.hpp"

namespace fissure {
namespace {

using test::Cantilever;

struct Deflection {
  int particles;
  double x, measured, theory;
};

// The mean vertical displacement of the particles within one resolution of the free end, and
// the theory at their mean x.
Deflection static_tip_deflection(const Scene& scene, double resolution, double gravity) {
  auto model = make_model(scene);
  Dynamics dynamics(scene, *model);
  const Particles& p = scene.particles;
  const State s = test::static_equilibrium(dynamics, test::at_rest(p));

  const auto [x, w] = test::tip_deflection(p, s.position, resolution);
  return {p.count(), x, w, test::timoshenko_deflection(gravity, x)};
}

Deflection static_tip_deflection(double resolution, const std::string& material = "") {
  const double gravity = 9.81;
  return static_tip_deflection(test::cantilever_scene(resolution, gravity, material), resolution,
                               gravity);
}

// The order p of a sequence r(λ) = r* + C λ^p from three resolutions λ = b/2, b/3, b/4:
// (r2 − r3)/(r3 − r4) = (2^−p − 3^−p)/(3^−p − 4^−p), solved by bisection on p ∈ [0.1, 10]
// (the right side grows with p).
double observed_order(double d23, double d34) {
  const double target = d23 / d34;
  auto ratio = [](double p) {
    return (std::pow(2, -p) - std::pow(3, -p)) / (std::pow(3, -p) - std::pow(4, -p));
  };
  double lo = 0.1, hi = 10;
  for (int k = 0; k < 60; ++k) (ratio(0.5 * (lo + hi)) < target ? lo : hi) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

// λ = 0.1/2, 0.1/3, 0.1/4 m: 2, 3 and 4 tets through the 0.1 m thickness (1.4 to 2.8
// horizons), so λ halves over two refinements. A third halving, 0.0125 m, is out of the time
// budget (about 60k particles, minutes per Newton solve).
//
// The error against theory does not fall monotonically (docs/verification.md): the ratio
// r = w/theory falls through 1 as λ shrinks (likely a soft clamp at the coarsest λ against the
// stiffening surface effect); further runs at λ = 0.028 and 0.020 m gave 0.960 and 0.953, a
// plateau, not a return to 1. 3D elasticity gives r = 0.994 for this clamp
// (bench_fem_cantilever, quadratic tets). Asserted instead: the discrete solution converges, i.e.
// the change of r shrinks at each refinement (its observed order is printed, not asserted), and the
// finest is within 5% of theory, the bound of test_cantilever.cpp (surface effect at 2.8 horizons
// across: up to 9.6% stiffer in uniaxial stress, docs/model.md).
TEST(CantileverConvergence, StaticDeflectionConvergesWithResolution) {
  const double thickness = Cantilever::side;
  double ratio[3];
  for (int k = 0; k < 3; ++k) {
    const double resolution = thickness / (k + 2);
    const Deflection d = static_tip_deflection(resolution);
    ratio[k] = d.measured / d.theory;
    std::printf(
        "lambda %.4f m: %5d particles, tip x %.4f m, w %.4e m, theory %.4e m, ratio %.4f, "
        "error %+.4f\n",
        resolution, d.particles, d.x, d.measured, d.theory, ratio[k], ratio[k] - 1);
  }
  const double d23 = std::abs(ratio[0] - ratio[1]), d34 = std::abs(ratio[1] - ratio[2]);
  std::printf("successive changes of the ratio: %.4f, %.4f; observed order %.2f\n", d23, d34,
              observed_order(d23, d34));
  EXPECT_LT(d34, d23);
  EXPECT_NEAR(ratio[2], 1.0, 0.05);
}

// The same with the deviatoric calibration (surface_correction: full, docs/model.md deviation
// 8), which makes every homogeneous strain exact on 87% of the particles of the finest beam:
// the beam is then too soft, and its error falls at each refinement (measured 1.457, 1.221,
// 1.145; observed order 2.2). The surface stiffening that `dilatation` leaves was cancelling
// most of a larger softening from the strain gradient across each family, which no homogeneous
// calibration touches (docs/verification.md). Asserted: softer than theory at every λ, the error
// falling monotonically and its change shrinking; a calibration that did nothing gives the
// ratios of the test above (0.963 at the finest λ) and fails.
TEST(CantileverConvergence, FullSurfaceCorrectionIsSoftAndConverges) {
  const double thickness = Cantilever::side;
  double error[3];
  for (int k = 0; k < 3; ++k) {
    const double resolution = thickness / (k + 2);
    const Deflection d = static_tip_deflection(resolution, ", surface_correction: full");
    error[k] = d.measured / d.theory - 1;
    std::printf("full, lambda %.4f m: %5d particles, ratio %.4f, error %+.4f\n", resolution,
                d.particles, 1 + error[k], error[k]);
  }
  const double d23 = error[0] - error[1], d34 = error[1] - error[2];
  std::printf("full: successive changes %.4f, %.4f; observed order %.2f\n", d23, d34,
              observed_order(d23, d34));
  EXPECT_GT(error[2], 0.0);
  EXPECT_GT(d34, 0.0);
  EXPECT_LT(d34, d23);
}

// The second-order model (surface_correction: fictitious, docs/model.md deviation 8) on the beam
// alone with its face x = 0 clamped: the target, within 1% of Timoshenko at λ = 0.025
// with the error falling at each refinement. Measured in bench_fictitious_particles (the same
// model, linearised): 0.9859, 0.9898, 0.9938. 3D elasticity with the face held gives 0.994 at
// this clamp (bench_fem_cantilever), the limit the ratio should approach: a model that kept the
// `dilatation` correction's surface stiffening (0.963), or lost the stabilisation (1.0079 at
// λ = 0.05, the error not falling), fails.
TEST(CantileverConvergence, FictitiousParticlesConvergeWithin1Percent) {
  const double thickness = Cantilever::side, gravity = 9.81;
  double error[3];
  for (int k = 0; k < 3; ++k) {
    const double resolution = thickness / (k + 2);
    const Deflection d = static_tip_deflection(
        test::clamped_face_cantilever_scene(resolution, gravity), resolution, gravity);
    error[k] = d.measured / d.theory - 1;
    std::printf("fictitious, lambda %.4f m: %5d particles, ratio %.4f, error %+.4f\n", resolution,
                d.particles, 1 + error[k], error[k]);
  }
  EXPECT_LT(std::abs(error[2]), 0.01);
  EXPECT_LT(std::abs(error[1]), std::abs(error[0]));
  EXPECT_LT(std::abs(error[2]), std::abs(error[1]));
}

}  // namespace
}  // namespace fissure
