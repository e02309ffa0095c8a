// The `lps` and `paper` model variants (material.model, docs/model.md) side by side on the same
// homogeneous deformations of the same tet-sampled block, checking the documented differences:
//   deviation 3: the paper's continuum constants 9/(4πδ⁴), b = 15μ/(2πδ⁵) miss κ on a discrete
//     family ("by tens of percent", notes §2 at δ = 1.45 lattice spacings), LPS's
//     per-particle m_i = Σ ω|ξ|²V makes κ exact on every particle (W = ½κ(tr ε)² under εI);
//   deviation 1: the paper's Λ = n·ξ/|ξ| makes θ depend on rotation: under y = R(90°)(1 + ε)x
//     its θ falls to ≈ ⅓, LPS's is unchanged (objectivity).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "model/model.hpp"
#include "support/dilatation.hpp"
#include "support/scenes.hpp"

namespace fissure {
namespace {

struct Figures {
  double bulk_ratio;      // κ_eff/κ, mean of W_i / (4.5 κ ε²) under εI
  double rotation_ratio;  // mean θ_i(R(90°)(1 + ε)I) / θ_i((1 + ε)I)
  double bulk_spread;     // max_i |W_i / (4.5 κ ε²) − κ_eff/κ|
};

Figures measure(const std::string& variant, double bulk, double shear, double horizon) {
  const double size = 0.2, lambda = 0.02, eps = 1e-5;
  const Scene scene = test::block_scene(size, lambda, bulk, shear, variant, horizon);
  auto model = make_model(scene);
  const Particles& p = scene.particles;
  // Interior: two default horizons from every face, so every family is complete.
  const auto members = test::interior(p, size, 2 * 1.45 * lambda);
  const double stretch[9] = {1 + eps, 0, 0, 0, 1 + eps, 0, 0, 0, 1 + eps};
  const double rotated[9] = {0, -(1 + eps), 0, 1 + eps, 0, 0, 0, 0, 1 + eps};
  const auto y0 = test::deform(p, stretch);
  std::vector<double> w(p.count()), f(y0.size());
  model->energy_density(y0.data(), w.data());
  model->forces(y0.data(), f.data());
  const auto theta = test::dilatation(*model, y0);
  const auto y1 = test::deform(p, rotated);
  model->forces(y1.data(), f.data());
  const auto theta_rotated = test::dilatation(*model, y1);
  Figures result = {0, 0, 0};
  for (int i : members) {
    result.bulk_ratio += w[i] / (4.5 * bulk * eps * eps) / members.size();
    result.rotation_ratio += theta_rotated[i] / theta[i] / members.size();
  }
  for (int i : members)
    result.bulk_spread =
        std::max(result.bulk_spread, std::abs(w[i] / (4.5 * bulk * eps * eps) - result.bulk_ratio));
  std::printf(
      "%-5s delta %.3f lambda: %zu interior particles of %d, kappa_eff/kappa %.7f (spread %.3g), "
      "theta(rotated)/theta %.7f\n",
      variant.c_str(), horizon, members.size(), p.count(), result.bulk_ratio, result.bulk_spread,
      result.rotation_ratio);
  return result;
}

// A 0.2 m block at λ = 0.02 m, κ = 2 MPa, μ = 1 MPa (ν = 0.29), at the default horizon
// δ = 1.45 λ and at δ = 0.725 λ ≈ 1.45 particle spacings (a tet of edge λ puts particles about
// λ/2 apart), the horizon of the notes' figure that docs/model.md quotes.
TEST(ModelVariants, PaperMissesBulkModulusAndObjectivityWhereLpsIsExact) {
  const double bulk = 2.0e6, shear = 1.0e6;
  const Figures lps = measure("lps", bulk, shear, 1.45);
  const Figures paper = measure("paper", bulk, shear, 1.45);
  const Figures lps_small = measure("lps", bulk, shear, 0.725);
  const Figures paper_small = measure("paper", bulk, shear, 0.725);
  // LPS: under εI every bond's extension is exactly ε|ξ| and m_i normalises each family, so
  // θ_i = 3ε and W_i = 4.5 κ ε² on every particle, and θ is unchanged by the rotation, all up
  // to the float32 bond weights (relative rounding 6e-8 each; measured spread 1.3e-8 and
  // 4.3e-8, ratios 1 to 7 digits). 1e-6 is 16 float roundings and fails a constant off by 1e-5.
  for (const Figures& f : {lps, lps_small}) {
    EXPECT_NEAR(f.bulk_ratio, 1.0, 1e-6);
    EXPECT_LT(f.bulk_spread, 1e-6);
    EXPECT_NEAR(f.rotation_ratio, 1.0, 1e-6);
  }
  // paper: the continuum constants leave each particle's κ to its family's discrete sums.
  // At δ = 0.725 λ that is "tens of percent" as documented (bound 0.1 per particle); at the
  // default horizon the families are larger and the scatter smaller (bound 0.05), while the
  // block mean comes close to κ (printed, not asserted: the docs make no claim on it).
  EXPECT_GT(paper_small.bulk_spread, 0.1);
  EXPECT_GT(paper.bulk_spread, 0.05);
  // paper θ under a 90° rotation: (1 + 2 cos φ)/3 per bond, ⅓ for a full family; an objective
  // model gives 1, so < 0.8 separates the two.
  EXPECT_LT(paper.rotation_ratio, 0.8);
  EXPECT_LT(paper_small.rotation_ratio, 0.8);
}

}  // namespace
}  // namespace fissure
