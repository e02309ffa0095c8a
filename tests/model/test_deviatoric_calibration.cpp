// The deviatoric calibration (model/deviatoric_calibration.hpp): per row, bond stiffnesses
// g_ij = B_i w_ij from the module's weights w_ij = ρ_ij ω_ij that
// give the continuum's deviatoric energy μ|ε|² for every small traceless strain ε, checked from
// finite strains applied to the particles' positions (not from the a-vector algebra of the
// module); bounded weights; the reported residual; and ρ ≡ 1 where a row falls back.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "model/deviatoric_calibration.hpp"
#include "model/model.hpp"
#include "support/eigenvalues.hpp"
#include "support/scenes.hpp"

namespace fissure {
namespace {

using Matrix3 = Eigen::Matrix3d;
using Matrix5 = Eigen::Matrix<double, 5, 5>;

// What the calibration takes from the LPS model: ω_ij = δ/|ξ| (Eq 5) in single precision,
// m_i = Σ_j ω|ξ|²V_j from the rounded ω (notes §6), μ_i.
struct ModelInputs {
  std::vector<float> omega;
  std::vector<double> shear, weighted_volume;
};

ModelInputs model_inputs(const Particles& p, const Families& f,
                         const std::vector<double>& horizon_of_body,
                         const std::vector<double>& shear_of_body) {
  ModelInputs in;
  MaterialPoints m;
  for (int i = 0; i < p.count(); ++i) {
    m.horizon.push_back(horizon_of_body[p.body[i]]);
    in.shear.push_back(shear_of_body[p.body[i]]);
  }
  in.omega.resize(f.directed_bonds());
  in.weighted_volume.assign(p.count(), 0.0);
  for (int i = 0; i < p.count(); ++i)
    for (int b = f.offsets[i]; b < f.offsets[i + 1]; ++b) {
      const auto xi = reference_vector(p, i, f.neighbors[b]);
      in.omega[b] = static_cast<float>(influence(m, i, xi.data(), f.reference_length[b]));
      in.weighted_volume[i] += double(in.omega[b]) * f.reference_length[b] * f.reference_length[b] *
                               p.volume[f.neighbors[b]];
    }
  return in;
}

ModelInputs model_inputs(const Scene& scene) {
  std::vector<double> shear;
  for (const auto& body : scene.config.bodies) shear.push_back(body.material.shear_modulus);
  return model_inputs(scene.particles, scene.families, scene.horizon_of_body, shear);
}

DeviatoricCalibration calibrate(const Particles& p, const Families& f, const ModelInputs& in) {
  const int bodies = *std::max_element(p.body.begin(), p.body.end()) + 1;
  return deviatoric_weights(p, f, in.omega, in.shear, in.weighted_volume,
                            std::vector<DeviatoricShape>(bodies, isotropic_deviatoric_shape()));
}

// The bond stiffnesses g_ij = B_i w_ij of the weights w, B_i = 15μ_i/m_i (notes §6); with
// w = ω (ρ ≡ 1) the uncorrected model's.
std::vector<double> stiffness(const Families& f, const ModelInputs& in,
                              const std::vector<float>& w) {
  std::vector<double> g(f.directed_bonds());
  for (std::size_t i = 0; i + 1 < f.offsets.size(); ++i)
    for (int b = f.offsets[i]; b < f.offsets[i + 1]; ++b)
      g[b] = 15.0 * in.shear[i] / in.weighted_volume[i] * double(w[b]);
  return g;
}

// The orthonormal deviatoric basis of the header: xy, xz, yz, (xx − yy)/√2, (xx + yy − 2zz)/√6.
std::vector<Matrix3> deviatoric_basis() {
  const double r2 = 1 / std::sqrt(2.0), r6 = 1 / std::sqrt(6.0);
  std::vector<Matrix3> D(5, Matrix3::Zero());
  D[0](0, 1) = D[0](1, 0) = r2;
  D[1](0, 2) = D[1](2, 0) = r2;
  D[2](1, 2) = D[2](2, 1) = r2;
  D[3](0, 0) = r2;
  D[3](1, 1) = -r2;
  D[4](0, 0) = D[4](1, 1) = r6;
  D[4](2, 2) = -2 * r6;
  return D;
}

// ½ Σ_j g_ij ê_ij² V_j for the strain E on each of `rows` (0 elsewhere), from positions:
// e_ij = |y_j − y_i| − |ξ| at y = (I ± E)x, ê = e − tr(E)|ξ|/3 = e (E traceless). The mean over
// ±E removes the O(ε) terms of the extension |ξ + Eξ| − |ξ| = |ξ|(a + b/2 − a²/2 + O(ε³))
// (a = ξ̂ᵀEξ̂, b = |Eξ̂|²), as the energy is even in E to that order: what is left is the quadratic
// energy up to a relative O(ε²).
std::vector<double> deviatoric_energy(const Particles& p, const Families& f,
                                      const std::vector<double>& g, const Matrix3& E,
                                      const std::vector<int>& rows) {
  std::vector<double> w(p.count(), 0.0);
  for (const double sign : {1.0, -1.0}) {
    double F[9];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) F[3 * r + c] = (r == c ? 1.0 : 0.0) + sign * E(r, c);
    const auto y = test::deform(p, F);
#pragma omp parallel for schedule(static)
    for (std::size_t r = 0; r < rows.size(); ++r)
      for (int i = rows[r], b = f.offsets[i]; b < f.offsets[i + 1]; ++b) {
        const int j = f.neighbors[b];
        const double e = std::hypot(y[3 * j] - y[3 * i], y[3 * j + 1] - y[3 * i + 1],
                                    y[3 * j + 2] - y[3 * i + 2]) -
                         f.reference_length[b];
        w[i] += 0.25 * g[b] * e * e * p.volume[j];
      }
  }
  return w;
}

// Per row of `rows`, the 5×5 matrix Q of the deviatoric energy W = ½ xᵀQx, x_k = D_k:E, from the
// energies of the modes εD_k and (polarised) of ε(D_k + D_l): Q_kk = 2W_k/ε²,
// Q_kl = (W_kl − W_k − W_l)/ε². Also the largest relative error |W/(μ|E|²) − 1| of these 15
// strains, and of `extra` ones.
struct RowEnergies {
  std::vector<Matrix5> Q;
  std::vector<double> strain_error;
};

RowEnergies row_energies(const Particles& p, const Families& f, const std::vector<double>& g,
                         const std::vector<double>& shear, double eps,
                         const std::vector<Matrix3>& extra, const std::vector<int>& rows) {
  const auto D = deviatoric_basis();
  RowEnergies r{std::vector<Matrix5>(p.count()), std::vector<double>(p.count(), 0.0)};
  auto record = [&](const Matrix3& E, const std::vector<double>& w) {
    const double continuum = E.squaredNorm();  // |E|² per unit μ (E traceless)
    for (int i : rows)
      r.strain_error[i] = std::max(r.strain_error[i], std::abs(w[i] / (shear[i] * continuum) - 1));
  };
  std::vector<std::vector<double>> mode(5);
  for (int k = 0; k < 5; ++k) {
    mode[k] = deviatoric_energy(p, f, g, eps * D[k], rows);
    record(eps * D[k], mode[k]);
    for (int i : rows) r.Q[i](k, k) = 2 * mode[k][i] / (eps * eps);
  }
  for (int k = 0; k < 5; ++k)
    for (int l = k + 1; l < 5; ++l) {
      const Matrix3 E = eps * (D[k] + D[l]);
      const auto w = deviatoric_energy(p, f, g, E, rows);
      record(E, w);
      for (int i : rows)
        r.Q[i](k, l) = r.Q[i](l, k) = (w[i] - mode[k][i] - mode[l][i]) / (eps * eps);
    }
  for (const Matrix3& E : extra) record(E, deviatoric_energy(p, f, g, E, rows));
  return r;
}

// max |eig(Q/2μ) − 1|: the largest relative error of the deviatoric energy over all strains.
double eigen_residual(const Matrix5& Q, double shear) {
  return (test::symmetric_eigenvalues(Q / (2 * shear)).array() - 1).abs().maxCoeff();
}

// Random symmetric traceless strains of norm eps.
std::vector<Matrix3> random_deviatoric_strains(int count, double eps) {
  std::mt19937 random(15);
  std::normal_distribution<double> normal;
  std::vector<Matrix3> strains;
  for (int k = 0; k < count; ++k) {
    Matrix3 E;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) E(r, c) = normal(random);
    E = 0.5 * (E + E.transpose()).eval();
    E -= E.trace() / 3 * Matrix3::Identity();
    strains.push_back(eps * E / E.norm());
  }
  return strains;
}

// The 0.2 m tet block at λ = 0.02 with E = 1 MPa and Poisson ratio nu, built once per process.
const Scene& block(double nu) {
  static std::deque<std::pair<double, Scene>> scenes;  // a deque keeps earlier references valid
  for (const auto& [n, scene] : scenes)
    if (n == nu) return scene;
  const double E = 1.0e6;
  scenes.emplace_back(nu, test::block_scene(0.2, 0.02, E / (3 * (1 - 2 * nu)), E / (2 * (1 + nu))));
  return scenes.back().second;
}

// Every small traceless strain gives μ|ε|² on every row the calibration reports exact, and no
// row is worse than with ρ ≡ 1, each row's error over all strains taken from the 5×5 energy
// matrix of its finite strains. Tolerance on exact rows: the module calls a row exact when its
// residual, computed from the rounded g, is ≤ kExactDeviatoricResidual, so every strain's energy
// is within that relative amount; the ± pair leaves a relative O(ε²) = 1e-12, and the round-off
// of e = |y_j − y_i| − |ξ| (positions of 0.2 m, 1e-16 relative, against e ≈ 1e-6 |ξ| ≈ 3e-8 m)
// is about 1e-9 relative per bond and the polarised entries Q_kl lose no more than a factor of a
// few to cancellation: 1e-8 covers them. (Measured: 2.4e-8 at most, the rounding of g.) ρ does
// not depend on μ, which scales B_i and the target alike; the three Poisson ratios check that μ
// is carried through. Target μ instead of 2μ, V_j or |ξ|² left out of the weights, a wrong basis
// vector, a row starting from the previous row's multipliers or too few proximal passes (no
// row exact) fail it. The energies with ρ ≡ 1 are only compared on the rows not exact, so only
// those are computed.
class DeviatoricCalibrationPoisson : public ::testing::TestWithParam<double> {};

TEST_P(DeviatoricCalibrationPoisson, EveryDeviatoricStrainIsExactOnCalibratedRows) {
  const Scene& scene = block(GetParam());
  const Particles& p = scene.particles;
  const Families& f = scene.families;
  const ModelInputs in = model_inputs(scene);
  const DeviatoricCalibration cal = calibrate(p, f, in);
  const double eps = 1e-6, tolerance = kExactDeviatoricResidual + 1e-8;
  const auto extra = random_deviatoric_strains(3, eps);
  std::vector<int> every_row(p.count()), not_exact;
  for (int i = 0; i < p.count(); ++i) {
    every_row[i] = i;
    if (cal.residual[i] > kExactDeviatoricResidual) not_exact.push_back(i);
  }
  const RowEnergies calibrated =
      row_energies(p, f, stiffness(f, in, cal.weights), in.shear, eps, extra, every_row);
  const RowEnergies plain =
      row_energies(p, f, stiffness(f, in, in.omega), in.shear, eps, extra, not_exact);
  int exact = 0, inexact = 0;
  double exact_error = 0, inexact_largest = 0, plain_largest = 0;
  for (int i = 0; i < p.count(); ++i) {
    const double residual = eigen_residual(calibrated.Q[i], in.shear[i]);
    if (cal.residual[i] <= kExactDeviatoricResidual) {
      ++exact;
      exact_error = std::max({exact_error, residual, calibrated.strain_error[i]});
      EXPECT_LE(calibrated.strain_error[i], tolerance) << "row " << i;
      EXPECT_LE(residual, tolerance) << "row " << i;
      // and what the positions give is the residual the module reports (the rounding of g)
      EXPECT_LE(residual, cal.residual[i] + 1e-8) << "row " << i;
    } else {
      ++inexact;
      inexact_largest = std::max(inexact_largest, residual);
      const double plain_residual = eigen_residual(plain.Q[i], in.shear[i]);
      plain_largest = std::max(plain_largest, plain_residual);
      EXPECT_LE(residual, plain_residual + 1e-8) << "row " << i;
    }
  }
  std::printf(
      "nu %.2f: %d particles, %zu bonds; exact rows %d (largest error from positions %.2e), not "
      "exact %d (largest residual %.3f, module %.3f), rows with rho = 1: %d; rho = 1 on the rows "
      "not exact: largest residual %.3f\n",
      GetParam(), p.count(), f.directed_bonds(), exact, exact_error, inexact, inexact_largest,
      cal.largest_residual, cal.fallback_rows, plain_largest);
  EXPECT_EQ(exact, cal.exact_rows);
  // Most rows are exact (measured 95.6%; the others sit on edges and corners of the block).
  EXPECT_GT(exact, 0.9 * p.count());
}

INSTANTIATE_TEST_SUITE_P(Poisson, DeviatoricCalibrationPoisson, ::testing::Values(0.1, 0.25, 0.45));

// One tet layer (λ = 0.02 thick): a bar 0.2 × 0.02 × 0.02 m, every family cut by four faces and
// too flat for 15 conditions, and a sheet 0.2 × 0.2 × 0.02 m, whose rows run into the bounds.
const Scene& thin_bar() {
  static const Scene scene = test::block_scene(
      {.size = {0.2, 0.02, 0.02}, .resolution = 0.02, .bulk = 2.0e6, .shear = 1.0e6});
  return scene;
}
const Scene& thin_sheet() {
  static const Scene scene = test::block_scene(
      {.size = {0.2, 0.2, 0.02}, .resolution = 0.02, .bulk = 2.0e6, .shear = 1.0e6});
  return scene;
}

// A flat square lattice of 15 × 15 particles (spacing h, δ = 3h): every family lies in a plane,
// so the a_j span only part of the deviatoric space and no row's Gram matrix is regular.
struct Sheet {
  Particles particles;
  Families families;
  std::vector<double> horizon{0.03};
};

Sheet flat_sheet() {
  const double h = 0.01;
  Sheet sheet;
  for (int i = 0; i < 15; ++i)
    for (int j = 0; j < 15; ++j) {
      sheet.particles.reference.insert(sheet.particles.reference.end(), {i * h, j * h, 0.0});
      sheet.particles.volume.push_back(h * h * h);
      sheet.particles.body.push_back(0);
    }
  sheet.families = build_families(sheet.particles, sheet.horizon);
  return sheet;
}

// Row i's w against ω_ij: ρ_min ω ≤ w ≤ ρ_max ω up to the rounding of w to single precision
// (2⁻²⁴ relative; 2⁻²³ allows for that of ρ in double), and w finite. Returns the range of
// w / ω.
std::pair<double, double> check_bounds(const Families& f, const ModelInputs& in,
                                       const DeviatoricCalibration& cal, const char* name) {
  const double rounding = std::ldexp(1.0, -23);
  double low = std::numeric_limits<double>::infinity(), high = 0;
  int outside = 0;
  for (std::size_t i = 0; i + 1 < f.offsets.size(); ++i)
    for (int b = f.offsets[i]; b < f.offsets[i + 1]; ++b) {
      const double plain = in.omega[b];
      const double g = cal.weights[b];
      if (!(std::isfinite(g) && g >= kMinimumDeviatoricFactor * plain * (1 - rounding) &&
            g <= kMaximumDeviatoricFactor * plain * (1 + rounding)) &&
          outside++ == 0)
        ADD_FAILURE() << name << " row " << i << " bond " << b << ": w " << g << ", omega "
                      << plain;
      low = std::min(low, g / plain);
      high = std::max(high, g / plain);
    }
  EXPECT_EQ(outside, 0) << name << ": bonds outside the bounds";
  int outcome[4] = {};
  for (const DeviatoricRow row : cal.rows) ++outcome[int(row)];
  std::printf(
      "%s: %zu rows, w / omega in [%.7f, %.7f]; calibrated %d, too few bonds %d, singular "
      "%d, not better %d; exact %d, largest residual %.3f\n",
      name, cal.rows.size(), low, high, outcome[0], outcome[1], outcome[2], outcome[3],
      cal.exact_rows, cal.largest_residual);
  return {low, high};
}

// The bounds hold on every bond of the block and the one-layer sheet, where some weights reach
// both bounds (so the bounds are what holds them), and of the one-layer bar and the flat
// lattice sheet, where every row keeps ρ ≡ 1. Unclipped Lagrange weights (negative on edge
// rows), NaN from a singular Gram matrix or a bound applied to the wrong factor fail it.
TEST(DeviatoricCalibration, WeightsArePositiveAndBounded) {
  const double rounding = std::ldexp(1.0, -23);
  for (const Scene* scene : {&block(0.25), &thin_sheet(), &thin_bar()}) {
    const ModelInputs in = model_inputs(*scene);
    const auto [low, high] =
        check_bounds(scene->families, in, calibrate(scene->particles, scene->families, in),
                     scene == &thin_bar()     ? "one-layer bar"
                     : scene == &thin_sheet() ? "one-layer sheet"
                                              : "block");
    if (scene == &thin_bar()) {
      EXPECT_NEAR(low, 1.0, rounding);
      EXPECT_NEAR(high, 1.0, rounding);
    } else {
      EXPECT_LT(low, kMinimumDeviatoricFactor * (1 + rounding));
      EXPECT_GT(high, kMaximumDeviatoricFactor * (1 - rounding));
    }
  }
  const Sheet sheet = flat_sheet();
  const ModelInputs sheet_in =
      model_inputs(sheet.particles, sheet.families, sheet.horizon, {1.0e6});
  const auto [low, high] = check_bounds(
      sheet.families, sheet_in, calibrate(sheet.particles, sheet.families, sheet_in), "flat sheet");
  EXPECT_NEAR(low, 1.0, rounding);
  EXPECT_NEAR(high, 1.0, rounding);
}

// max |eig(A_i/2μ_i) − 1| recomputed from the weights with the strain basis as 3×3 tensors,
// A_kl = Σ_j g_ij |ξ|² V_j (ξ̂ᵀD_kξ̂)(ξ̂ᵀD_lξ̂).
std::vector<double> recomputed_residual(const Particles& p, const Families& f,
                                        const std::vector<double>& g,
                                        const std::vector<double>& shear) {
  const auto D = deviatoric_basis();
  std::vector<double> residual(p.count());
  for (int i = 0; i < p.count(); ++i) {
    Matrix5 A = Matrix5::Zero();
    for (int b = f.offsets[i]; b < f.offsets[i + 1]; ++b) {
      const auto xi = reference_vector(p, i, f.neighbors[b]);
      const Eigen::Vector3d n = Eigen::Vector3d(xi[0], xi[1], xi[2]) / f.reference_length[b];
      Eigen::Matrix<double, 5, 1> a;
      for (int k = 0; k < 5; ++k) a(k) = n.dot(D[k] * n);
      A += g[b] * f.reference_length[b] * f.reference_length[b] * p.volume[f.neighbors[b]] * a *
           a.transpose();
    }
    residual[i] = eigen_residual(A, shear[i]);
  }
  return residual;
}

// The reported residual and summary are what the weights give, from the rounded g: to 1e-12
// (double round-off of sums of O(1) terms). A residual taken from the unrounded weights (off by
// about 6e-8), against μ instead of 2μ, or a wrong count fails it.
TEST(DeviatoricCalibration, ResidualMatchesRecomputation) {
  for (const Scene* scene : {&block(0.25), &thin_sheet(), &thin_bar()}) {
    const Particles& p = scene->particles;
    const ModelInputs in = model_inputs(*scene);
    const DeviatoricCalibration cal = calibrate(p, scene->families, in);
    const auto residual = recomputed_residual(
        p, scene->families, stiffness(scene->families, in, cal.weights), in.shear);
    int exact = 0, fallback = 0;
    double largest = 0;
    for (int i = 0; i < p.count(); ++i) {
      EXPECT_NEAR(cal.residual[i], residual[i], 1e-12) << "row " << i;
      exact += residual[i] <= kExactDeviatoricResidual;
      fallback += cal.rows[i] != DeviatoricRow::calibrated;
      largest = std::max(largest, residual[i]);
    }
    EXPECT_EQ(cal.exact_rows, exact);
    EXPECT_EQ(cal.fallback_rows, fallback);
    EXPECT_NEAR(cal.largest_residual, largest, 1e-12);
  }
}

// A row that keeps ρ ≡ 1 has the uncorrected model's weights bit for bit, w = ω:
// a block row cut to 10 bonds (too few for 15 conditions), every row of the one-layer bar and
// every row of the flat sheet (singular Gram matrices). The other rows of the block are unchanged
// by the cut row, bit for bit (rows are independent). A fallback that applies ρ anyway, rounds ρω
// differently, or leaks one row's scratch into another fails it.
TEST(DeviatoricCalibration, UncalibratedRowIsTheCurrentModel) {
  const Scene& scene = block(0.25);
  const Particles& p = scene.particles;
  const Families& f = scene.families;
  const int cut = p.count() / 2;
  Families fewer;
  fewer.offsets.push_back(0);
  for (int i = 0; i < p.count(); ++i) {
    const int end = i == cut ? f.offsets[i] + 10 : f.offsets[i + 1];
    for (int b = f.offsets[i]; b < end; ++b) {
      fewer.neighbors.push_back(f.neighbors[b]);
      fewer.reference_length.push_back(f.reference_length[b]);
    }
    fewer.offsets.push_back(static_cast<int>(fewer.neighbors.size()));
  }
  std::vector<double> shear;
  for (const auto& body : scene.config.bodies) shear.push_back(body.material.shear_modulus);
  const ModelInputs in = model_inputs(p, fewer, scene.horizon_of_body, shear);
  const DeviatoricCalibration cal = calibrate(p, fewer, in);
  const DeviatoricCalibration whole = calibrate(p, f, model_inputs(scene));
  const std::vector<float>& plain = in.omega;
  ASSERT_EQ(cal.rows[cut], DeviatoricRow::too_few_bonds);
  for (int b = fewer.offsets[cut]; b < fewer.offsets[cut + 1]; ++b)
    EXPECT_EQ(cal.weights[b], plain[b]) << "bond " << b;
  int changed = 0;
  for (int i = 0; i < p.count(); ++i) {
    if (i == cut) continue;
    const int shift = i > cut ? f.offsets[cut + 1] - fewer.offsets[cut + 1] : 0;
    for (int b = fewer.offsets[i]; b < fewer.offsets[i + 1]; ++b)
      changed += cal.weights[b] != whole.weights[b + shift];
  }
  EXPECT_EQ(changed, 0);
  // The one-layer bar's rows fall back by themselves (too few bonds, or too flat a family).
  const Scene& bar = thin_bar();
  const ModelInputs bar_in = model_inputs(bar);
  const DeviatoricCalibration bar_cal = calibrate(bar.particles, bar.families, bar_in);
  EXPECT_EQ(bar_cal.fallback_rows, bar.particles.count());
  EXPECT_EQ(bar_cal.weights, bar_in.omega);

  const Sheet sheet = flat_sheet();
  const ModelInputs sheet_in =
      model_inputs(sheet.particles, sheet.families, sheet.horizon, {1.0e6});
  const DeviatoricCalibration sheet_cal = calibrate(sheet.particles, sheet.families, sheet_in);
  const std::vector<float>& sheet_plain = sheet_in.omega;
  for (int i = 0; i < sheet.particles.count(); ++i) {
    const int bonds = sheet.families.offsets[i + 1] - sheet.families.offsets[i];
    EXPECT_EQ(sheet_cal.rows[i],
              bonds < 15 ? DeviatoricRow::too_few_bonds : DeviatoricRow::singular)
        << "row " << i;
  }
  EXPECT_EQ(sheet_cal.weights, sheet_plain);
  EXPECT_EQ(sheet_cal.fallback_rows, sheet.particles.count());
}

}  // namespace
}  // namespace fissure
