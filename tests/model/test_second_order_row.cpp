// One row of the second-order LPS energy (model/second_order_row.hpp): on an interior
// particle of a tet-sampled block, with both calibrations' weights and the fit over its family.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "model/deviatoric_calibration.hpp"
#include "model/dilatation_calibration.hpp"
#include "model/second_order_row.hpp"
#include "support/random_fields.hpp"
#include "support/scenes.hpp"

namespace fissure {
namespace {

constexpr double kBulk = 5e8, kShear = 3e8;

// Row i of a block: its bonds' data, kept alive for the SecondOrderRow that points into them.
struct RowData {
  std::vector<double> xi, length, c, w, volume;
  std::vector<QuadraticBasis> fit;
  SecondOrderRow row;
};

// The particle nearest the centre of a 0.24 m block at λ = 0.04 m, whose family is whole.
RowData interior_row() {
  const Scene scene = test::block_scene(0.24, 0.04, kBulk, kShear);
  const Particles& p = scene.particles;
  const Families& f = scene.families;
  const double delta = scene.horizon_of_body[0];
  std::vector<float> omega(f.directed_bonds());
  std::vector<double> m(p.count(), 0.0);
  for (int i = 0; i < p.count(); ++i)
    for (int b = f.offsets[i]; b < f.offsets[i + 1]; ++b) {
      omega[b] = static_cast<float>(delta / f.reference_length[b]);  // Eq 5
      m[i] += double(omega[b]) * f.reference_length[b] * f.reference_length[b] *
              p.volume[f.neighbors[b]];
    }
  const std::vector<float> c = dilatation_weights(p, f, omega, m);
  const std::vector<float> w =
      deviatoric_weights(p, f, omega, std::vector<double>(p.count(), kShear), m,
                         {isotropic_deviatoric_shape()})
          .weights;
  int i = 0;
  double nearest = INFINITY;
  for (int k = 0; k < p.count(); ++k) {
    double r2 = 0;
    for (int a = 0; a < 3; ++a) r2 += std::pow(p.reference[3 * k + a] - 0.12, 2);
    if (r2 < nearest) nearest = r2, i = k;
  }
  RowData data;
  std::vector<Eigen::Vector3d> members;
  std::vector<double> fit_weight;
  for (int b = f.offsets[i]; b < f.offsets[i + 1]; ++b) {
    const int j = f.neighbors[b];
    Eigen::Vector3d xi;
    for (int a = 0; a < 3; ++a) xi[a] = p.reference[3 * j + a] - p.reference[3 * i + a];
    data.xi.insert(data.xi.end(), xi.data(), xi.data() + 3);
    data.length.push_back(f.reference_length[b]);
    data.c.push_back(c[b]), data.w.push_back(w[b]), data.volume.push_back(p.volume[j]);
    members.push_back(xi), fit_weight.push_back(delta / xi.norm() * p.volume[j]);
  }
  EXPECT_TRUE(quadratic_fit(members, fit_weight, delta, data.fit));
  const double h2 = std::pow(p.volume[i], 2.0 / 3);
  data.row = {
      .bonds = static_cast<int>(members.size()),
      .xi = data.xi.data(),
      .length = data.length.data(),
      .dilatation_weight = data.c.data(),
      .deviatoric_weight = data.w.data(),
      .member_volume = data.volume.data(),
      .fit = data.fit.data(),
      .scale = delta,
      .volume = p.volume[i],
      .bulk = kBulk,
      .shear = kShear,
      .deviatoric_modulus = 15 * kShear / m[i],
      // a cell's second moment, anisotropic so that its off-diagonal terms count
      .cell_moment = {0.06 * p.volume[i] * h2, 0.05 * p.volume[i] * h2, 0.04 * p.volume[i] * h2,
                      0.01 * p.volume[i] * h2, -0.005 * p.volume[i] * h2, 0.008 * p.volume[i] * h2},
      // on, so that every test below covers the stabilisation too
      .stabilization = 10};
  return data;
}

// d with each bond moved by up to `size` × s at random: a field the fit cannot follow, which
// the stabilisation prices.
void perturb(const RowData& data, std::mt19937& rng, double size, std::vector<double>& d) {
  std::uniform_real_distribution<double> uniform(-1, 1);
  for (double& v : d) v += size * data.row.scale * uniform(rng);
}

// Bond vectors d_b = y(x_i + ξ_b) − y(x_i) of y(x) = x + Hξ + ½ Γ(ξ, ξ), Γ_a = ∂²u_a (symmetric).
std::vector<double> deformed(const RowData& data, const Eigen::Matrix3d& H,
                             const std::array<Eigen::Matrix3d, 3>& Gamma) {
  std::vector<double> d(data.xi.size());
  for (int b = 0; b < data.row.bonds; ++b) {
    const Eigen::Vector3d xi(&data.xi[3 * b]);
    for (int a = 0; a < 3; ++a)
      d[3 * b + a] = xi[a] + H.row(a).dot(xi) + 0.5 * xi.dot(Gamma[a] * xi);
  }
  return d;
}

// A small homogeneous strain gives V_i ½ε:C:ε: the corrected bonds equal the plain ones (a
// linear field has no curvature to remove), the calibrations make the row exact, and the cell
// term vanishes. Within 2e-6: the calibration counts a row exact at 1e-6 of the energy
// (kExactDeviatoricResidual), and the stretch's nonlinearity adds O(|ε|) = 1e-6 (measured
// 4.4e-7).
TEST(SecondOrderRow, HomogeneousStrainGivesTheContinuumEnergy) {
  const RowData data = interior_row();
  std::mt19937 rng(3);
  for (int trial = 0; trial < 4; ++trial) {
    const Eigen::Matrix3d A = test::random_matrix(rng), e = 1e-6 * 0.5 * (A + A.transpose());
    const std::array<Eigen::Matrix3d, 3> none{Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero(),
                                              Eigen::Matrix3d::Zero()};
    const std::vector<double> d = deformed(data, e, none);
    const double expected = data.row.volume * test::isotropic_energy_density(e, kBulk, kShear);
    const double ratio = second_order_row_energy(data.row, d.data(), nullptr) / expected;
    std::printf("homogeneous trial %d: energy / continuum %.9f\n", trial, ratio);
    EXPECT_NEAR(ratio, 1.0, 2e-6) << "trial " << trial;
  }
}

// A displacement quadratic in x whose strain vanishes at x_i stores only the cell's share of
// its strain gradient, ½ Σ_kl M_kl ∂_kε:C:∂_lε; with a strain at x_i as well, V_i W(ε_i) on top.
// A row that kept the bonds' curvature would store instead what the bonds' midpoints sample, of
// the order of the family's second moment (δ² against the cell's h²/20, tens of times more), and
// fail; so would a cell term with a wrong index order or a missing symmetrisation. Within 2e-6,
// as above: the strains are at most about 1e-6 (measured 8e-8).
TEST(SecondOrderRow, QuadraticDisplacementGivesTheCellsEnergy) {
  const RowData data = interior_row();
  std::mt19937 rng(5);
  const auto& c = data.row.cell_moment;
  const double M[3][3] = {{c[0], c[3], c[4]}, {c[3], c[1], c[5]}, {c[4], c[5], c[2]}};
  for (int trial = 0; trial < 4; ++trial) {
    // ∂²u_a/∂x_k∂x_l, symmetric in k, l
    const std::array<Eigen::Matrix3d, 3> Gamma = test::random_curvature(rng, 1e-5);
    const Eigen::Matrix3d A = test::random_matrix(rng);
    const Eigen::Matrix3d H = trial < 2 ? Eigen::Matrix3d::Zero() : Eigen::Matrix3d(1e-7 * A);
    // ∂_kε_ab = ½(∂_k∂_b u_a + ∂_k∂_a u_b)
    std::array<Eigen::Matrix3d, 3> gradient;
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) gradient[k](a, b) = 0.5 * (Gamma[a](k, b) + Gamma[b](k, a));
    double expected =
        data.row.volume * test::isotropic_energy_density(0.5 * (H + H.transpose()), kBulk, kShear);
    const double lame = kBulk - 2 * kShear / 3;
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 3; ++l)
        expected += 0.5 * M[k][l] *
                    (lame * gradient[k].trace() * gradient[l].trace() +
                     2 * kShear * (gradient[k].array() * gradient[l].array()).sum());
    const std::vector<double> d = deformed(data, H, Gamma);
    const double ratio = second_order_row_energy(data.row, d.data(), nullptr) / expected;
    std::printf("quadratic trial %d: energy / continuum %.9f\n", trial, ratio);
    EXPECT_NEAR(ratio, 1.0, 2e-6) << "trial " << trial;
  }
}

// The gradient against central differences of the energy, at a random finite deformation (a
// rotation, a 1% strain and a curvature): each of the 3 × bonds components within 1e-6 of the
// largest. A dropped chain-rule term (the curvature's pull on every bond, or the cell term's)
// is of the size of the gradient itself.
TEST(SecondOrderRow, GradientMatchesFiniteDifferences) {
  const RowData data = interior_row();
  std::mt19937 rng(9);
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const std::array<Eigen::Matrix3d, 3> Gamma = test::random_curvature(rng, 0.3);
  std::vector<double> d = deformed(data, 0.01 * test::random_matrix(rng), Gamma);
  perturb(data, rng, 1e-3, d);
  for (int b = 0; b < data.row.bonds; ++b) {
    const Eigen::Vector3d v = R * Eigen::Vector3d(&d[3 * b]);
    for (int a = 0; a < 3; ++a) d[3 * b + a] = v[a];
  }
  std::vector<double> gradient(d.size());
  second_order_row_energy(data.row, d.data(), gradient.data());
  double largest = 0, error = 0;
  for (double g : gradient) largest = std::max(largest, std::abs(g));
  const double h = 1e-7 * data.row.scale;
  for (std::size_t k = 0; k < d.size(); ++k) {
    std::vector<double> plus = d, minus = d;
    plus[k] += h, minus[k] -= h;
    const double difference = (second_order_row_energy(data.row, plus.data(), nullptr) -
                               second_order_row_energy(data.row, minus.data(), nullptr)) /
                              (2 * h);
    error = std::max(error, std::abs(difference - gradient[k]));
  }
  std::printf("largest gradient %.3e, largest difference from central differences %.3e\n", largest,
              error);
  EXPECT_LT(error, 1e-6 * largest);
}

// The Hessian against central differences of the gradient at the same finite deformation as
// above, column by column: within 1e-6 of its largest entry, and symmetric. Leaving out the
// geometric part (the stretches' curvature), the curvature's pull in J, or the cell term's
// second derivatives each changes entries by far more.
TEST(SecondOrderRow, HessianMatchesFiniteDifferencesOfTheGradient) {
  const RowData data = interior_row();
  std::mt19937 rng(9);
  const std::array<Eigen::Matrix3d, 3> Gamma = test::random_curvature(rng, 0.3);
  std::vector<double> d = deformed(data, 0.01 * test::random_matrix(rng), Gamma);
  perturb(data, rng, 1e-3, d);
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (int b = 0; b < data.row.bonds; ++b) {
    const Eigen::Vector3d v = R * Eigen::Vector3d(&d[3 * b]);
    for (int a = 0; a < 3; ++a) d[3 * b + a] = v[a];
  }
  Eigen::MatrixXd H;
  second_order_row_hessian(data.row, d.data(), H);
  const int size = static_cast<int>(d.size());
  ASSERT_EQ(H.rows(), size);
  const double largest = H.cwiseAbs().maxCoeff();
  EXPECT_LT((H - H.transpose()).cwiseAbs().maxCoeff(), 1e-12 * largest);
  const double h = 1e-6 * data.row.scale;
  std::vector<double> plus_gradient(size), minus_gradient(size);
  double error = 0;
  for (int k = 0; k < size; ++k) {
    std::vector<double> plus = d, minus = d;
    plus[k] += h, minus[k] -= h;
    second_order_row_energy(data.row, plus.data(), plus_gradient.data());
    second_order_row_energy(data.row, minus.data(), minus_gradient.data());
    for (int r = 0; r < size; ++r)
      error = std::max(error, std::abs((plus_gradient[r] - minus_gradient[r]) / (2 * h) - H(r, k)));
  }
  std::printf("largest Hessian entry %.3e, largest difference from central differences %.3e\n",
              largest, error);
  EXPECT_LT(error, 1e-6 * largest);
}

// A rotation of the deformed row leaves its energy unchanged and rotates its gradient: the fit,
// the corrected bonds and Fᵀ∂_kF all turn with it. A cell term on sym(∂_kF) instead of
// sym(Fᵀ∂_kF) changes by the rotation's size and fails.
TEST(SecondOrderRow, EnergyIsObjective) {
  const RowData data = interior_row();
  std::mt19937 rng(13);
  const std::array<Eigen::Matrix3d, 3> Gamma = test::random_curvature(rng, 0.3);
  std::vector<double> d = deformed(data, 0.01 * test::random_matrix(rng), Gamma);
  perturb(data, rng, 1e-3, d);
  std::vector<double> gradient(d.size()), turned_gradient(d.size()), turned(d.size());
  const double energy = second_order_row_energy(data.row, d.data(), gradient.data());
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(1.9, Eigen::Vector3d(-2, 1, 0.5).normalized()).toRotationMatrix();
  for (int b = 0; b < data.row.bonds; ++b) {
    const Eigen::Vector3d v = R * Eigen::Vector3d(&d[3 * b]);
    for (int a = 0; a < 3; ++a) turned[3 * b + a] = v[a];
  }
  const double turned_energy =
      second_order_row_energy(data.row, turned.data(), turned_gradient.data());
  EXPECT_NEAR(turned_energy / energy, 1.0, 1e-10);
  double largest = 0, error = 0;
  for (int b = 0; b < data.row.bonds; ++b) {
    const Eigen::Vector3d expected = R * Eigen::Vector3d(&gradient[3 * b]);
    for (int a = 0; a < 3; ++a) {
      largest = std::max(largest, std::abs(expected[a]));
      error = std::max(error, std::abs(turned_gradient[3 * b + a] - expected[a]));
    }
  }
  EXPECT_LT(error, 1e-10 * largest);
}

// The stabilisation is ½ αμ V_i Σ_b ω_b V_b |z_b|²/|ξ_b|² / Σ_b ω_b V_b over the residuals z_b
// of the weighted least-squares quadratic through the bonds, here solved anew by QR: the row's
// energy with α = 10 less its energy with α = 0, at a quadratic field perturbed bond by bond.
// Within 1e-9: both are sums of the same squares (measured 2e-14). A residual that kept the
// fit's linear part, a wrong weight or a constant off would fail, and so would the homogeneous
// and quadratic tests above (which run with α = 10) with a residual that left out the linear
// terms of the fit.
TEST(SecondOrderRow, StabilisationPricesWhatTheFitLeaves) {
  RowData data = interior_row();
  std::mt19937 rng(17);
  std::vector<double> d =
      deformed(data, 1e-3 * test::random_matrix(rng), test::random_curvature(rng, 0.1));
  perturb(data, rng, 1e-4, d);
  const int n = data.row.bonds;
  const double s = data.row.scale;
  Eigen::MatrixXd basis(n, 9);
  Eigen::VectorXd root_weight(n);
  double mass = 0;
  for (int b = 0; b < n; ++b) {
    const Eigen::Vector3d xi(&data.xi[3 * b]);
    basis.row(b) << xi.x() / s, xi.y() / s, xi.z() / s, 0.5 * xi.x() * xi.x() / (s * s),
        0.5 * xi.y() * xi.y() / (s * s), 0.5 * xi.z() * xi.z() / (s * s), xi.x() * xi.y() / (s * s),
        xi.x() * xi.z() / (s * s), xi.y() * xi.z() / (s * s);
    root_weight(b) = std::sqrt(s / xi.norm() * data.volume[b]);  // √(ω_b V_b), the fit's weight
    mass += s / xi.norm() * data.volume[b];
  }
  const Eigen::MatrixXd weighted = root_weight.asDiagonal() * basis;
  double expected = 0;
  for (int a = 0; a < 3; ++a) {
    Eigen::VectorXd component(n);
    for (int b = 0; b < n; ++b) component(b) = d[3 * b + a];
    const Eigen::VectorXd q =
        weighted.colPivHouseholderQr().solve(root_weight.asDiagonal() * component);
    const Eigen::VectorXd z = component - basis * q;
    for (int b = 0; b < n; ++b)
      expected += s / data.length[b] * data.volume[b] * z(b) * z(b) / std::pow(data.length[b], 2);
  }
  expected *= 0.5 * 10 * kShear * data.row.volume / mass;
  const double with = second_order_row_energy(data.row, d.data(), nullptr);
  data.row.stabilization = 0;
  const double without = second_order_row_energy(data.row, d.data(), nullptr);
  std::printf("stabilisation energy %.6e, expected %.6e (row energy without it %.6e)\n",
              with - without, expected, without);
  EXPECT_GT(expected, 1e-3 * without);
  EXPECT_NEAR((with - without) / expected, 1.0, 1e-9);
}

}  // namespace
}  // namespace fissure
