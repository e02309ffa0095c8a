// The stiffness interfaces of implicit steps beyond the assembled matrices: the matrix-free tangent
// product against the assembled tangent, forces and energy from one pass against forces() and
// elastic_energy(), and the scalar one-hop stiffness against the majoriser.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "linear/sparse_symmetric.hpp"
#include "model/model.hpp"
#include "support/stiffness_block.hpp"

namespace fissure {
namespace {

using test::deformed;
using test::small_block;

double relative_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double error = 0, norm = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    error += (a[k] - b[k]) * (a[k] - b[k]);
    norm += b[k] * b[k];
  }
  return std::sqrt(error / norm);
}

// A direction with every component different (probe picks one of several).
std::vector<double> probe_direction(std::size_t n, int probe) {
  std::vector<double> v(n);
  for (std::size_t k = 0; k < n; ++k) v[k] = std::sin(1.7 * k + 3.1 * probe) + 0.3 * probe;
  return v;
}

// The largest |apply_tangent(v) − K v| / |K v| over 4 directions, K assembled at y with
// clamp_assembled, the product linearized at y with clamp_product.
double product_error(Model& model, const Families& families, const std::vector<double>& y,
                     bool clamp_product, bool clamp_assembled) {
  SparseSymmetric K = two_hop_pattern(families);
  model.stiffness()->assemble_tangent(y.data(), K, clamp_assembled);
  model.stiffness()->linearize(y.data(), clamp_product);
  const std::size_t n = y.size();
  std::vector<double> assembled(n), product(n);
  double worst = 0;
  for (int probe = 0; probe < 4; ++probe) {
    const std::vector<double> v = probe_direction(n, probe);
    K.multiply(v.data(), assembled.data());
    model.stiffness()->apply_tangent(v.data(), product.data());
    worst = std::max(worst, relative_difference(product, assembled));
  }
  return worst;
}

// The product matches the assembled tangent to round-off in tension and in compression (where the
// geometric term has both signs), with and without clamp_compression.
void expect_product_matches_assembly(Model& model, const Scene& scene, const char* label) {
  for (const double strain : {0.02, -0.03}) {
    const auto y = deformed(scene.particles, strain);
    for (const bool clamp : {false, true}) {
      const double error = product_error(model, scene.families, y, clamp, clamp);
      std::printf("%s, strain %+.2f, clamp %d: |K v (matrix-free) - K v| / |K v| = %.2e\n", label,
                  strain, clamp, error);
      EXPECT_LT(error, 1e-12) << label << " strain " << strain << " clamp " << clamp;
    }
  }
}

// Breaks every third bond of every fourth particle, in both rows of the pair; returns the pairs.
std::vector<std::pair<int, int>> break_some_bonds(Model& model, const Families& families) {
  std::vector<std::pair<int, int>> broken;
  const int n = static_cast<int>(families.offsets.size()) - 1;
  for (int i = 0; i < n; i += 4)
    for (int b = families.offsets[i]; b < families.offsets[i + 1]; b += 3) {
      const int j = families.neighbors[b];
      if (j < i || !model.bond_intact(b)) continue;
      model.break_bond(i, b);
      model.break_bond(j, families.reverse[b]);
      broken.emplace_back(i, j);
    }
  return broken;
}

TEST(TangentProduct, MatchesAssembledTangentElastic) {
  const Scene scene = small_block();
  auto model = make_model(scene);
  expect_product_matches_assembly(*model, scene, "elastic");
}

TEST(TangentProduct, MatchesAssembledTangentWithPlasticExtension) {
  const Scene scene = small_block(", plasticity: {yield_stress: 5.0e3}");
  auto model = make_model(scene);
  ASSERT_NE(model->plastic_flow(), nullptr);
  EXPECT_GT(model->plastic_flow()->update_plasticity(deformed(scene.particles, 0.05).data()), 0u);
  double largest = 0;
  for (const double ep : model->plastic_flow()->plastic_extension())
    largest = std::max(largest, std::abs(ep));
  std::printf("plastic: largest |e^p| %.2e m\n", largest);
  EXPECT_GT(largest, 0.0);
  expect_product_matches_assembly(*model, scene, "plastic");
}

TEST(TangentProduct, MatchesAssembledTangentAfterBreakingBonds) {
  const Scene scene = small_block();
  auto model = make_model(scene);
  const auto broken = break_some_bonds(*model, scene.families);
  std::printf("broken: %zu of %zu pairs\n", broken.size(), scene.families.directed_bonds() / 2);
  ASSERT_GT(broken.size(), 10u);
  expect_product_matches_assembly(*model, scene, "broken bonds");
}

TEST(TangentProduct, MatchesAssembledTangentAnisotropic) {
  const Scene scene = small_block(", anisotropy: {direction: [1, 0, 0], ratio: 2}");
  auto model = make_model(scene);
  expect_product_matches_assembly(*model, scene, "anisotropic");
}

// The product against an independent derivative, central differences of the forces:
// K v = −(F(y + εv) − F(y − εv))/(2ε), at a stretch and a compression, unclamped. With ε |v|∞ =
// 1e-7 m against bonds of about 2e-2 m the truncation is of order (5e-6)² of |K v|; the forces'
// round-off divided by 2ε dominates (measured 1.5e-10): asserted at 1e-8. A tangent that missed the
// anisotropic weights' derivative or kept a broken bond's stiffness is off by far more.
void expect_product_is_force_derivative(Model& model, const Scene& scene, const char* label) {
  for (const double strain : {0.02, -0.03}) {
    const auto y = deformed(scene.particles, strain);
    const std::size_t n = y.size();
    const double epsilon = 1e-7;
    std::vector<std::vector<double>> differences;
    for (int probe = 0; probe < 2; ++probe) {
      std::vector<double> v = probe_direction(n, probe), up(y), down(y), f_up(n), f_down(n);
      for (std::size_t k = 0; k < n; ++k) up[k] += epsilon * v[k], down[k] -= epsilon * v[k];
      model.forces(up.data(), f_up.data());
      model.forces(down.data(), f_down.data());
      std::vector<double> d(n);
      for (std::size_t k = 0; k < n; ++k) d[k] = -(f_up[k] - f_down[k]) / (2 * epsilon);
      differences.push_back(d);
    }
    model.stiffness()->linearize(y.data(), false);
    double worst = 0;
    for (int probe = 0; probe < 2; ++probe) {
      const std::vector<double> v = probe_direction(n, probe);
      std::vector<double> product(n);
      model.stiffness()->apply_tangent(v.data(), product.data());
      worst = std::max(worst, relative_difference(product, differences[probe]));
    }
    std::printf("%s, strain %+.2f: |K v - differences of F| / |K v| = %.2e\n", label, strain,
                worst);
    EXPECT_LT(worst, 1e-8) << label << " strain " << strain;
  }
}

TEST(TangentProduct, IsTheDerivativeOfTheForcesAnisotropicAndAfterBreakingBonds) {
  const Scene anisotropic = small_block(", anisotropy: {direction: [1, 0, 0], ratio: 2}");
  auto model = make_model(anisotropic);
  expect_product_is_force_derivative(*model, anisotropic, "anisotropic");
  const Scene scene = small_block();
  auto broken = make_model(scene);
  ASSERT_GT(break_some_bonds(*broken, scene.families).size(), 10u);
  expect_product_is_force_derivative(*broken, scene, "broken bonds");
}

// The comparison sees the geometric term: in compression, where some bonds carry p < 0, the
// product with clamp_compression is far from the unclamped assembly, and the other way round.
TEST(TangentProduct, ClampOnACompressedStateChangesTheProduct) {
  const Scene scene = small_block();
  auto model = make_model(scene);
  const auto y = deformed(scene.particles, -0.03);
  const double clamped_vs_full = product_error(*model, scene.families, y, true, false);
  const double full_vs_clamped = product_error(*model, scene.families, y, false, true);
  std::printf("compressed: clamped product vs K %.2e, product vs clamped K+ %.2e\n",
              clamped_vs_full, full_vs_clamped);
  EXPECT_GT(clamped_vs_full, 1e-6);
  EXPECT_GT(full_vs_clamped, 1e-6);
}

// One pass gives forces() bitwise and elastic_energy() to round-off of the sum.
void expect_forces_and_energy_match(Model& model, const Particles& particles, const char* label) {
  for (const double strain : {0.02, -0.03}) {
    const auto y = deformed(particles, strain);
    std::vector<double> f(y.size()), g(y.size());
    model.forces(y.data(), f.data());
    const double energy = model.elastic_energy(y.data());
    const double combined = model.forces_and_energy(y.data(), g.data());
    const double relative = std::abs(combined - energy) / energy;
    std::printf("%s, strain %+.2f: energy %.6e J, |one pass - elastic_energy| / energy = %.2e\n",
                label, strain, energy, relative);
    EXPECT_GT(energy, 0.0);
    EXPECT_LT(relative, 1e-12) << label << " strain " << strain;
    for (std::size_t k = 0; k < y.size(); ++k) ASSERT_EQ(g[k], f[k]) << label << " component " << k;
  }
}

TEST(ForcesAndEnergy, MatchForcesAndElasticEnergyElastic) {
  const Scene scene = small_block();
  auto model = make_model(scene);
  expect_forces_and_energy_match(*model, scene.particles, "elastic");
}

TEST(ForcesAndEnergy, MatchForcesAndElasticEnergyWithPlasticExtension) {
  const Scene scene = small_block(", plasticity: {yield_stress: 5.0e3}");
  auto model = make_model(scene);
  EXPECT_GT(model->plastic_flow()->update_plasticity(deformed(scene.particles, 0.05).data()), 0u);
  expect_forces_and_energy_match(*model, scene.particles, "plastic");
}

// L is a symmetric graph Laplacian (rows sum to zero, positive diagonal) with 3 tr L = tr K^bw
// at rest, and a broken bond has no weight.
TEST(ScalarStiffness, IsALaplacianWithAThirdOfTheMajoriserTrace) {
  const Scene scene = small_block();
  auto model = make_model(scene);
  const auto broken = break_some_bonds(*model, scene.families);
  SparseSymmetric L = scalar_bond_pattern(scene.families);
  model->stiffness()->assemble_scalar_stiffness(L);
  const int n = L.rows;
  double trace = 0, worst_row_sum = 0, worst_asymmetry = 0, smallest_diagonal = INFINITY;
  for (int i = 0; i < n; ++i) {
    const double diagonal = L.values[L.find(i, i)];
    double sum = 0;
    for (int k = L.offsets[i]; k < L.offsets[i + 1]; ++k) {
      sum += L.values[k];
      const int j = L.columns[k];
      const int transposed = L.find(j, i);
      ASSERT_GE(transposed, 0);
      worst_asymmetry = std::max(worst_asymmetry, std::abs(L.values[k] - L.values[transposed]));
      if (j != i) {
        EXPECT_LE(L.values[k], 0.0);
      }
    }
    trace += diagonal;
    smallest_diagonal = std::min(smallest_diagonal, diagonal);
    worst_row_sum = std::max(worst_row_sum, std::abs(sum) / diagonal);
  }
  SparseSymmetric K = bond_pattern(scene.families);
  model->stiffness()->assemble_majoriser(scene.particles.reference.data(), K);
  double majoriser_trace = 0;
  for (int r = 0; r < K.rows; ++r) majoriser_trace += K.values[K.find(r, r)];
  const double trace_error = std::abs(3 * trace - majoriser_trace) / majoriser_trace;
  double broken_weight = 0;
  for (const auto& [i, j] : broken)
    broken_weight = std::max(
        {broken_weight, std::abs(L.values[L.find(i, j)]), std::abs(L.values[L.find(j, i)])});
  std::printf(
      "scalar stiffness: N = %d, max |row sum| / L_ii %.2e, max |L_ij - L_ji| %.2e, min L_ii "
      "%.3e, |3 tr L - tr K^bw| / tr K^bw %.2e, max |L_ij| of %zu broken pairs %.1e\n",
      n, worst_row_sum, worst_asymmetry, smallest_diagonal, trace_error, broken.size(),
      broken_weight);
  EXPECT_EQ(worst_asymmetry, 0.0);
  EXPECT_LT(worst_row_sum, 1e-12);
  EXPECT_GT(smallest_diagonal, 0.0);
  EXPECT_LT(trace_error, 1e-12);
  ASSERT_GT(broken.size(), 10u);
  EXPECT_EQ(broken_weight, 0.0);
}

}  // namespace
}  // namespace fissure
