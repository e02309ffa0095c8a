#include "model/deviatoric_calibration.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "model/model.hpp"

namespace fissure {

namespace {

using Vector5 = Eigen::Matrix<double, 5, 1>;
using Matrix5 = Eigen::Matrix<double, 5, 5>;
using Vector15 = Eigen::Matrix<double, 15, 1>;
using Matrix15 = Eigen::Matrix<double, 15, 15>;
using Columns15 = Eigen::Map<Eigen::Matrix<double, 15, Eigen::Dynamic>>;
using Column = Eigen::Map<Eigen::VectorXd>;

// Weight ε of the proximal term ½ε·scale|λ − λ_k|² and the number of proximal passes. Where no
// bounded ρ is exact the term keeps each pass's problem bounded below and λ finite, and the
// passes move ρ towards the least-squares compromise. A feasible row converges by the factor
// ε/(ε + h) per pass, h the smallest curvature of the dual relative to scale (about 1e-3 with
// every bond inside its bounds, less with bounds active): on the 0.2 m tet block at λ = 0.02
// (13,579 rows) 8 passes left 6 feasible rows short of exact, 16 left 1 and 32 none, for 15%
// more time (a row past convergence stops; an infeasible one costs a Newton step or two a pass).
constexpr double kProximalWeight = 1e-5;
constexpr int kProximalPasses = 32;
// Newton steps per pass: with every bond inside its bounds a pass's problem is quadratic and
// one step solves it; each change of the active set takes one or two more.
constexpr int kNewtonSteps = 50;
// The dual gradient Σ w ρ s − t is the error of A_i/(2μ_i): 1e-12 of the row's scale (Σ w = 7.5
// for an intact family) is far below the single-precision rounding of g (2⁻²⁴ = 6e-8) and above
// the round-off of its sum.
constexpr double kGradientTolerance = 1e-12;
// A Gram matrix whose pivot ratio is below this is singular: its 15 conditions are not
// independent (a flat family). Tet families measure ≥ 2e-3 (reciprocal condition number, ≥ 6e-3
// pivot ratio, on the 0.2 m block), so the threshold sits far from both.
constexpr double kSmallestReciprocalCondition = 1e-10;
// Armijo backtracking: sufficient decrease, and the step below which a Newton direction is given
// up (the objective's decrease is then at round-off and λ is as good as it gets).
constexpr double kArmijo = 1e-4;
constexpr double kSmallestStep = 1e-10;

// Row k and column l of entry e of the upper triangle of a 5×5 matrix, row by row.
constexpr int kUpperRow[15] = {0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 3, 3, 4};
constexpr int kUpperColumn[15] = {0, 1, 2, 3, 4, 1, 2, 3, 4, 2, 3, 4, 3, 4, 4};

// a(ξ̂), a_k = ξ̂ᵀD_kξ̂ for the orthonormal deviatoric basis of the header; |a|² = 2/3.
Vector5 deviatoric_coordinates(const double u[3]) {
  const double r2 = std::numbers::sqrt2, r6 = std::sqrt(6.0);
  Vector5 a;
  a << r2 * u[0] * u[1], r2 * u[0] * u[2], r2 * u[1] * u[2], (u[0] * u[0] - u[1] * u[1]) / r2,
      (u[0] * u[0] + u[1] * u[1] - 2 * u[2] * u[2]) / r6;
  return a;
}

Matrix5 from_upper_triangle(const Vector15& upper) {
  Matrix5 m;
  for (int e = 0; e < 15; ++e)
    m(kUpperRow[e], kUpperColumn[e]) = m(kUpperColumn[e], kUpperRow[e]) = upper(e);
  return m;
}

// ρ = Φ'(z) = clip(1 + z, ρ_min, ρ_max), Φ being the dual's term per bond; inside the bounds
// ρ is free to move (the dual's Hessian sees the bond).
double factor(double z) {
  return std::clamp(1.0 + z, kMinimumDeviatoricFactor, kMaximumDeviatoricFactor);
}
bool inside(double z) {
  return 1.0 + z > kMinimumDeviatoricFactor && 1.0 + z < kMaximumDeviatoricFactor;
}

// Φ(z + h) − Φ(z) = ∫_0^h clip(1 + z + s) ds, integrated piece by piece (ρ_min below s = low − z,
// 1 + z + s between, ρ_max above s = high − z) rather than as a difference of Φ, which would
// lose the small changes of the last Newton steps to the round-off of Φ itself.
double primitive_change(double z, double h) {
  const double from = std::min(0.0, h), to = std::max(0.0, h);
  const double low = std::clamp(kMinimumDeviatoricFactor - 1 - z, from, to);
  const double high = std::clamp(kMaximumDeviatoricFactor - 1 - z, from, to);
  const double integral = kMinimumDeviatoricFactor * (low - from) +
                          (high - low) * (1 + z + 0.5 * (low + high)) +
                          kMaximumDeviatoricFactor * (to - high);
  return h >= 0 ? integral : -integral;
}

// U Uᵀ + shift I in the lower triangle (all that LDLT reads; the upper one holds zeros): Σ_j w_j
// s_j s_jᵀ for the columns √w_j s_j of U.
Matrix15 gram_matrix(const Columns15& U, double shift) {
  Matrix15 m = shift * Matrix15::Identity();
  m.selfadjointView<Eigen::Lower>().rankUpdate(U);
  return m;
}

// Per-thread scratch for one row of N bonds: s_j (15 per bond), the weights w_j = ω B_i|ξ|²V_j
// /(2μ_i), z_j = s_jᵀλ, the Newton direction's d_j = s_jᵀΔλ, w_j ρ_j, √w_j s_j on the bonds
// inside their bounds, |ξ|²V_j and ω (ρ ≡ 1).
struct RowScratch {
  std::vector<double> s, w, z, d, weighted, scaled, length_volume;
  std::vector<float> plain;
  std::vector<char> factored;  // 1: inside its bounds in the factorised Newton matrix
  void resize(int bonds) {
    factored.resize(bonds);
    s.resize(15 * bonds);
    scaled.resize(15 * bonds);
    for (auto* v : {&w, &z, &d, &weighted, &length_volume}) v->resize(bonds);
    plain.resize(bonds);
  }
};

// λ_i, the minimiser of the dual of  min ½Σ_j w_j(ρ_j − 1)²  s.t.  Σ_j w_j ρ_j s_j = t,
// ρ_min ≤ ρ_j ≤ ρ_max:  F(λ) = Σ_j w_j Φ(s_jᵀλ) − tᵀλ, convex with ∇F = Σ_j w_j ρ_j s_j − t
// (zero: the constraints hold) and ∇²F = Σ_{ρ_j inside its bounds} w_j s_j s_jᵀ. Semismooth
// Newton with Armijo backtracking on F + ½ε·scale|λ − λ_k|², the proximal point method's k-th
// problem: its minimisers converge to the exact solution where one exists and stay finite
// (a bounded compromise) where F is unbounded below. Leaves z_j = s_jᵀλ in the scratch; false
// if a Newton matrix cannot be factorised.
bool solve_row(int bonds, const Vector15& t, const Matrix15& gram, RowScratch& r) {
  Columns15 S(r.s.data(), 15, bonds), scaled(r.scaled.data(), 15, bonds);
  Column w(r.w.data(), bonds), z(r.z.data(), bonds), d(r.d.data(), bonds),
      weighted(r.weighted.data(), bonds);
  const double scale = w.sum(), proximal = kProximalWeight * scale;
  Vector15 lambda = Vector15::Zero();
  z.setZero();
  // At λ = 0 every ρ is 1, inside its bounds: the Newton matrix is the Gram matrix + ε·scale I.
  Eigen::LDLT<Matrix15> newton(Matrix15(gram + proximal * Matrix15::Identity()));
  if (newton.info() != Eigen::Success) return false;
  std::fill(r.factored.begin(), r.factored.begin() + bonds, 1);
  for (int pass = 0; pass < kProximalPasses; ++pass) {
    const Vector15 anchor = lambda;
    for (int step = 0; step <= kNewtonSteps; ++step) {
      bool same_bonds = true;  // inside their bounds as when the Newton matrix was factorised
      for (int j = 0; j < bonds; ++j) {
        weighted(j) = w(j) * factor(z(j));
        same_bonds = same_bonds && inside(z(j)) == bool(r.factored[j]);
      }
      const Vector15 gradient = S * weighted - t + proximal * (lambda - anchor);
      if (gradient.lpNorm<Eigen::Infinity>() <= kGradientTolerance * scale) {
        if (step == 0) return true;  // at λ = λ_k: F's own gradient vanishes
        break;
      }
      if (step == kNewtonSteps) break;
      if (!same_bonds) {
        for (int j = 0; j < bonds; ++j) {
          r.factored[j] = inside(z(j));
          scaled.col(j) = r.factored[j] ? Vector15(std::sqrt(w(j)) * S.col(j)) : Vector15::Zero();
        }
        newton.compute(gram_matrix(scaled, proximal));
        if (newton.info() != Eigen::Success) return false;
      }
      const Vector15 direction = -newton.solve(gradient);
      d.noalias() = S.transpose() * direction;
      // The change of the objective along the step, term by term.
      const double slope = gradient.dot(direction);
      auto change = [&](double length) {
        double f = 0;
        for (int j = 0; j < bonds; ++j) f += w(j) * primitive_change(z(j), length * d(j));
        return f - length * t.dot(direction) +
               proximal * length *
                   ((lambda - anchor).dot(direction) + 0.5 * length * direction.squaredNorm());
      };
      double length = 1;
      while (change(length) > kArmijo * length * slope) {
        length *= 0.5;
        if (length < kSmallestStep) return true;  // no decrease left to measure
      }
      lambda += length * direction;
      z += length * d;
    }
  }
  return true;
}

// max |eig(L⁻¹ (A/2μ) L⁻ᵀ) − 1| with T/2μ = L Lᵀ: the largest relative error of the deviatoric
// energy ½xᵀAx against ½xᵀTx over all x, from the rounded weights w (A_i = Σ_j g|ξ|²V_j a_j a_jᵀ,
// g = B_i w). Infinite if the eigenvalues cannot be computed.
double row_residual(const float* w, double B, int bonds, double two_mu,
                    const Matrix5& inverse_factor, RowScratch& r) {
  const Columns15 S(r.s.data(), 15, bonds);
  Column weighted(r.weighted.data(), bonds);
  for (int j = 0; j < bonds; ++j) weighted(j) = B * double(w[j]) * r.length_volume[j] / two_mu;
  const Matrix5 A = from_upper_triangle(S * weighted);
  const Eigen::SelfAdjointEigenSolver<Matrix5> eigen(inverse_factor * A *
                                                     inverse_factor.transpose());
  if (eigen.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
  return (eigen.eigenvalues().array() - 1).abs().maxCoeff();
}

}  // namespace

DeviatoricShape isotropic_deviatoric_shape() {
  DeviatoricShape shape{};
  for (int k = 0; k < 5; ++k) shape[6 * k] = 1;
  return shape;
}

// T/2μ = (15/2) ⟨ω̂ a aᵀ⟩ / ⟨ω̂⟩ over the unit sphere with ω̂ = 1/|G ξ̂|: the continuum limit of
// A_i/2μ = (B_i/2μ) Σ_j ω|ξ|²V_j a aᵀ with ω = δ/|Gξ| (Eq 17), B_i = 15μ/m_i, whose radial
// integrals cancel (I₅ for G = I, as ⟨a aᵀ⟩ = 2/15 I₅). Gauss–Legendre in cos θ times the
// trapezoid rule in φ integrates spherical polynomials of degree < 2·64 exactly, so the smooth ω̂
// of an invertible G to round-off.
DeviatoricShape anisotropic_deviatoric_shape(const std::array<double, 9>& G) {
  constexpr int kPolar = 64, kAzimuthal = 128;
  Matrix5 sum = Matrix5::Zero();
  double weight_sum = 0;
  for (int k = 0; k < kPolar; ++k) {
    // the k-th root of the Legendre polynomial P_64 by Newton's method, and its weight
    double z = std::cos(std::numbers::pi * (k + 0.75) / (kPolar + 0.5)), derivative = 0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1, p1 = z;
      for (int l = 2; l <= kPolar; ++l) {
        const double p2 = ((2 * l - 1) * z * p1 - (l - 1) * p0) / l;
        p0 = p1;
        p1 = p2;
      }
      derivative = kPolar * (z * p1 - p0) / (z * z - 1);
      const double step = p1 / derivative;
      z -= step;
      if (std::abs(step) < 1e-15) break;
    }
    const double polar_weight = 2 / ((1 - z * z) * derivative * derivative);
    const double r = std::sqrt(1 - z * z);
    for (int m = 0; m < kAzimuthal; ++m) {
      const double phi = 2 * std::numbers::pi * m / kAzimuthal;
      const double u[3] = {r * std::cos(phi), r * std::sin(phi), z};
      double g[3];
      for (int row = 0; row < 3; ++row)
        g[row] = G[3 * row] * u[0] + G[3 * row + 1] * u[1] + G[3 * row + 2] * u[2];
      const double omega = polar_weight / std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
      const Vector5 a = deviatoric_coordinates(u);
      sum += omega * a * a.transpose();
      weight_sum += omega;
    }
  }
  DeviatoricShape shape;
  for (int k = 0; k < 5; ++k)
    for (int l = 0; l < 5; ++l) shape[5 * k + l] = 7.5 * 0.5 * (sum(k, l) + sum(l, k)) / weight_sum;
  return shape;
}

DeviatoricCalibration deviatoric_weights(const Particles& particles, const Families& families,
                                         const std::vector<float>& omega,
                                         const std::vector<double>& shear_modulus,
                                         const std::vector<double>& weighted_volume,
                                         const std::vector<DeviatoricShape>& shape_of_body) {
  const int n = particles.count();
  const auto& V = particles.volume;
  // Per body: t = the upper triangle of T/2μ, and L⁻¹ for the residual.
  std::vector<Vector15> target(shape_of_body.size());
  std::vector<Matrix5> inverse_factor(shape_of_body.size());
  for (std::size_t k = 0; k < shape_of_body.size(); ++k) {
    const Matrix5 shape =
        Eigen::Map<const Eigen::Matrix<double, 5, 5, Eigen::RowMajor>>(shape_of_body[k].data());
    const Eigen::LLT<Matrix5> cholesky(shape);
    if (shape != shape.transpose() || cholesky.info() != Eigen::Success)
      throw std::invalid_argument("the deviatoric target of body " + std::to_string(k) +
                                  " is not symmetric positive definite");
    for (int e = 0; e < 15; ++e) target[k](e) = shape(kUpperRow[e], kUpperColumn[e]);
    inverse_factor[k] = cholesky.matrixL().solve(Matrix5::Identity());
  }
  for (int i = 0; i < n; ++i)
    if (particles.body[i] < 0 || std::size_t(particles.body[i]) >= shape_of_body.size())
      throw std::invalid_argument("no deviatoric target for body " +
                                  std::to_string(particles.body[i]));

  DeviatoricCalibration result;
  result.weights.resize(families.directed_bonds());
  result.residual.resize(n);
  result.rows.resize(n);
#pragma omp parallel
  {
    RowScratch r;
#pragma omp for schedule(dynamic, 64)
    for (int i = families.first_own_row(); i < families.end_own_row(); ++i) {
      const int begin = families.offsets[i], bonds = families.offsets[i + 1] - begin;
      const int body = particles.body[i];
      // B_i = 15μ_i/m_i, as the model (notes §6)
      const double B = weighted_volume[i] > 0 ? 15.0 * shear_modulus[i] / weighted_volume[i] : 0;
      const double two_mu = 2 * shear_modulus[i];
      r.resize(bonds);
      for (int j = 0; j < bonds; ++j) {
        const int b = begin + j, k = families.neighbors[b];
        const double xi = families.reference_length[b];
        const auto xi_vector = reference_vector(particles, i, k);
        const double u[3] = {xi_vector[0] / xi, xi_vector[1] / xi, xi_vector[2] / xi};
        const Vector5 a = deviatoric_coordinates(u);
        for (int e = 0; e < 15; ++e) r.s[15 * j + e] = a(kUpperColumn[e]) * a(kUpperRow[e]);
        r.length_volume[j] = xi * xi * V[k];
        r.w[j] = double(omega[b]) * B * r.length_volume[j] / two_mu;
        r.plain[j] = omega[b];
      }
      float* w = result.weights.data() + begin;
      const double plain_residual =
          row_residual(r.plain.data(), B, bonds, two_mu, inverse_factor[body], r);
      DeviatoricRow outcome = DeviatoricRow::too_few_bonds;
      double residual = plain_residual;
      if (bonds >= 15 && B > 0) {
        // The Gram matrix Σ_j w_j s_j s_jᵀ, the Newton matrix without bounds: non-singular iff
        // the s_j span R¹⁵, i.e. unbounded ρ can meet any target.
        Columns15 S(r.s.data(), 15, bonds), scaled(r.scaled.data(), 15, bonds);
        scaled = S * Column(r.w.data(), bonds).cwiseSqrt().asDiagonal();
        const Matrix15 gram = gram_matrix(scaled, 0);
        // Pivoted LDLT: its smallest pivot is ≥ the smallest eigenvalue and its largest ≤ the
        // largest, so their ratio is ≥ the reciprocal condition number, and a rank-deficient
        // Gram matrix leaves a pivot at round-off.
        const Eigen::LDLT<Matrix15> pivots(gram);
        outcome = DeviatoricRow::singular;
        if (pivots.info() == Eigen::Success &&
            pivots.vectorD().minCoeff() >=
                kSmallestReciprocalCondition * pivots.vectorD().maxCoeff() &&
            solve_row(bonds, target[body], gram, r)) {
          for (int j = 0; j < bonds; ++j)
            w[j] = static_cast<float>(factor(r.z[j]) * double(omega[begin + j]));  // ρ_ij ω_ij
          residual = row_residual(w, B, bonds, two_mu, inverse_factor[body], r);
          outcome =
              residual <= plain_residual ? DeviatoricRow::calibrated : DeviatoricRow::not_better;
        }
      }
      if (outcome != DeviatoricRow::calibrated) {
        std::copy(r.plain.begin(), r.plain.begin() + bonds, w);
        residual = plain_residual;
      }
      result.residual[i] = residual;
      result.rows[i] = outcome;
    }
  }
  for (int i = families.first_own_row(); i < families.end_own_row(); ++i) {
    result.exact_rows += result.residual[i] <= kExactDeviatoricResidual;
    result.fallback_rows += result.rows[i] != DeviatoricRow::calibrated;
    result.largest_residual = std::max(result.largest_residual, result.residual[i]);
  }
  return result;
}

}  // namespace fissure
