// The model's evaluations are pure: what one returns does not depend on
// which evaluation ran before it, so a line search's trial points or the ledger's energy samples
// cannot change what a frame writes. And its optional capabilities are there exactly when the
// model and the scene have them.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "model/model.hpp"
#include "support/dilatation.hpp"
#include "support/scenes.hpp"

namespace fissure {
namespace {

struct Evaluations {
  std::vector<double> theta, force, energy_density;
  double energy;
};

Evaluations evaluate(Model& model, const std::vector<double>& y) {
  Evaluations e{test::dilatation(model, y), std::vector<double>(y.size()),
                std::vector<double>(y.size() / 3), 0};
  model.forces(y.data(), e.force.data());
  model.energy_density(y.data(), e.energy_density.data());
  std::vector<double> f(y.size());
  e.energy = model.forces_and_energy(y.data(), f.data());
  return e;
}

Scene block(const std::string& model, const std::string& material) {
  return test::block_scene({.size = {0.1, 0.1, 0.1},
                            .resolution = 0.025,
                            .bulk = 1.0e6,
                            .shear = 1.0e6,
                            .model = model,
                            .material = material});
}

// Every evaluation at y gives bitwise what it gave before evaluations at other points ran in
// between, in any order; a model whose dilatation() returned the last evaluation's θ (the
// interface before this test) gives θ(y2) here and fails.
TEST(PureEvaluation, NoEvaluationChangesWhatAnotherReturns) {
  for (const auto& [model_name, material] : std::vector<std::pair<std::string, std::string>>{
           {"lps", ""}, {"lps", ", plasticity: {yield_stress: 1.0e4}"}, {"paper", ""}}) {
    SCOPED_TRACE(model_name + material);
    const Scene scene = block(model_name, material);
    auto model = make_model(scene);
    const double F1[9] = {1.01, 0.02, 0, 0, 0.99, 0.01, 0, 0, 1.005};
    const double F2[9] = {0.97, 0, 0.03, 0.01, 1.02, 0, 0, 0.02, 1.0};
    const auto y1 = test::deform(scene.particles, F1);
    const auto y2 = test::deform(scene.particles, F2);
    const Evaluations first = evaluate(*model, y1);
    const Evaluations other = evaluate(*model, y2);
    std::vector<double> f(y1.size()), w(y1.size() / 3);
    model->energy_density(y2.data(), w.data());
    EXPECT_NE(other.theta, first.theta);  // the two points differ, so the check can fail
    const std::vector<double> theta_after = test::dilatation(*model, y1);
    model->forces(y2.data(), f.data());
    const Evaluations again = evaluate(*model, y1);
    EXPECT_EQ(theta_after, first.theta);
    EXPECT_EQ(again.theta, first.theta);
    EXPECT_EQ(again.force, first.force);
    EXPECT_EQ(again.energy_density, first.energy_density);
    EXPECT_EQ(again.energy, first.energy);
  }
}

// The dilatation the forces use: for a pure dilatation y = (1 + ε)x every bond stretches by ε,
// so θ = Σ c_ij ε|ξ| V_j, which the calibration makes 3ε on every particle (docs/model.md).
TEST(PureEvaluation, DilatationIsTheCalibratedOneAtTheGivenPositions) {
  const Scene scene = block("lps", "");
  auto model = make_model(scene);
  const double eps = 1e-4;
  const double F[9] = {1 + eps, 0, 0, 0, 1 + eps, 0, 0, 0, 1 + eps};
  const std::vector<double> theta = test::dilatation(*model, test::deform(scene.particles, F));
  for (double t : theta) EXPECT_NEAR(t / (3 * eps), 1.0, 1.2e-7);
}

// A model refers to its scene's particles and families, so each scene outlives its model.
TEST(PureEvaluation, CapabilitiesArePresentExactlyWhereTheModelHasThem) {
  const Scene elastic_scene = block("lps", "");
  auto elastic = make_model(elastic_scene);
  EXPECT_NE(elastic->stiffness(), nullptr);
  EXPECT_EQ(elastic->plastic_flow(), nullptr);
  const Scene plastic_scene = block("lps", ", plasticity: {yield_stress: 1.0e4}");
  auto plastic = make_model(plastic_scene);
  EXPECT_NE(plastic->stiffness(), nullptr);
  ASSERT_NE(plastic->plastic_flow(), nullptr);
  EXPECT_EQ(plastic->plastic_flow()->plastic_extension().size(),
            plastic->families().directed_bonds());
  const Scene paper_scene = block("paper", "");
  auto paper = make_model(paper_scene);
  EXPECT_EQ(paper->stiffness(), nullptr);
  EXPECT_EQ(paper->plastic_flow(), nullptr);
}

}  // namespace
}  // namespace fissure
