// Torsion of a circular bar: the torque per unit twist rate is μJ (Saint-Venant; for a circle
// the cross-sections turn rigidly and do not warp), J = πR⁴/2: a measure of μ independent of
// the homogeneous energies of test EffectiveModuli.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "integrators/integrator.hpp"
#include "model/model.hpp"
#include "support/scenes.hpp"
#include "support/static_equilibrium.hpp"

namespace fissure {
namespace {

TEST(Torsion, TorquePerTwistRateMatchesSaintVenant) {
  const double length = 0.3, radius = 0.05, lambda = 0.02, grip = 0.04, twist = 2e-3;
  const double bulk = 2.0e6, shear = 1.0e6;
  const std::string yaml = fmt::format(
      "time: {{end: 1.0}}\nbodies:\n  - geometry: {{cylinder: {{p0: [0, 0, 0], p1: [{0}, 0, 0], "
      "radius: {1}}}}}\n    resolution: {2}\n"
      "    material: {{density: 1000, bulk_modulus: {3}, shear_modulus: {4}}}\n"
      "constraints:\n"
      "  - {{region: {{box: {{min: [-1, -1, -1], max: [{5}, 1, 1]}}}}, fix: true}}\n"
      "  - {{region: {{box: {{min: [{6}, -1, -1], max: [1, 1, 1]}}}}, angular_velocity: [{7}, 0, "
      "0], center: [0, 0, 0]}}\n",
      length, radius, lambda, bulk, shear, grip, length - grip, twist);
  const Scene scene = build_scene(parse_config(yaml, "torsion.yaml"));
  auto model = make_model(scene);
  Dynamics dynamics(scene, *model);
  const Particles& p = scene.particles;
  // held ends: x < grip fixed, x > L − grip turned by `twist` (angular velocity × 1 s)
  const State s = test::static_equilibrium(dynamics, test::at_rest(p));

  // Twist rate: the angle α_i = (y u_z − z u_y)/r² of each gauge particle (small rotation about
  // x), fitted as α = θ' x + c weighting by r² (the least-squares fit of the rigid rotation of
  // the sections to the displacements), over |x − L/2| ≤ L/4, a radius from the grips.
  double sw = 0, sx = 0, sa = 0, sxx = 0, sxa = 0;
  for (int i = 0; i < p.count(); ++i) {
    const double* x = &p.reference[3 * i];
    if (std::abs(x[0] - length / 2) > length / 4) continue;
    const double r2 = x[1] * x[1] + x[2] * x[2];
    if (r2 == 0) continue;
    const double uy = s.position[3 * i + 1] - x[1], uz = s.position[3 * i + 2] - x[2];
    const double a = (x[1] * uz - x[2] * uy) / r2;
    sw += r2, sx += r2 * x[0], sa += r2 * a, sxx += r2 * x[0] * x[0], sxa += r2 * x[0] * a;
  }
  const double rate = (sw * sxa - sx * sa) / (sw * sxx - sx * sx);
  // Torque: the moment about x of the internal forces on the turned grip (equal and opposite to
  // what the constraint applies).
  std::vector<double> f(s.position.size());
  model->forces(s.position.data(), f.data());
  double torque = 0, volume = 0;
  for (int i = 0; i < p.count(); ++i) {
    volume += p.volume[i];
    if (p.reference[3 * i] < length - grip) continue;
    const double* y = &s.position[3 * i];
    torque -= y[1] * f[3 * i + 2] - y[2] * f[3 * i + 1];
  }
  // J of the meshed section: its area A = volume / L (TetGen's facets cut the circle), J = A²/2π.
  const double area = volume / length, J = area * area / (2 * std::numbers::pi);
  const double nominal = std::numbers::pi * std::pow(radius, 4) / 2;
  const double mu_eff = torque / (J * rate);
  std::printf(
      "%d particles, twist rate %.4e rad/m (ends: %.4e), torque %.4e N m, J %.4e m^4 "
      "(circle %.4e): mu_eff/mu %.4f\n",
      p.count(), rate, twist / (length - 2 * grip), torque, J, nominal, mu_eff / shear);
  // The section is 2R/δ = 3.45 horizons across. Families cut by the surface stiffen the deviatoric
  // response and never soften it, and κ is exact, so μ_eff ≥ μ (the meshed J = A²/2π is if
  // anything low: a polygon's polar moment exceeds that of the circle of its area, by 1.3e-4
  // for the 16-gon whose area, 0.974 of the circle's, TetGen meshes). The excess is at most that
  // documented for a thinner bar, 2.76 horizons across (docs/model.md: E_eff = 1.096 E at κ = μ,
  // i.e. μ' = 1.132 μ; 1.06 μ at 5.5 horizons).
  EXPECT_GT(mu_eff / shear, 1.0);
  EXPECT_LT(mu_eff / shear, 1.132);
}

}  // namespace
}  // namespace fissure
