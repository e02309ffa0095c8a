// The constants of petsc_newton's schemes, each pinned against an independent statement of it:
// the Butcher tableaux against the order conditions, the stability function and the embedded
// weights' order; Newmark's β, γ, generalized-α's map from ρ∞ and the damping term of every
// scheme against the schemes' defining recurrences written here from the literature, on a scalar
// damped oscillator ÿ + c ẏ + ω² y = 0 (m = 1). There ImplicitScheme's potential is
// A/2 (z − ỹ)² + ω²/2 z², minimised in closed form by z = A ỹ / (A + ω²), so no solver blurs the
// comparison: what is left is round-off.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>

#include "integrators/implicit_scheme.hpp"
#include "integrators/sdirk_tableau.hpp"

namespace fissure {
namespace {

using Scheme = PetscNewtonSettings::Scheme;

// ---- Butcher tableaux --------------------------------------------------------------------------

struct Tableau {
  Eigen::MatrixXd a;
  Eigen::VectorXd b, b_embedded, c;
};

Tableau matrices(const SdirkTableau& t) {
  Tableau m{Eigen::MatrixXd(t.stages, t.stages), Eigen::VectorXd(t.stages),
            Eigen::VectorXd::Zero(t.stages), Eigen::VectorXd(t.stages)};
  for (int i = 0; i < t.stages; ++i)
    for (int j = 0; j < t.stages; ++j) m.a(i, j) = t.a[i * t.stages + j];
  for (int i = 0; i < t.stages; ++i) m.b(i) = t.b[i];
  for (std::size_t i = 0; i < t.b_embedded.size(); ++i) m.b_embedded(i) = t.b_embedded[i];
  m.c = m.a.rowwise().sum();
  return m;
}

// The rooted-tree order conditions up to order 4 (Hairer, Nørsett & Wanner, Solving ODEs I,
// Table II.2.2): Σ b Φ(tree) = 1/γ(tree). Returns the largest residual among those of order ≤ p.
double order_residual(const Eigen::VectorXd& b, const Tableau& t, int p) {
  const Eigen::VectorXd one = Eigen::VectorXd::Ones(b.size());
  const Eigen::VectorXd c = t.c, c2 = c.cwiseProduct(c), ac = t.a * c;
  struct Condition {
    int order;
    double value, expected;
  };
  const Condition conditions[] = {
      {1, b.dot(one), 1.0},
      {2, b.dot(c), 1.0 / 2},
      {3, b.dot(c2), 1.0 / 3},
      {3, b.dot(ac), 1.0 / 6},
      {4, b.dot(c2.cwiseProduct(c)), 1.0 / 4},
      {4, b.dot(c.cwiseProduct(ac)), 1.0 / 8},
      {4, b.dot(t.a * c2), 1.0 / 12},
      {4, b.dot(t.a * ac), 1.0 / 24},
  };
  double worst = 0;
  for (const Condition& k : conditions)
    if (k.order <= p) worst = std::max(worst, std::abs(k.value - k.expected));
  return worst;
}

// The stability function R(z) = 1 + z bᵀ (I − zA)⁻¹ 1 of y' = λy, z = hλ.
std::complex<double> stability(const Tableau& t, std::complex<double> z) {
  const long s = t.b.size();
  const Eigen::MatrixXcd m =
      Eigen::MatrixXcd::Identity(s, s) - z * t.a.cast<std::complex<double>>();
  const Eigen::VectorXcd k = m.partialPivLu().solve(Eigen::VectorXcd::Ones(s));
  return 1.0 + z * t.b.cast<std::complex<double>>().dot(k);
}

const SdirkTableau* tableaux[] = {&sdirk3_tableau(), &sdirk4_tableau(), &esdirk4_tableau()};

// Every entry is a rational number or γ rounded to a double (relative 1.1e-16); the conditions sum
// at most 5³ products of entries no larger than 8, so round-off stays below 1e-13. An entry 1%
// off moves some condition by at least 1% of its smallest nonzero weight product, above 1e-5.
constexpr double kOrderTolerance = 1e-12;

TEST(SchemeConstants, TableauxMeetTheOrderConditionsOfTheirOrderAndNoHigher) {
  for (const SdirkTableau* s : tableaux) {
    const Tableau t = matrices(*s);
    const double met = order_residual(t.b, t, s->order);
    std::printf("%s: order-%d residual %.1e\n", s->name.c_str(), s->order, met);
    EXPECT_LT(met, kOrderTolerance) << s->name;
    for (int i = 0; i < s->stages; ++i) {
      EXPECT_TRUE(s->explicit_stage(i) ? i == 0 : t.a(i, i) == s->gamma) << s->name << " " << i;
      for (int j = i + 1; j < s->stages; ++j) EXPECT_EQ(t.a(i, j), 0.0) << s->name;
    }
    if (s->stiffly_accurate) {
      EXPECT_EQ((t.b.transpose() - t.a.row(s->stages - 1)).norm(), 0) << s->name;
    }
  }
}

// SDIRK3's γ is the root of γ³ − 3γ² + 3γ/2 − 1/6 in (1/6, 1/2) that makes it L-stable
// (Alexander 1977, Theorem 5); ESDIRK4's stages after the first have stage order 2, A c = c²/2
// (Kennedy & Carpenter 2003).
TEST(SchemeConstants, Sdirk3GammaAndEsdirk4StageOrder) {
  const double g = sdirk3_tableau().gamma;
  EXPECT_LT(std::abs(g * g * g - 3 * g * g + 1.5 * g - 1.0 / 6), 1e-15);
  EXPECT_TRUE(g > 1.0 / 6 && g < 0.5);
  const Tableau t = matrices(esdirk4_tableau());
  const Eigen::VectorXd stage = t.a * t.c - 0.5 * t.c.cwiseProduct(t.c);
  EXPECT_LT(stage.tail(stage.size() - 1).cwiseAbs().maxCoeff(), kOrderTolerance);
}

// L-stability: |R| ≤ 1 on the imaginary axis (A-stability; the maximum principle extends it to
// the left half-plane since R has no pole there, its poles being at 1/γ > 0) and R(−∞) = 0. For
// these stiffly accurate schemes R(z) = O(1/z), so |R(−1e9)| is ~1e-9.
TEST(SchemeConstants, EveryTableauIsLStable) {
  for (const SdirkTableau* s : tableaux) {
    const Tableau t = matrices(*s);
    double largest = 0;
    for (double y = 1e-3; y < 1e4; y *= 1.1)
      largest = std::max(largest, std::abs(stability(t, {0, y})));
    const double at_infinity = std::abs(stability(t, -1e9));
    std::printf("%s: max |R(iy)| %.15f, |R(-1e9)| %.1e\n", s->name.c_str(), largest, at_infinity);
    EXPECT_LE(largest, 1 + 1e-12) << s->name;
    EXPECT_LT(at_infinity, 1e-7) << s->name;
  }
}

// The embedded weights b̂ are of order p − 1 and not p, so h Σ (b − b̂) k is the leading error of
// the lower-order solution: a local error estimate of order p.
TEST(SchemeConstants, EmbeddedWeightsAreOneOrderLower) {
  for (const SdirkTableau* s : tableaux) {
    if (s->b_embedded.empty()) continue;
    const Tableau t = matrices(*s);
    const double met = order_residual(t.b_embedded, t, s->order - 1);
    const double missed = order_residual(t.b_embedded, t, s->order);
    std::printf("%s embedded: order-%d residual %.1e, order-%d %.1e\n", s->name.c_str(),
                s->order - 1, met, s->order, missed);
    EXPECT_LT(met, kOrderTolerance) << s->name;
    EXPECT_GT(missed, 1e-4) << s->name;
  }
}

// ---- The schemes on the scalar oscillator
// ---------------------------------------------------------

struct Motion {
  double y, v, a;
};

struct Oscillator {
  double omega, c;
  double acceleration(double y, double v) const { return -omega * omega * y - c * v; }
};

// One step of ImplicitScheme, each stage's minimiser in closed form.
Motion scheme_step(ImplicitScheme& scheme, const Oscillator& o, Motion m, double h) {
  State state;
  state.position = {m.y};
  state.velocity = {m.v};
  std::vector<double> acceleration = {m.a}, z(1);
  for (int i = 0; i < scheme.stages(); ++i) {
    scheme.predict(state, acceleration, o.c, h, i);
    if (scheme.explicit_stage()) continue;
    const double inertia = scheme.inertia();
    z[0] = inertia * scheme.target()[0] / (inertia + o.omega * o.omega);
    scheme.finish_stage(z, {}, h);
  }
  scheme.correct(z, {}, state, acceleration, h);
  return {state.position[0], state.velocity[0], acceleration[0]};
}

// Generalized-α (Chung & Hulbert, J. Appl. Mech. 60 (1993), Eqs 2-4, 17 and 25), Newmark's
// average acceleration being α_m = α_f = 0, β = ¼, γ = ½: the unknowns (y₁, v₁, a₁) solve
//   (1 − α_m) a₁ + α_m a + c((1 − α_f) v₁ + α_f v) + ω²((1 − α_f) y₁ + α_f y) = 0,
//   y₁ = y + h v + h²((½ − β) a + β a₁),   v₁ = v + h((1 − γ) a + γ a₁).
struct GeneralizedAlpha {
  double alpha_m = 0, alpha_f = 0, beta = 0.25, gamma = 0.5;
  static GeneralizedAlpha from_rho(double r) {
    GeneralizedAlpha g;
    g.alpha_m = (2 * r - 1) / (r + 1);
    g.alpha_f = r / (r + 1);
    g.gamma = 0.5 - g.alpha_m + g.alpha_f;
    g.beta = 0.25 * std::pow(1 - g.alpha_m + g.alpha_f, 2);
    return g;
  }
  Motion step(const Oscillator& o, Motion m, double h) const {
    const double w2 = o.omega * o.omega;
    Eigen::Matrix3d lhs;
    Eigen::Vector3d rhs;
    lhs << w2 * (1 - alpha_f), o.c * (1 - alpha_f), 1 - alpha_m,  //
        1, 0, -beta * h * h,                                      //
        0, 1, -gamma * h;
    rhs << -alpha_m * m.a - o.c * alpha_f * m.v - w2 * alpha_f * m.y,
        m.y + h * m.v + h * h * (0.5 - beta) * m.a, m.v + h * (1 - gamma) * m.a;
    const Eigen::Vector3d x = lhs.partialPivLu().solve(rhs);
    return {x(0), x(1), x(2)};
  }
};

// Backward Euler: v₁ = v + h a₁, y₁ = y + h v₁, a₁ = −ω² y₁ − c v₁.
Motion backward_euler_step(const Oscillator& o, Motion m, double h) {
  Eigen::Matrix3d lhs;
  Eigen::Vector3d rhs;
  lhs << 1, -h, 0,  //
      0, 1, -h,     //
      o.omega * o.omega, o.c, 1;
  rhs << m.y, m.v, 0;
  const Eigen::Vector3d x = lhs.partialPivLu().solve(rhs);
  return {x(0), x(1), x(2)};
}

// A Runge–Kutta step of u' = J u, u = (y, v), J = [[0, 1], [−ω², −c]] from the tableau:
// U_i = u + h Σ_j a_ij J U_j, u₁ = u + h Σ_i b_i J U_i; the acceleration is J u₁'s second entry.
Motion runge_kutta_step(const Tableau& t, const Oscillator& o, Motion m, double h) {
  Eigen::Matrix2d j;
  j << 0, 1, -o.omega * o.omega, -o.c;
  const int n = static_cast<int>(t.b.size());
  Eigen::MatrixXd lhs = Eigen::MatrixXd::Identity(2 * n, 2 * n);
  Eigen::VectorXd rhs(2 * n);
  for (int i = 0; i < n; ++i) {
    rhs.segment<2>(2 * i) << m.y, m.v;
    for (int k = 0; k < n; ++k) lhs.block<2, 2>(2 * i, 2 * k) -= h * t.a(i, k) * j;
  }
  const Eigen::VectorXd stages = lhs.partialPivLu().solve(rhs);
  Eigen::Vector2d u(m.y, m.v);
  for (int i = 0; i < n; ++i) u += h * t.b(i) * j * stages.segment<2>(2 * i);
  return {u(0), u(1), o.acceleration(u(0), u(1))};
}

struct SchemeCase {
  Scheme scheme;
  double rho_infinity;
};

// Twenty steps from y = 1, v = 0 at ωh from well resolved to far past the explicit limit, without
// and with damping c = 0.4 ω; the largest difference from the reference over the steps, in units
// of the initial amplitude. Round-off: every quantity is within a few (ωh)⁰ of the amplitude, so
// 1e-12 holds with a factor 100 to spare; a constant 1% off changes a step by 1e-3 (ωh)² or more.
template <class Reference>
void expect_reference(const SchemeCase& c, Reference reference) {
  for (const double omega_h : {0.3, 3.0, 300.0})
    for (const double damping : {0.0, 0.4}) {
      const double h = 1e-3;
      const Oscillator o{omega_h / h, damping * omega_h / h};
      ImplicitScheme scheme(c.scheme, c.rho_infinity);
      Motion got{1, 0, o.acceleration(1, 0)}, expected = got;
      double worst = 0;
      for (int n = 0; n < 20; ++n) {
        got = scheme_step(scheme, o, got, h);
        expected = reference(o, expected, h);
        worst =
            std::max({worst, std::abs(got.y - expected.y), std::abs(got.v - expected.v) / o.omega});
      }
      EXPECT_LT(worst, 1e-12) << scheme_name(c.scheme) << " rho " << c.rho_infinity << " omega h "
                              << omega_h << " c/omega " << damping;
    }
}

TEST(SchemeConstants, BackwardEulerIsItsRecurrenceWithDamping) {
  expect_reference({Scheme::backward_euler, 0}, backward_euler_step);
}

TEST(SchemeConstants, NewmarkIsAverageAccelerationWithDamping) {
  const GeneralizedAlpha newmark;
  expect_reference({Scheme::newmark, 0},
                   [&](const Oscillator& o, Motion m, double h) { return newmark.step(o, m, h); });
}

TEST(SchemeConstants, GeneralizedAlphaIsChungHulbertWithDamping) {
  for (const double rho : {0.0, 0.5, 0.8, 1.0}) {
    const GeneralizedAlpha alpha = GeneralizedAlpha::from_rho(rho);
    expect_reference({Scheme::alpha, rho},
                     [&](const Oscillator& o, Motion m, double h) { return alpha.step(o, m, h); });
  }
}

TEST(SchemeConstants, EverySdirkSchemeIsItsTableauWithDamping) {
  for (const Scheme s : {Scheme::sdirk3, Scheme::sdirk4, Scheme::esdirk4}) {
    const Tableau t = matrices(*sdirk_tableau(s));
    expect_reference({s, 0}, [&](const Oscillator& o, Motion m, double h) {
      return runge_kutta_step(t, o, m, h);
    });
  }
}

// Generalized-α's defining property (Chung & Hulbert 1993, Eq. 25): the spectral radius of its
// amplification matrix at ωh → ∞ is ρ∞, with no reference to the map's formulas. The matrix
// maps (y, v/ω, a/ω²) over one step, built column by column from ImplicitScheme at ωh = 1e8; its
// eigenvalues meet in a triple root −ρ∞ there, which round-off splits by (1e-16)^⅓ ≈ 5e-6.
TEST(SchemeConstants, GeneralizedAlphaSpectralRadiusAtInfinityIsRhoInfinity) {
  for (const double rho : {0.0, 0.3, 0.5, 0.8, 1.0}) {
    const double h = 1, omega = 1e8;
    const Oscillator o{omega, 0};
    Eigen::Matrix3d amplification;
    for (int k = 0; k < 3; ++k) {
      ImplicitScheme scheme(Scheme::alpha, rho);
      const Motion start{k == 0 ? 1.0 : 0.0, k == 1 ? omega : 0.0, k == 2 ? omega * omega : 0.0};
      const Motion end = scheme_step(scheme, o, start, h);
      amplification.col(k) << end.y, end.v / omega, end.a / (omega * omega);
    }
    const double radius = amplification.eigenvalues().cwiseAbs().maxCoeff();
    std::printf("rho_infinity %.1f: spectral radius at omega h = 1e8: %.6f\n", rho, radius);
    EXPECT_NEAR(radius, rho, 1e-4) << rho;
  }
}

}  // namespace
}  // namespace fissure
