// Lateral contraction under uniaxial stretch: −ε_lateral / ε_axial = ν = (3κ − 2μ) / (2(3κ + μ))
// for the three materials of the paper's Figure 9 (configs/beam_stretch.yaml).
#include <gtest/gtest.h>

#include <cmath>
#include <ostream>

#include "integrators/integrator.hpp"
#include "model/model.hpp"
#include "support/beam.hpp"
#include "support/scenes.hpp"
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

// ν after the documented surface effect of a bar 2.8 horizons wide (docs/model.md, "Remaining
// surface effect": E_eff = 1.096 E in homogeneous uniaxial stress at w/δ = 2.76 with κ = μ,
// calibrated weights; test SurfaceEffect bounds it below 1.10). κ is exact on every particle
// (test EffectiveModuli) and the excess comes from the per-mode deviatoric energy of cut families,
// a property of the bond geometry, so it scales μ by a factor that does not depend on κ/μ:
// 1.096 E(κ, κ) = E(κ, μ'κ) gives μ' = 1.132, and ν' = ν(κ, μ' μ) (Eq: E = 9κμ/(3κ + μ)).
double surface_stiffened_poisson_ratio(double bulk, double shear) {
  const double excess = 1.096 * test::youngs_modulus(1, 1);  // E_eff / κ at κ = μ = 1
  const double factor = 3 * excess / (9 - excess);           // μ'/μ from 9μ'/(3 + μ') = excess
  return test::poisson_ratio(bulk, factor * shear);
}

// The 1.0 × 0.2 × 0.2 m beam of configs/beam_stretch.yaml at its resolution λ = 0.05 m
// (2.8 horizons across), ends x < 0.05 and x > 0.95 held and pulled apart by 0.5 mm each
// (axial strain 1.1e-3, linear), solved for static equilibrium (petsc_newton, scheme static).
// The strains are fitted over the gauge |x − 0.5| ≤ 0.15 m, 1.5 widths from the grips, where
// their restraint of the contraction has died out (Saint-Venant).
// `extra` is appended to the material map. Returns the measured ν.
double measured_poisson_ratio(const Material& m, const std::string& extra) {
  const double pull = 5e-4;
  const Scene scene =
      test::block_scene({.size = {1, 0.2, 0.2},
                         .resolution = 0.05,
                         .bulk = m.bulk,
                         .shear = m.shear,
                         .material = extra,
                         .scene = fmt::format("constraints:\n"
                                              "  - {{region: {{box: {{min: [-1, -1, -1], max: "
                                              "[0.05, 1, 1]}}}}, velocity: [{}, 0, 0]}}\n"
                                              "  - {{region: {{box: {{min: [0.95, -1, -1], max: "
                                              "[2, 1, 1]}}}}, velocity: [{}, 0, 0]}}\n",
                                              -pull, pull)});
  auto model = make_model(scene);
  Dynamics dynamics(scene, *model);
  const Particles& p = scene.particles;
  // held ends move by velocity × 1 s
  const State s = test::static_equilibrium(dynamics, test::at_rest(p));

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
      "lateral %.4e\n  nu measured %.4f, theory (3k-2mu)/(2(3k+mu)) %.4f (difference %+.4f), "
      "after the documented surface effect %.4f (difference %+.4f)\n",
      m.bulk, m.shear, p.count(), gauge.size(), axial, lateral, nu, expected, nu - expected,
      surface, surface - expected);
  return nu;
}

// κ = 2.0 MPa; μ = 2.2, 0.92, 0.15 MPa: ν = 0.10, 0.30, 0.46 (configs/beam_stretch.yaml).
const auto kFigure9 =
    ::testing::Values(Material{2.0e6, 2.2e6, "nu_0_10"}, Material{2.0e6, 9.2e5, "nu_0_30"},
                      Material{2.0e6, 1.5e5, "nu_0_46"});
std::string material_name(const ::testing::TestParamInfo<Material>& info) {
  return info.param.name;
}

class PoissonRatio : public ::testing::TestWithParam<Material> {};

TEST_P(PoissonRatio, LateralContractionMatchesNu) {
  const Material m = GetParam();
  const double nu = measured_poisson_ratio(m, "");
  const double expected = test::poisson_ratio(m.bulk, m.shear);
  const double surface = surface_stiffened_poisson_ratio(m.bulk, m.shear);
  // Sign: a family cut by a free surface stiffens the deviatoric response and leaves κ exact,
  // so μ_eff > μ and ν = (3κ − 2μ)/(2(3κ + μ)) falls (dν/dμ < 0): ν may only lie below theory.
  EXPECT_LT(nu, expected);
  // Size: the documented deviatoric excess lowers ν to `surface` (by 0.038, 0.022, 0.005 for the
  // three materials). A homogeneous field is not the bar's equilibrium: the grips hold the
  // ends' contraction and the stiff surface layer relaxes the core, which lowers ν a further
  // 0.006 to 0.009 at this resolution (docs/verification.md b); 0.012 bounds that part. Without
  // the dilatation calibration (plain weights) θ picks up shear near the surfaces and ν comes
  // out above theory (0.321 and 0.518 for the last two materials): it fails the sign.
  EXPECT_GT(nu, surface - 0.012);
}

INSTANTIATE_TEST_SUITE_P(Figure9, PoissonRatio, kFigure9, material_name);

// With the deviatoric calibration (surface_correction: full, docs/model.md deviation 8) every
// homogeneous strain is exact on the particles that can be, the surface stiffening is gone, and
// ν is within issue 15's 0.02 of theory (measured −0.008, −0.010, −0.005: what is left is the
// grips' restraint and the inexact edge rows). A calibration that did nothing gives the table
// above (0.043 low for the first material) and fails.
class PoissonRatioFull : public ::testing::TestWithParam<Material> {};

TEST_P(PoissonRatioFull, LateralContractionMatchesNu) {
  const Material m = GetParam();
  const double nu = measured_poisson_ratio(m, ", surface_correction: full");
  EXPECT_NEAR(nu, test::poisson_ratio(m.bulk, m.shear), 0.02);
}

INSTANTIATE_TEST_SUITE_P(Figure9, PoissonRatioFull, kFigure9, material_name);

// The same with the second-order model (surface_correction: fictitious, docs/model.md
// deviation 8): every homogeneous strain exact on every particle, edges included, and ν within
// issue 15's 0.02 (measured +0.016, +0.012, +0.004: above theory, where the grips' restraint
// alone would lower it; the cause is not known, docs/verification.md f). The `dilatation`
// model's 0.043 low for the first material fails.
class PoissonRatioFictitious : public ::testing::TestWithParam<Material> {};

TEST_P(PoissonRatioFictitious, LateralContractionMatchesNu) {
  const Material m = GetParam();
  const double nu = measured_poisson_ratio(m, ", surface_correction: fictitious");
  EXPECT_NEAR(nu, test::poisson_ratio(m.bulk, m.shear), 0.02);
}

INSTANTIATE_TEST_SUITE_P(Figure9, PoissonRatioFictitious, kFigure9, material_name);

}  // namespace
}  // namespace fissure
