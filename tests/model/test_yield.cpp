// Where plastic flow starts and where the return map puts a bond: the per-bond criterion
// |A_dev| ≤ A^c with A^c = 10 δ σ_y / m_i (docs/model.md, Plasticity 4; notes §6).
//
// With A_dev = 4ω b_i ê = 2 (δ/|ξ|)(15μ/m_i) ê (Eq 12), the criterion reads
//   |A_dev| / A^c = 3μ |ê| / (σ_y |ξ|) ≤ 1,
// whatever the family (m_i cancels): a bond yields when its deviatoric stretch ê/|ξ| reaches
// σ_y/(3μ). Under a small homogeneous strain ε, ê/|ξ| = ξ̂ᵀ dev(ε) ξ̂ on every particle (θ_i = tr ε
// with the calibrated weights), so the load at first yield follows from the bond directions alone.
#include <gtest/gtest.h>

#include <cmath>

#include "core/named_arrays.hpp"
#include "model/model.hpp"
#include "support/dilatation.hpp"
#include "support/scenes.hpp"

namespace fissure {
namespace {

constexpr double bulk = 1.0e6, shear = 1.0e6;

// A 0.1 m block at λ = 0.02 with κ = μ = 1 MPa and yield stress σ_y.
Scene plastic_block(double yield_stress) {
  return test::block_scene(
      {.size = {0.1, 0.1, 0.1},
       .resolution = 0.02,
       .bulk = bulk,
       .shear = shear,
       .material = fmt::format(", plasticity: {{yield_stress: {}}}", yield_stress)});
}

// ξ̂ᵀ D ξ̂ for a symmetric 3×3 D (row major) and the reference direction of bond b of particle i.
double normal_component(const Scene& scene, int i, int b, const double D[9]) {
  const auto& x = scene.particles.reference;
  const int j = scene.families.neighbors[b];
  const double xi = scene.families.reference_length[b];
  double u[3], s = 0;
  for (int k = 0; k < 3; ++k) u[k] = (x[3 * j + k] - x[3 * i + k]) / xi;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) s += u[r] * D[3 * r + c] * u[c];
  return s;
}

// 3μ |ê_ij| / (σ_y |ξ_ij|) = |A_dev| / A^c for every directed bond at positions y, from the
// model's e^p and θ^p (θ at y): ê = e − e^p − (θ_i − θ^p_i)|ξ|/3.
std::vector<double> yield_ratio(Model& model, const Scene& scene, const std::vector<double>& y,
                                double yield_stress) {
  const std::vector<double> theta = test::dilatation(model, y);
  const std::vector<double> theta_p = *find_array(model.saved_state(), "model.plastic_dilatation");
  const auto& ep = model.plastic_flow()->plastic_extension();
  const Families& fam = scene.families;
  std::vector<double> ratio(fam.directed_bonds());
  for (int i = 0; i < scene.particles.count(); ++i)
    for (int b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b) {
      const int j = fam.neighbors[b];
      const double xi = fam.reference_length[b];
      const double length =
          std::hypot(y[3 * j] - y[3 * i], y[3 * j + 1] - y[3 * i + 1], y[3 * j + 2] - y[3 * i + 2]);
      const double e_hat = length - xi - ep[b] - (theta[i] - theta_p[i]) * xi / 3;
      ratio[b] = 3 * shear * std::abs(e_hat) / (yield_stress * xi);
    }
  return ratio;
}

struct Load {
  const char* name;
  double direction[9];  // the strain per unit load: ε = s D
  double dev[9];        // dev D
  double equivalent;    // the continuum's equivalent stress per unit s: first yield at σ_y
};
void PrintTo(const Load& l, std::ostream* os) { *os << l.name; }

constexpr double nu = (3 * bulk - 2 * shear) / (2 * (3 * bulk + shear));  // 0.125
constexpr double youngs = 9 * bulk * shear / (3 * bulk + shear);

class YieldOnset : public ::testing::TestWithParam<Load> {};

// A homogeneous strain s D just below the predicted first yield leaves every e^p zero and the
// reference shape at rest (no force, no energy: no permanent set); just above it, bonds yield
// and the unloaded reference shape stores energy (the rest shape has moved: a permanent set).
// Prediction: bond b yields at s = σ_y / (3μ |ξ̂ᵀ dev D ξ̂|), so first yield is at
// s* = σ_y / (3μ max_b |ξ̂ᵀ dev D ξ̂|). In the continuum (bonds in every direction) this is
// uniaxial stress σ = σ_y (max ξ̂ᵀ dev D ξ̂ = (1 + ν)·2/3 along the axis) and pure shear
// τ = 2σ_y/3 (max = 1 at 45°): a maximum deviatoric stress criterion, not von Mises (τ = σ_y/√3).
// σ_y = 100 Pa keeps the yield strain at 6e-5, so the O(ε) nonlinearity of the extension
// shifts the onset by 1e-4 relative at most; brackets of ±1e-3 hold that with a factor 10, and
// a yield constant off by 0.5% (10 → 10.05) fails them.
TEST_P(YieldOnset, StartsAtThePredictedLoad) {
  const Load& load = GetParam();
  const double yield_stress = 100;
  const Scene scene = plastic_block(yield_stress);
  auto model = make_model(scene);
  const Families& fam = scene.families;
  double largest = 0;
  for (int i = 0; i < scene.particles.count(); ++i)
    for (int b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b)
      largest = std::max(largest, std::abs(normal_component(scene, i, b, load.dev)));
  const double onset = yield_stress / (3 * shear * largest);
  const double continuum = yield_stress / load.equivalent;
  std::printf(
      "%s: first yield predicted at s = %.6e (continuum %.6e: bond directions cover %.4f "
      "of the continuum's largest deviatoric stretch)\n",
      load.name, onset, continuum, continuum / onset);
  // The sampled directions miss the continuum's extreme one by a few degrees at most.
  EXPECT_LE(continuum, onset * (1 + 1e-12));
  EXPECT_GT(continuum / onset, 0.95);
  for (const double factor : {0.999, 1.001}) {
    auto fresh = make_model(scene);
    double F[9];
    for (int k = 0; k < 9; ++k)
      F[k] = (k % 4 == 0 ? 1.0 : 0.0) + factor * onset * load.direction[k];
    const std::size_t yielded =
        fresh->plastic_flow()->update_plasticity(test::deform(scene.particles, F).data());
    const double unloaded = fresh->elastic_energy(scene.particles.reference.data());
    std::printf("  load %.3f x predicted: %zu bonds yield, unloaded reference stores %.3e J\n",
                factor, yielded, unloaded);
    if (factor < 1) {
      EXPECT_EQ(yielded, 0u);
      EXPECT_EQ(unloaded, 0.0);
      for (double ep : fresh->plastic_flow()->plastic_extension()) EXPECT_EQ(ep, 0.0);
    } else {
      EXPECT_GT(yielded, 0u);
      EXPECT_GT(unloaded, 0.0);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    Loads, YieldOnset,
    ::testing::Values(
        // uniaxial stress σ = E s: ε = s diag(1, −ν, −ν), dev ε = s(1 + ν) diag(2/3, −1/3, −1/3)
        Load{"uniaxial_stress",
             {1, 0, 0, 0, -nu, 0, 0, 0, -nu},
             {2 * (1 + nu) / 3, 0, 0, 0, -(1 + nu) / 3, 0, 0, 0, -(1 + nu) / 3},
             youngs},
        // pure shear ε12 = s, τ = 2μ s: first yield at τ = 2σ_y/3, so the equivalent is 1.5 τ = 3μ
        // s
        Load{"pure_shear", {0, 1, 0, 1, 0, 0, 0, 0, 0}, {0, 1, 0, 1, 0, 0, 0, 0, 0}, 3 * shear}),
    [](const auto& info) { return std::string(info.param.name); });

// Where the return map puts a bond. The per-bond step Δe^p = (A_dev − A^c sign A_dev)/(4ωb)
// sets |A_dev| = A^c exactly for the θ^p the step started from; the new θ^p_i = Σ_j c_ij e^p_ij V_j
// then shifts every ê of the family by +Δθ^p_i |ξ|/3 (ê = e − e^p − (θ_i − θ^p_i)|ξ|/3), so a
// bond the map moved ends at |A_dev|/A^c = |1 + sign(Δe^p) μ Δθ^p_i / σ_y|, and any bond at most
// μ |Δθ^p_i| / σ_y outside the surface. Both hold to the single-precision ω of the model's
// stiffness 4ωb (2⁻²⁴ = 6e-8 relative): 1e-7. Checked along a shear loading in steps of 0.1 and
// of 150 onset strains (s* = σ_y/(3μ), test YieldOnset). The departure μ|Δθ^p|/σ_y is not small:
// it is printed and documented (docs/model.md, Plasticity 2): the map is one sweep of the
// family's coupled projection, not the projection itself.
TEST(YieldSurface, ReturnMapLandsOnTheSurfaceOfItsStartingPlasticDilatation) {
  const double yield_stress = 1.0e4, onset = yield_stress / (3 * shear);
  for (const double increment : {0.1, 150.0}) {
    const Scene scene = plastic_block(yield_stress);
    auto model = make_model(scene);
    const Families& fam = scene.families;
    double departure = 0, identity = 0, admissible = 0;
    std::size_t moved = 0;
    // from first yield to 2 onset strains past it, or one increment past it
    const double last = onset * (1 + std::max(2.0, increment)) * (1 + 1e-12);
    for (double s = onset * (1 + increment); s <= last; s += increment * onset) {
      const double F[9] = {1, s, 0, s, 1, 0, 0, 0, 1};  // pure shear ε12 = s
      const auto y = test::deform(scene.particles, F);
      const std::vector<double> ep_before = model->plastic_flow()->plastic_extension();
      const std::vector<double> theta_p_before =
          *find_array(model->saved_state(), "model.plastic_dilatation");
      ASSERT_GT(model->plastic_flow()->update_plasticity(y.data()), 0u) << "s = " << s;
      const std::vector<double> theta_p =
          *find_array(model->saved_state(), "model.plastic_dilatation");
      const auto ratio = yield_ratio(*model, scene, y, yield_stress);
      const auto& ep = model->plastic_flow()->plastic_extension();
      for (int i = 0; i < scene.particles.count(); ++i) {
        const double shift = shear * (theta_p[i] - theta_p_before[i]) / yield_stress;
        for (int b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b) {
          admissible = std::max(admissible, ratio[b] - 1 - std::abs(shift));
          if (ep[b] == ep_before[b]) continue;
          const double sign = ep[b] > ep_before[b] ? 1.0 : -1.0;
          identity = std::max(identity, std::abs(ratio[b] - std::abs(1 + sign * shift)));
          departure = std::max(departure, std::abs(ratio[b] - 1));
          ++moved;
        }
      }
    }
    std::printf(
        "shear steps of %.1f onset strains: %zu bond returns, each on the surface of its "
        "starting theta^p within %.1e; max ||A_dev|/A^c - 1| %.2e\n",
        increment, moved, identity, departure);
    EXPECT_GT(moved, 0u);
    EXPECT_LT(identity, 1e-7);
    EXPECT_LT(admissible, 1e-7);
  }
}

}  // namespace
}  // namespace fissure
