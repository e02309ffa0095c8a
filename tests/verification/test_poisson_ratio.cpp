// Lateral contraction under uniaxial stretch: −ε_lateral / ε_axial = ν = (3κ − 2μ) / (2(3κ + μ))
// for the three materials of the paper's Figure 9 (configs/beam_stretch.yaml).
#include <gtest/gtest.h>

#include <cmath>
#include <ostream>

#include "integrators/integrator.hpp"
#include "model/model.hpp"
#include "support/beam.hpp"
#include "support/static_equilibrium.hpp"

namespace fissure {
namespace {

struct Material {
  double bulk, shear;
  const char* name;  // the test's name suffix
};
void PrintTo(const Material& m, std::ostream* os) { *os << m.name; }

// Least-squares slope of displacement component `d` against reference coordinate `c` over
// `members`: the strain ∂u_d/∂x_c of a homogeneous field, any rigid offset removed.
double strain(const Particles& p, const std::vector<double>& y, const std::vector<int>& members,
              int d, int c) {
  double sx = 0, su = 0, sxx = 0, sxu = 0;
  for (int i : members) {
    const double x = p.reference[3 * i + c], u = y[3 * i + d] - p.reference[3 * i + d];
    sx += x, su += u, sxx += x * x, sxu += x * u;
  }
  const double n = members.size();
  return (n * sxu - sx * su) / (n * sxx - sx * sx);
}

// The Poisson ratio of the discrete bar itself under homogeneous deformation: with
// Π(a, b) the elastic energy of y = diag(1 + a, 1 + b, 1 + b) x, a quadratic form
// ½(A a² + 2B ab + D b²), the lateral strain that minimises it is b = −(B/D) a, so ν_h = B/D.
// No solver is involved; ν_h carries the discretisation's surface effect.
double homogeneous_poisson_ratio(Model& model, const Particles& p) {
  auto energy = [&](double a, double b) {
    const double F[9] = {1 + a, 0, 0, 0, 1 + b, 0, 0, 0, 1 + b};
    const auto y = test::deform(p, F);
    return model.elastic_energy(y.data());
  };
  const double e = 1e-5, a_only = energy(e, 0), b_only = energy(0, e);
  return 0.5 * (energy(e, e) - a_only - b_only) / b_only;
}

// ν after the surface effect docs/model.md measures for a bar 2.8 horizons wide (test
// SurfaceEffect): E_eff = 1.096 E in uniaxial stress. κ is exact (calibrated dilatation), so the
// excess is deviatoric: solve E_eff = 9κμ'/(3κ + μ') for μ' and return ν(κ, μ').
double surface_stiffened_poisson_ratio(double bulk, double shear) {
  const double e = 1.096 * test::youngs_modulus(bulk, shear);
  return test::poisson_ratio(bulk, 3 * bulk * e / (9 * bulk - e));
}

class PoissonRatio : public ::testing::TestWithParam<Material> {};

// The 1.0 × 0.2 × 0.2 m beam of configs/beam_stretch.yaml at its resolution λ = 0.05 m
// (2.8 horizons across), ends x < 0.05 and x > 0.95 held and pulled apart by 0.5 mm each
// (axial strain 1.1e-3, linear), solved for static equilibrium (petsc_newton, scheme static).
// The strains are fitted over the gauge |x − 0.5| ≤ 0.15 m, 1.5 widths from the grips, where
// their restraint of the contraction has died out (Saint-Venant).
TEST_P(PoissonRatio, LateralContractionMatchesNu) {
  const Material m = GetParam();
  const double pull = 5e-4;
  const std::string yaml = fmt::format(
      "time: {{end: 1.0}}\nbodies:\n  - geometry: {{box: {{min: [0, 0, 0], max: [1, 0.2, 0.2]}}}}\n"
      "    resolution: 0.05\n"
      "    material: {{density: 1000, bulk_modulus: {}, shear_modulus: {}}}\n"
      "constraints:\n"
      "  - {{region: {{box: {{min: [-1, -1, -1], max: [0.05, 1, 1]}}}}, velocity: [{}, 0, 0]}}\n"
      "  - {{region: {{box: {{min: [0.95, -1, -1], max: [2, 1, 1]}}}}, velocity: [{}, 0, 0]}}\n",
      m.bulk, m.shear, -pull, pull);
  const Scene scene = build_scene(parse_config(yaml, "stretch.yaml"));
  auto model = make_model(scene);
  Dynamics dynamics(scene, *model);
  const Particles& p = scene.particles;
  // held ends move by velocity × 1 s
  const State s = test::static_equilibrium(dynamics, test::at_rest(p));

  const double nu_h = homogeneous_poisson_ratio(*model, p);
  std::vector<int> gauge;
  for (int i = 0; i < p.count(); ++i)
    if (std::abs(p.reference[3 * i] - 0.5) <= 0.15) gauge.push_back(i);
  const double axial = strain(p, s.position, gauge, 0, 0);
  const double lateral =
      0.5 * (strain(p, s.position, gauge, 1, 1) + strain(p, s.position, gauge, 2, 2));
  const double nu = -lateral / axial, expected = test::poisson_ratio(m.bulk, m.shear);
  const double surface = surface_stiffened_poisson_ratio(m.bulk, m.shear);
  std::printf(
      "kappa %.3g Pa, mu %.3g Pa: %d particles (%zu in the gauge), axial strain %.4e, "
      "lateral %.4e\n  nu measured %.4f, theory (3k-2mu)/(2(3k+mu)) %.4f (difference "
      "%+.4f), homogeneous %.4f, surface-stiffened %.4f\n",
      m.bulk, m.shear, p.count(), gauge.size(), axial, lateral, nu, expected, nu - expected, nu_h,
      surface);
  // At 2.8 horizons across, ν is low by the documented surface effect: a 9.6% stiffer
  // deviatoric response lowers ν by 0.039, 0.019 and 0.004 for the three materials
  // (`surface`), and the homogeneous ν_h of the same particles agrees with that. The stretch
  // must reproduce ν_h up to the non-homogeneous relaxation near the free surfaces and grips
  // that a homogeneous field lacks (measured 0.008 to 0.010; bound 0.015), and so deviate
  // from theory by no more than the surface effect plus that bound. A wrong κ or μ, sign or
  // strain measure moves ν by far more at ν = 0.10 and 0.30.
  EXPECT_NEAR(nu, nu_h, 0.015);
  EXPECT_LE(std::abs(nu - expected), std::abs(surface - expected) + 0.015);
}

// κ = 2.0 MPa; μ = 2.2, 0.92, 0.15 MPa: ν = 0.10, 0.30, 0.46 (configs/beam_stretch.yaml).
INSTANTIATE_TEST_SUITE_P(Figure9, PoissonRatio,
                         ::testing::Values(Material{2.0e6, 2.2e6, "nu_0_10"},
                                           Material{2.0e6, 9.2e5, "nu_0_30"},
                                           Material{2.0e6, 1.5e5, "nu_0_46"}),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace fissure
