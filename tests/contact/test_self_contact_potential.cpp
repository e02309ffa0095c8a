// Self-contact as a potential of the positions (SelfContact::potential, docs/integrators.md,
// "Contact"): B = Σ over unbonded pairs ½ k p², its gradient, and its Hessian's projection, as
// diagonal blocks (the factor's) and pair blocks (add_coupling, the Newton matrix's), checked on
// two blocks of separate bodies that start overlapping by 4 mm (at rest: the start-at-rest rule
// caps their radii), pressed 2 mm further and moved randomly. Central
// differences of a C² function err by O(ε²): at ε = 1e-8 m on overlaps of 1e-3 m and more, far
// below the 1e-6 asked. The projection leaves out each pair's term −k (p/d)(I − n nᵀ) on purpose;
// the test adds it back, pair by pair over every pair, and then the product must be the
// differences' own. A gradient off by a constant, a missing half of the pairs, a coupling block
// of the wrong sign or left out, or a diagonal block that double counts fails. The update bound
// keeps each particle within skin/2 of a common motion and lets a rigid translation through.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "contact/self_contact.hpp"
#include "model/model.hpp"
#include "scene/config.hpp"
#include "support/contact_sizes.hpp"
#include "support/potential_evaluation.hpp"

namespace fissure {
namespace {

// Two blocks of separate bodies overlapping by 4 mm in x (no bonds between them), 2 cm apart.
const char* kTwoBlocks =
    "time: {end: 1.0}\ncontact: {self: true}\nbodies:\n"
    "  - geometry: {box: {min: [0, 0, 0], max: [0.1, 0.1, 0.1]}}\n    resolution: 0.02\n"
    "    material: {density: 1000, bulk_modulus: 1.0e6, shear_modulus: 1.0e6}\n"
    "  - geometry: {box: {min: [0.096, 0, 0], max: [0.196, 0.1, 0.1]}}\n    resolution: 0.02\n"
    "    material: {density: 1000, bulk_modulus: 2.0e6, shear_modulus: 1.0e6}\n";

using test::evaluate;
using test::Evaluation;

// The state: the second block pushed 2 mm further into the first, and every particle moved by up
// to 1 mm in a random direction.
std::vector<double> pressed(const Scene& scene) {
  std::vector<double> y = scene.particles.reference;
  std::mt19937 random(3);
  std::uniform_real_distribution<double> uniform(-5.8e-4, 5.8e-4);
  for (double& v : y) v += uniform(random);
  for (int i = 0; i < scene.particles.count(); ++i)
    if (scene.particles.body[i] == 1) y[3 * i] -= 2e-3;
  return y;
}

class SelfContactPotential : public ::testing::Test {
 protected:
  Scene scene = build_scene(parse_config(kTwoBlocks, "two_blocks.yaml"));
  std::unique_ptr<Model> model = make_model(scene);
  SelfContact contact{scene, *model};
  std::vector<double> z = pressed(scene);
};

TEST_F(SelfContactPotential, ForceIsTheNegativeGradientOfTheEnergy) {
  const Evaluation at = evaluate(contact, z);
  std::vector<double> force(z.size(), 0.0);
  contact.add_forces(z.data(), force.data());
  double scale = 0;
  for (double f : force) scale = std::max(scale, std::abs(f));
  ASSERT_GT(scale, 0) << "no pair in contact";
  ASSERT_GT(at.energy, 0);
  int checked = 0;
  const double eps = 1e-8;
  for (std::size_t k = 0; k < z.size(); ++k) {
    EXPECT_NEAR(at.gradient[k], -force[k], 1e-12 * scale) << "component " << k;
    if (force[k] == 0) continue;
    ++checked;
    std::vector<double> plus = z, minus = z;
    plus[k] += eps;
    minus[k] -= eps;
    const double slope = (contact.potential(plus.data(), nullptr, nullptr) -
                          contact.potential(minus.data(), nullptr, nullptr)) /
                         (2 * eps);
    EXPECT_NEAR(at.gradient[k], slope, 1e-6 * scale) << "component " << k;
  }
  EXPECT_GT(checked, 30);
}

TEST_F(SelfContactPotential, ProjectedHessianPlusItsLeftOutTermIsTheDifferencesOwn) {
  const Evaluation at = evaluate(contact, z);
  const std::size_t n = z.size() / 3;
  std::mt19937 random(11);
  std::normal_distribution<double> normal;
  std::vector<double> v(z.size());
  for (double& x : v) x = normal(random);
  // The projection's product: the diagonal blocks and the coupling.
  std::vector<double> product(z.size(), 0.0);
  for (std::size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) product[3 * i + a] += at.blocks[9 * i + 3 * a + b] * v[3 * i + b];
  contact.add_coupling(z.data(), v.data(), product.data());
  // The left-out term, −k (p/d)(I − n nᵀ)(v_i − v_j) on row i, over every pair of the two bodies
  // (all the unbonded ones) within reach, with the documented radii and stiffness.
  const test::ContactSizes c = test::documented_sizes(scene, {1.0e6, 2.0e6});
  std::vector<double> left_out(z.size(), 0.0);
  int pairs = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      if (scene.particles.body[i] == scene.particles.body[j]) continue;
      double d[3], dv[3];
      for (int a = 0; a < 3; ++a) {
        d[a] = z[3 * i + a] - z[3 * j + a];
        dv[a] = v[3 * i + a] - v[3 * j + a];
      }
      const double distance = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      const double overlap = c.radius[i] + c.radius[j] - distance;
      if (overlap <= 0) continue;
      ++pairs;
      const double k = 0.5 * (c.stiffness[i] + c.stiffness[j]);
      const double along = (d[0] * dv[0] + d[1] * dv[1] + d[2] * dv[2]) / distance;
      for (int a = 0; a < 3; ++a)
        left_out[3 * i + a] -= k * overlap / distance * (dv[a] - along * d[a] / distance);
    }
  ASSERT_GT(pairs, 20);
  // Central differences of the gradient along v.
  const double eps = 1e-8;
  std::vector<double> plus = z, minus = z;
  for (std::size_t k = 0; k < z.size(); ++k) {
    plus[k] += eps * v[k];
    minus[k] -= eps * v[k];
  }
  const Evaluation up = evaluate(contact, plus), down = evaluate(contact, minus);
  double scale = 0;
  for (double p : product) scale = std::max(scale, std::abs(p));
  ASSERT_GT(scale, 0);
  for (std::size_t k = 0; k < z.size(); ++k) {
    const double difference = (up.gradient[k] - down.gradient[k]) / (2 * eps);
    EXPECT_NEAR(product[k] + left_out[k], difference, 1e-6 * scale) << "component " << k;
  }
  // and the projection is positive semidefinite: vᵀ H⁺ v = Σ k (n·(v_i − v_j))² ≥ 0
  double quadratic = 0;
  for (std::size_t k = 0; k < z.size(); ++k) quadratic += v[k] * product[k];
  EXPECT_GT(quadratic, 0);
}

TEST_F(SelfContactPotential, UpdateBoundKeepsRelativeMotionWithinHalfTheSkin) {
  evaluate(contact, z);
  const double skin = contact.skin();
  const std::size_t n = z.size() / 3;
  // every particle carried 10 skins along x: a rigid translation, admitted whole
  std::vector<double> dz(z.size(), 0.0);
  for (std::size_t i = 0; i < n; ++i) dz[3 * i] = 10 * skin;
  EXPECT_EQ(contact.max_step(dz.data()), 1.0);
  // one particle moved 10.2 skins against the others: cut to where the box around the
  // displacements has half-diagonal skin/2, that particle's motion then skin
  dz[0] = -10 * skin;
  dz[1] = 2 * skin;
  dz[2] = 0;
  for (std::size_t i = 1; i < n; ++i) dz[3 * i] = 0;
  const double alpha = contact.max_step(dz.data());
  EXPECT_NEAR(alpha * std::sqrt(dz[0] * dz[0] + dz[1] * dz[1]), skin, 1e-12 * skin);
  // a small relative motion is admitted whole
  for (double& d : dz) d *= 1e-3;
  EXPECT_EQ(contact.max_step(dz.data()), 1.0);
}

}  // namespace
}  // namespace fissure
