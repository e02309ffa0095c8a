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
// ν is within the required 0.02 of theory (measured −0.008, −0.010, −0.005: what is left is the
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
// deviation 8), whose every row is exact for every homogeneous strain, edges and corners
// included: the energy of the bar in ε = e diag(1, −s, −s) is then Π(s) = V W(s), W = ½λ(tr ε)²
// + μ ε:ε = ½λe²(1 − 2s)² + μe²(1 + 2s²), a parabola in s whose minimum lies at s = ν (dW/ds =
// 0 ⇔ s = λ/(2(λ + μ)) = (3κ − 2μ)/(2(3κ + μ))). So ν is measured by the bar's energy at three
// contractions, s = 0, ½, 1, through the model's whole energy (images, both calibrations, the
// cell term and the stabilisation, which vanishes on these fields), without a solve and at any
// resolution: λ = 0.1 m, 2 tets across the 0.2 m bar, every particle within a horizon of a
// face. Bound: each measured Π(s) = V W(s) (1 + r), |r| ≤ r_max = 1e-5 (asserted; the
// calibration's residual, 4.8e-7 per particle on a block in test SecondOrderModel, plus the
// bonds' nonlinearity at e = 1e-6), so the fitted curvature c and slope b of Π carry at most
// |δc| ≤ 2 r_max (Π0 + 2Π½ + Π1) and |δb| ≤ r_max (Π0 + Π1) + |δc|, and the minimum
// s* = −b/(2c) at most (|δb| + 2s*|δc|)/(2c): about 1e-5 here. A shear or bulk modulus 5% off
// moves ν by 0.0147, 0.0086, 0.0018 for the three materials and fails (and fails the energy's
// r_max by far). The gripped bar's equilibrium, which the particles relax away from the
// homogeneous field (docs/verification.md f: +0.016, +0.012, +0.004 at λ = 0.05), is not
// what this measures.
class PoissonRatioFictitious : public ::testing::TestWithParam<Material> {};

TEST_P(PoissonRatioFictitious, LateralContractionMatchesNu) {
  const Material m = GetParam();
  const double width = 0.2, e = 1e-6, r_max = 1e-5;
  const Scene scene = test::block_scene({.size = {1, width, width},
                                         .resolution = 0.1,
                                         .bulk = m.bulk,
                                         .shear = m.shear,
                                         .material = ", surface_correction: fictitious"});
  auto model = make_model(scene);
  const Particles& p = scene.particles;
  double volume = 0;
  for (double v : p.volume) volume += v;
  const double lame = m.bulk - 2.0 / 3 * m.shear;
  double energy[3];
  for (int k = 0; k < 3; ++k) {
    const double s = 0.5 * k;
    std::vector<double> y = p.reference;
    for (int i = 0; i < p.count(); ++i) {
      y[3 * i] += e * (p.reference[3 * i] - 0.5);
      for (int d = 1; d < 3; ++d) y[3 * i + d] -= s * e * (p.reference[3 * i + d] - 0.5 * width);
    }
    energy[k] = model->elastic_energy(y.data());
    const double continuum =
        volume * (0.5 * lame * std::pow(e * (1 - 2 * s), 2) + m.shear * e * e * (1 + 2 * s * s));
    EXPECT_NEAR(energy[k] / continuum, 1.0, r_max) << "s = " << s;
  }
  const double c = 2 * (energy[2] - 2 * energy[1] + energy[0]), b = energy[2] - energy[0] - c;
  const double nu = -b / (2 * c), expected = test::poisson_ratio(m.bulk, m.shear);
  const double dc = 2 * r_max * (energy[0] + 2 * energy[1] + energy[2]);
  const double db = r_max * (energy[0] + energy[2]) + dc;
  const double bound = (db + 2 * std::abs(nu) * dc) / (2 * c);
  std::printf(
      "fictitious: %d particles, energy at s = 0, 1/2, 1: %.6e %.6e %.6e J\n"
      "  nu measured %.6f, theory %.6f (difference %+.2e, bound %.2e)\n",
      p.count(), energy[0], energy[1], energy[2], nu, expected, nu - expected, bound);
  ASSERT_LT(bound, 1e-3);  // sharp enough for a modulus 5% off at every material
  EXPECT_NEAR(nu, expected, bound);
}

INSTANTIATE_TEST_SUITE_P(Figure9, PoissonRatioFictitious, kFigure9, material_name);

}  // namespace
}  // namespace fissure
