// The second-order model with fictitious particles (model/second_order_model.hpp; issue 15), on
// a tet-sampled block whose families its images complete.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "integrators/dynamics.hpp"
#include "integrators/registry.hpp"
#include "linear/sparse_symmetric.hpp"
#include "model/second_order_model.hpp"
#include "support/error_message.hpp"
#include "support/random_fields.hpp"
#include "support/scenes.hpp"

namespace fissure {
namespace {

constexpr double kBulk = 5e8, kShear = 3e8, kLambda = 0.04;
constexpr double kSize[3] = {0.24, 0.12, 0.12};

Scene block() {
  return test::block_scene({.size = {kSize[0], kSize[1], kSize[2]},
                            .resolution = kLambda,
                            .bulk = kBulk,
                            .shear = kShear,
                            .scene = "output: {surface: true}\n"});
}

// y(x) = x + H x + ½ Γ_a(x, x) per component a, x from the block's centre.
std::vector<double> deformed(const Particles& p, const Eigen::Matrix3d& H,
                             const std::array<Eigen::Matrix3d, 3>& Gamma) {
  std::vector<double> y(p.reference);
  for (int i = 0; i < p.count(); ++i) {
    Eigen::Vector3d x;
    for (int a = 0; a < 3; ++a) x[a] = p.reference[3 * i + a] - 0.5 * kSize[a];
    for (int a = 0; a < 3; ++a) y[3 * i + a] += H.row(a).dot(x) + 0.5 * x.dot(Gamma[a] * x);
  }
  return y;
}

// A finite deformation: a random curvature of size 0.05 and a random strain of size 0.01.
std::vector<double> randomly_deformed(const Particles& p, std::mt19937& rng) {
  const std::array<Eigen::Matrix3d, 3> Gamma = test::random_curvature(rng, 0.05);
  return deformed(p, 0.01 * test::random_matrix(rng), Gamma);
}

double total_energy(SecondOrderModel& model, const std::vector<double>& y) {
  std::vector<double> f(y.size());
  return model.forces_and_energy(y.data(), f.data());
}

// The images complete every family: every particle's deviatoric calibration is exact, and a
// small homogeneous strain gives each particle ½ε:C:ε within 2e-6 (a row counts as exact at
// 1e-6, and the stretch's nonlinearity adds O(|ε|) = 1e-6). Without images the block's surface rows
// are 5–10% off (test_full_surface_correction.cpp's uncalibrated figures).
TEST(SecondOrderModel, HomogeneousStrainIsExactOnEveryParticle) {
  const Scene scene = block();
  const auto model = make_second_order_model(scene, material_points(scene));
  const Particles& p = scene.particles;
  double images = 0, exact = 0;
  for (const auto& [name, value] : model->statistics()) {
    if (name == "fictitious_particles") images = value;
    if (name == "deviatoric_exact_rows") exact = value;
  }
  std::printf("%d particles, %.0f images, %.0f exactly calibrated rows\n", p.count(), images,
              exact);
  EXPECT_GT(images, 0);
  EXPECT_EQ(exact, p.count());
  std::mt19937 rng(1);
  const Eigen::Matrix3d A = test::random_matrix(rng), e = 1e-6 * 0.5 * (A + A.transpose());
  const std::array<Eigen::Matrix3d, 3> none{Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero(),
                                            Eigen::Matrix3d::Zero()};
  const std::vector<double> y = deformed(p, e, none);
  std::vector<double> w(p.count());
  model->energy_density(y.data(), w.data());
  double worst = 0;
  for (int i = 0; i < p.count(); ++i)
    worst = std::max(worst, std::abs(w[i] / test::isotropic_energy_density(e, kBulk, kShear) - 1));
  std::printf("largest relative error of W_i: %.2e\n", worst);
  EXPECT_LT(worst, 2e-6);
}

// Any displacement quadratic in x stores exactly the continuum's energy of the block,
// ∫W = V W(ε_0) + ½ Σ_kl J_kl ∂_kε:C:∂_lε with J = V/12 diag(a², b², c²) about its centre: each
// row gives its particle's V_i W(ε(x_i)) and its tet's second moment the rest, and the tets tile
// the block. Without the cell term the sum is short by the particles' quadrature (a few %),
// without the curvature removal it is long by the bonds' midpoint spread, and images that moved
// wrongly would break both. Within 2e-6, as above (strains of about 1e-6).
TEST(SecondOrderModel, QuadraticDisplacementStoresTheBlocksContinuumEnergy) {
  const Scene scene = block();
  const auto model = make_second_order_model(scene, material_points(scene));
  std::mt19937 rng(2);
  for (int trial = 0; trial < 3; ++trial) {
    const std::array<Eigen::Matrix3d, 3> Gamma = test::random_curvature(rng, 1e-5);
    const Eigen::Matrix3d A = test::random_matrix(rng);
    const Eigen::Matrix3d H = 1e-7 * trial * A;
    std::array<Eigen::Matrix3d, 3> gradient;  // ∂_kε_ab = ½(∂_k∂_b u_a + ∂_k∂_a u_b)
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) gradient[k](a, b) = 0.5 * (Gamma[a](k, b) + Gamma[b](k, a));
    const double volume = kSize[0] * kSize[1] * kSize[2], lame = kBulk - 2 * kShear / 3;
    double expected =
        volume * test::isotropic_energy_density(0.5 * (H + H.transpose()), kBulk, kShear);
    for (int k = 0; k < 3; ++k)
      expected += 0.5 * volume / 12 * kSize[k] * kSize[k] *
                  (lame * gradient[k].trace() * gradient[k].trace() +
                   2 * kShear * (gradient[k].array() * gradient[k].array()).sum());
    const double energy = total_energy(*model, deformed(scene.particles, H, Gamma));
    std::printf("trial %d: energy / continuum %.8f\n", trial, energy / expected);
    EXPECT_NEAR(energy / expected, 1.0, 2e-6);
  }
}

// Forces are −∂Π/∂y, the images' folded back through their stencils: the derivative of the
// energy along random directions by central differences against −f·v, at a finite deformation.
// A fold that missed the images' forces, or a sign, fails by O(1).
TEST(SecondOrderModel, ForcesAreMinusTheGradientOfTheEnergy) {
  const Scene scene = block();
  const auto model = make_second_order_model(scene, material_points(scene));
  std::mt19937 rng(3);
  const std::array<Eigen::Matrix3d, 3> Gamma = test::random_curvature(rng, 0.05);
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, -1, 2).normalized()).toRotationMatrix();
  const Eigen::Matrix3d H = R * (Eigen::Matrix3d::Identity() + 0.01 * test::random_matrix(rng)) -
                            Eigen::Matrix3d::Identity();
  const std::vector<double> y = deformed(scene.particles, H, Gamma);
  std::vector<double> f(y.size());
  model->forces(y.data(), f.data());
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 3; ++trial) {
    std::vector<double> v(y.size()), plus(y), minus(y);
    double power = 0;
    for (std::size_t k = 0; k < v.size(); ++k) v[k] = normal(rng), power -= f[k] * v[k];
    const double h = 1e-6 * kLambda;
    for (std::size_t k = 0; k < v.size(); ++k) plus[k] += h * v[k], minus[k] -= h * v[k];
    const double difference = (total_energy(*model, plus) - total_energy(*model, minus)) / (2 * h);
    std::printf("direction %d: dΠ/dv %.6e, −f·v %.6e\n", trial, difference, power);
    EXPECT_NEAR(difference / power, 1.0, 1e-6);
  }
}

// The stiffness (second_order_stiffness.cpp) is the derivative of the forces: at a finite
// deformation, K v assembled on the model's own pattern against −(f(y + hv) − f(y − hv))/2h along
// random directions (central differences: truncation O(h²), round-off about 1e-9 of K v here,
// asserted below 1e-8; measured 1.1e-10),
// and the matrix-free product equal to the assembled one to round-off. A fold that dropped the
// images' stencils, a pattern missing a coupling (assembly would not find its entry) or a
// transposed block fails by O(1).
TEST(SecondOrderModel, TangentIsTheDerivativeOfTheForces) {
  const Scene scene = block();
  const auto model = make_second_order_model(scene, material_points(scene));
  std::mt19937 rng(6);
  const std::vector<double> y = randomly_deformed(scene.particles, rng);
  Stiffness& stiffness = *model->stiffness();
  EXPECT_FALSE(stiffness.one_hop_matrices());
  SparseSymmetric K = stiffness.tangent_pattern(scene.families);
  K.values.assign(K.columns.size(), 0.0);
  stiffness.assemble_tangent(y.data(), K, false);
  stiffness.linearize(y.data(), false);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 3; ++trial) {
    std::vector<double> v(y.size()), plus(y), minus(y), f_plus(y.size()), f_minus(y.size()),
        assembled(y.size()), product(y.size());
    for (double& c : v) c = normal(rng);
    const double h = 1e-6 * kLambda;
    for (std::size_t k = 0; k < v.size(); ++k) plus[k] += h * v[k], minus[k] -= h * v[k];
    model->forces(plus.data(), f_plus.data());
    model->forces(minus.data(), f_minus.data());
    K.multiply(v.data(), assembled.data());
    stiffness.apply_tangent(v.data(), product.data());
    double norm = 0, difference_error = 0, product_error = 0;
    for (std::size_t k = 0; k < v.size(); ++k) {
      const double difference = -(f_plus[k] - f_minus[k]) / (2 * h);
      norm += assembled[k] * assembled[k];
      difference_error += (difference - assembled[k]) * (difference - assembled[k]);
      product_error += (product[k] - assembled[k]) * (product[k] - assembled[k]);
    }
    const double difference_ratio = std::sqrt(difference_error / norm),
                 product_ratio = std::sqrt(product_error / norm);
    std::printf("direction %d: |Kv - differences| / |Kv| %.2e, |matrix-free - Kv| / |Kv| %.2e\n",
                trial, difference_ratio, product_ratio);
    EXPECT_LT(difference_ratio, 1e-8);
    EXPECT_LT(product_ratio, 1e-12);
  }
}

// A rigid rotation of a deformed block leaves its energy unchanged and rotates its forces.
TEST(SecondOrderModel, EnergyAndForcesAreObjective) {
  const Scene scene = block();
  const auto model = make_second_order_model(scene, material_points(scene));
  std::mt19937 rng(4);
  const std::vector<double> y = randomly_deformed(scene.particles, rng);
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(2.1, Eigen::Vector3d(0.3, 1, -0.5).normalized()).toRotationMatrix();
  std::vector<double> turned(y.size()), f(y.size()), turned_f(y.size());
  for (std::size_t i = 0; i < y.size() / 3; ++i) {
    const Eigen::Vector3d v = R * Eigen::Vector3d(&y[3 * i]) + Eigen::Vector3d(0.5, -1, 2);
    for (int a = 0; a < 3; ++a) turned[3 * i + a] = v[a];
  }
  const double energy = model->forces_and_energy(y.data(), f.data());
  const double turned_energy = model->forces_and_energy(turned.data(), turned_f.data());
  EXPECT_NEAR(turned_energy / energy, 1.0, 1e-9);
  double largest = 0, error = 0;
  for (std::size_t i = 0; i < y.size() / 3; ++i) {
    const Eigen::Vector3d expected = R * Eigen::Vector3d(&f[3 * i]);
    for (int a = 0; a < 3; ++a) {
      largest = std::max(largest, std::abs(expected[a]));
      error = std::max(error, std::abs(turned_f[3 * i + a] - expected[a]));
    }
  }
  EXPECT_LT(error, 1e-8 * largest);
}

// The stable step is a bound: the highest frequency of the linearised block, by power iteration
// on M⁻¹K with K v from central differences of the forces (a lower bound on λmax), gives
// 2/√λ no shorter than the model's step. Printed: how much shorter the bound is, and the LPS
// model's step on the same particles for scale.
TEST(SecondOrderModel, StableTimeStepIsABound) {
  const Scene scene = block();
  const auto model = make_second_order_model(scene, material_points(scene));
  const Particles& p = scene.particles;
  const std::vector<double>& x = p.reference;
  std::vector<double> v(x.size()), Kv(x.size()), plus(x.size()), minus(x.size()), f_plus(x.size()),
      f_minus(x.size());
  std::mt19937 rng(5);
  std::normal_distribution<double> normal;
  for (double& c : v) c = normal(rng);
  double lambda = 0;
  for (int it = 0; it < 200; ++it) {
    double norm = 0;
    for (double c : v) norm += c * c;
    norm = std::sqrt(norm);
    for (double& c : v) c /= norm;
    const double h = 1e-6 * kLambda;
    for (std::size_t k = 0; k < x.size(); ++k)
      plus[k] = x[k] + h * v[k], minus[k] = x[k] - h * v[k];
    model->forces(plus.data(), f_plus.data());
    model->forces(minus.data(), f_minus.data());
    double vMv = 0, vKv = 0;
    for (std::size_t k = 0; k < x.size(); ++k) {
      Kv[k] = -(f_plus[k] - f_minus[k]) / (2 * h);
      vKv += v[k] * Kv[k], vMv += v[k] * v[k] * p.mass[k / 3];
    }
    lambda = vKv / vMv;  // Rayleigh quotient of M⁻¹K
    for (std::size_t k = 0; k < x.size(); ++k) v[k] = Kv[k] / p.mass[k / 3];
  }
  const double dt = model->stable_time_step(), limit = 2 / std::sqrt(lambda);
  std::printf(
      "model's step %.4e s, 2/sqrt(lambda) from power iteration %.4e s (ratio %.3f); the lps "
      "model's step %.4e s\n",
      dt, limit, dt / limit, make_model(scene)->stable_time_step());
  EXPECT_LE(dt, limit);
}

// -------------------------------------------------------------------------------------------
// The config: material.surface_correction: fictitious and a clamped face.

std::string fictitious_scene(const std::string& material, const std::string& rest) {
  return fmt::format(
      "time: {{end: 1.0}}\nbodies:\n"
      "  - geometry: {{box: {{min: [0, 0, 0], max: [{}, {}, {}]}}}}\n"
      "    resolution: {}\n"
      "    material: {{density: 1000, bulk_modulus: {}, shear_modulus: {}{}}}\n{}",
      kSize[0], kSize[1], kSize[2], kLambda, kBulk, kShear, material, rest);
}

const std::string kClamp = "constraints:\n  - {clamp: {point: [0, 0, 0], normal: [-1, 0, 0]}}\n";

// The key makes the second-order model (the same forces as make_second_order_model's, to the
// threads' summation order), and a clamped face holds no particle but resists a translation:
// under a uniform displacement the free block's forces vanish to round-off (its images'
// stencils sum to 1), the clamped one's do not (the images behind x = 0 stay put) and pull
// back, against the displacement, at least as a bar's axial stiffness would.
TEST(SecondOrderModel, ConfigKeyMakesItAndAClampedFaceResistsATranslation) {
  const Scene free_block =
      build_scene(parse_config(fictitious_scene(", surface_correction: fictitious", ""), "a.yaml"));
  const Scene clamped = build_scene(
      parse_config(fictitious_scene(", surface_correction: fictitious", kClamp), "a.yaml"));
  EXPECT_TRUE(clamped.config.constraints.at(0).clamp);
  const auto clamped_model = make_model(clamped);
  Dynamics dynamics(clamped, *clamped_model);
  std::vector<int> held;
  std::vector<Vec3> velocity;
  dynamics.held(0, held, velocity);
  EXPECT_TRUE(held.empty());
  const auto direct = make_second_order_model(free_block, material_points(free_block));
  const std::vector<double> y_curved =
      deformed(free_block.particles, 0.001 * Eigen::Matrix3d::Identity(),
               {Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero()});
  std::vector<double> f_direct(y_curved.size()), f_config(y_curved.size());
  direct->forces(y_curved.data(), f_direct.data());
  const auto free_model = make_model(free_block);
  free_model->forces(y_curved.data(), f_config.data());
  double force_difference = 0, force_scale = 0;  // threads sum in any order: round-off apart
  for (std::size_t k = 0; k < f_direct.size(); ++k) {
    force_difference = std::max(force_difference, std::abs(f_config[k] - f_direct[k]));
    force_scale = std::max(force_scale, std::abs(f_direct[k]));
  }
  EXPECT_LT(force_difference, 1e-12 * force_scale);

  double largest_free = 0;
  for (const Scene* scene : {&free_block, &clamped}) {
    std::vector<double> y(scene->particles.reference), f(y.size());
    for (std::size_t i = 0; i < y.size(); i += 3) y[i] += 1e-6;
    (scene == &free_block ? *free_model : *clamped_model).forces(y.data(), f.data());
    double along = 0, largest = 0;
    for (std::size_t i = 0; i < y.size(); i += 3) {
      along += f[i];
      for (int a = 0; a < 3; ++a) largest = std::max(largest, std::abs(f[i + a]));
    }
    std::printf("%s: largest force %.3e N, sum along the displacement %.3e N\n",
                scene == &free_block ? "free" : "clamped", largest, along);
    if (scene == &free_block) {
      largest_free = largest;
    } else {
      EXPECT_LT(largest_free, 1e-8 * largest);
      // at least a bar's axial resistance E A u / L, E > μ
      EXPECT_LT(along, -kShear * kSize[1] * kSize[2] * 1e-6 / kSize[0]);
    }
  }
}

// What the model cannot do is refused at load, naming the key: a clamp without it or off the
// body's faces, fracture, plasticity, initial cracks; and an implicit integrator asking for a
// one-hop matrix it lacks.
TEST(SecondOrderModel, ConfigRefusesWhatItCannotModel) {
  const std::string fictitious = ", surface_correction: fictitious";
  test::expect_input_error([&] { parse_config(fictitious_scene("", kClamp), "a.yaml"); }, "a.yaml",
                           "constraints[0].clamp: a clamped face needs bodies' "
                           "material.surface_correction: fictitious");
  test::expect_input_error(
      [&] {
        parse_config(fictitious_scene(fictitious + ", fracture: {critical_stretch: 0.01}", ""),
                     "a.yaml");
      },
      "a.yaml", "bodies[0].material.fracture: surface_correction: fictitious has no fracture");
  test::expect_input_error(
      [&] {
        parse_config(fictitious_scene(fictitious + ", plasticity: {yield: 1.0}", ""), "a.yaml");
      },
      "a.yaml", "bodies[0].material.plasticity: surface_correction: fictitious has no plasticity");
  test::expect_input_error(
      [&] {
        parse_config(fictitious_scene(fictitious,
                                      "initial_cracks:\n  - {plane: {point: [0.1, 0, "
                                      "0], normal: [1, 0, 0]}}\n"),
                     "a.yaml");
      },
      "a.yaml", "initial_cracks: surface_correction: fictitious has no fracture");
  test::expect_input_error(
      [&] {
        parse_config(fictitious_scene(fictitious,
                                      "constraints:\n  - {clamp: {point: [0, 0, 0], normal: "
                                      "[0, 0, 0]}}\n"),
                     "a.yaml");
      },
      "a.yaml", "constraints[0].clamp.normal: must not be zero");
  for (const char* clamp : {"{point: [0.12, 0, 0], normal: [-1, 0, 0]}",   // through the middle
                            "{point: [0, 0, 0], normal: [1, 0, 0]}",       // pointing inward
                            "{point: [-1, 0, 0], normal: [-1, 0, 0]}"}) {  // off the body
    const Scene clamped = build_scene(parse_config(
        fictitious_scene(fictitious, fmt::format("constraints:\n  - {{clamp: {}}}\n", clamp)),
        "a.yaml"));
    const auto e = test::input_error([&] { make_model(clamped); });
    ASSERT_TRUE(e.has_value()) << clamp;
    EXPECT_EQ(e->key(), "constraints[0].clamp") << e->what();
  }
  const Scene scene = build_scene(parse_config(
      fictitious_scene(fictitious, "integrator: {type: petsc_newton, preconditioner: gamg}\n"),
      "a.yaml"));
  auto model = make_model(scene);
  Dynamics dynamics(scene, *model);
  auto integrator = make_integrator(scene.config.integrator, "a.yaml");
  test::expect_input_error([&] { integrator->check(dynamics); }, "a.yaml",
                           "integrator.preconditioner: this model factors its tangent only");
}

}  // namespace
}  // namespace fissure
