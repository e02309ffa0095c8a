#pragma once
// Beam tests (tests/integrators/test_cantilever.cpp, tests/verification/): isotropic elastic
// constants from κ and μ, and a clamped cantilever at a chosen resolution.
#include <cmath>
#include <string>
#include <vector>

#include "support/scenes.hpp"

namespace fissure::test {

// Young's modulus E = 9κμ / (3κ + μ) and Poisson's ratio ν = (3κ − 2μ) / (2(3κ + μ)).
inline double youngs_modulus(double bulk, double shear) {
  return 9 * bulk * shear / (3 * bulk + shear);
}
inline double poisson_ratio(double bulk, double shear) {
  return (3 * bulk - 2 * shear) / (2 * (3 * bulk + shear));
}
// Cowper's (1966) shear coefficient of a rectangular section, k_s = 10(1 + ν) / (12 + 11ν).
inline double shear_coefficient(double nu) { return 10 * (1 + nu) / (12 + 11 * nu); }

// A 1.0 × 0.1 × 0.1 m beam along x, κ = 500 MPa, μ = 300 MPa (E = 750 MPa, ν = 0.25),
// ρ = 1000 kg/m³, clamped by holding the particles in x < 0: a block one horizon (1.45 λ) long
// behind the clamp face x = 0.
struct Cantilever {
  static constexpr double length = 1.0, side = 0.1, density = 1000;
  static constexpr double bulk = 5.0e8, shear = 3.0e8;
};

// `material` is appended to the material map, e.g. ", surface_correction: full", and `extra` to
// the scene, e.g. "output: {surface: true}\n".
inline Scene cantilever_scene(double resolution, double gravity, const std::string& material = "",
                              const std::string& extra = "") {
  using C = Cantilever;
  const double anchor = 1.45 * resolution;
  const std::string yaml = fmt::format(
      "time: {{end: 1.0}}\ngravity: [0, 0, {}]\nbodies:\n"
      "  - geometry: {{box: {{min: [{}, 0, 0], max: [{}, {}, {}]}}}}\n"
      "    resolution: {}\n    material: {{density: {}, bulk_modulus: {}, shear_modulus: {}{}}}\n"
      "constraints:\n  - {{region: {{box: {{min: [-1, -1, -1], max: [0, 1, 1]}}}}, fix: true}}\n{}",
      -gravity, -anchor, C::length, C::side, C::side, resolution, C::density, C::bulk, C::shear,
      material, extra);
  return build_scene(parse_config(yaml, "cantilever.yaml"));
}

// The same beam without the held block, x ≥ 0, with surface_correction: fictitious and its face
// x = 0 clamped (constraints: {clamp: ...}): the second-order model's images continue the field
// through the clamped face (docs/model.md, deviation 8).
inline Scene clamped_face_cantilever_scene(double resolution, double gravity,
                                           const std::string& extra = "") {
  using C = Cantilever;
  const std::string yaml = fmt::format(
      "time: {{end: 1.0}}\ngravity: [0, 0, {}]\nbodies:\n"
      "  - geometry: {{box: {{min: [0, 0, 0], max: [{}, {}, {}]}}}}\n"
      "    resolution: {}\n    material: {{density: {}, bulk_modulus: {}, shear_modulus: {}, "
      "surface_correction: fictitious}}\n"
      "constraints:\n  - {{clamp: {{point: [0, 0, 0], normal: [-1, 0, 0]}}}}\n{}",
      -gravity, C::length, C::side, C::side, resolution, C::density, C::bulk, C::shear, extra);
  return build_scene(parse_config(yaml, "clamped_face_cantilever.yaml"));
}

// The particles within one resolution of the free end x = L.
inline std::vector<int> tip_particles(const Particles& p, double resolution) {
  std::vector<int> tip;
  for (int i = 0; i < p.count(); ++i)
    if (p.reference[3 * i] >= Cantilever::length - resolution) tip.push_back(i);
  return tip;
}

// Where the tip of a deflected cantilever is: the mean reference x of the tip particles and
// their mean downward displacement w at `position`.
struct TipDeflection {
  double x, w;
};
inline TipDeflection tip_deflection(const Particles& p, const std::vector<double>& position,
                                    double resolution) {
  const auto tip = tip_particles(p, resolution);
  double sum_x = 0, sum_w = 0;
  for (int i : tip) {
    sum_x += p.reference[3 * i];
    sum_w -= position[3 * i + 2] - p.reference[3 * i + 2];
  }
  return {sum_x / tip.size(), sum_w / tip.size()};
}

// Euler–Bernoulli deflection at x of the cantilever under its own weight q per length:
// q x² (6L² − 4Lx + x²) / (24 E I).
inline double euler_bernoulli_deflection(double q, double E, double x) {
  const double L = Cantilever::length, I = std::pow(Cantilever::side, 4) / 12;
  return q * x * x * (6 * L * L - 4 * L * x + x * x) / (24 * E * I);
}

// Euler–Bernoulli plus Timoshenko's shear deflection at x of the cantilever under its own weight
// in `gravity`: q x²(6L² − 4Lx + x²)/(24 EI) + q (Lx − x²/2)/(k_s μ A), q = ρ g A, k_s Cowper's.
inline double timoshenko_deflection(double gravity, double x) {
  using C = Cantilever;
  const double A = C::side * C::side, q = C::density * gravity * A;
  const double ks = shear_coefficient(poisson_ratio(C::bulk, C::shear));
  return euler_bernoulli_deflection(q, youngs_modulus(C::bulk, C::shear), x) +
         q * (C::length * x - 0.5 * x * x) / (ks * C::shear * A);
}

// The cantilever's first bending frequency [rad/s]: Euler–Bernoulli, ω1 = (β1L)² √(EI/(ρAL⁴))
// with β1L = 1.8751, and Timoshenko's to first order in (β1 r)², r² = I/A (rotary inertia and
// shear, Timoshenko 1921): ω1 [1 − ½ (β1 r)² (1 + E/(k_s μ))].
constexpr double kFirstModeBetaL = 1.8751040687;
inline double euler_bernoulli_first_frequency() {
  using C = Cantilever;
  const double A = C::side * C::side, I = std::pow(C::side, 4) / 12;
  return kFirstModeBetaL * kFirstModeBetaL *
         std::sqrt(youngs_modulus(C::bulk, C::shear) * I /
                   (C::density * A * std::pow(C::length, 4)));
}
inline double timoshenko_first_frequency() {
  using C = Cantilever;
  const double beta_r_squared =
      kFirstModeBetaL * kFirstModeBetaL / (C::length * C::length) * std::pow(C::side, 2) / 12;
  const double ks = shear_coefficient(poisson_ratio(C::bulk, C::shear));
  return euler_bernoulli_first_frequency() *
         (1 - 0.5 * beta_r_squared * (1 + youngs_modulus(C::bulk, C::shear) / (ks * C::shear)));
}

// The factor c of the least-squares fit w ≈ a + b x + c theory(x) to the samples (x, w) with x
// in [from, to]: the deflection over the theory's once a rigid offset and rotation, which a
// compliant clamp adds, are taken out.
template <class Theory>
double deflection_over_theory_beyond_clamp(const std::vector<double>& x,
                                           const std::vector<double>& w, Theory theory, double from,
                                           double to) {
  double A[3][4] = {};  // normal equations [NᵀN | Nᵀw], N = (1, x, theory(x))
  for (std::size_t k = 0; k < x.size(); ++k) {
    if (x[k] < from || x[k] > to) continue;
    const double n[3] = {1.0, x[k], theory(x[k])};
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) A[r][c] += n[r] * n[c];
      A[r][3] += n[r] * w[k];
    }
  }
  for (int p = 0; p < 3; ++p)  // Gaussian elimination; NᵀN is positive definite
    for (int r = p + 1; r < 3; ++r) {
      const double f = A[r][p] / A[p][p];
      for (int c = p; c < 4; ++c) A[r][c] -= f * A[p][c];
    }
  double coefficient[3];
  for (int r = 2; r >= 0; --r) {
    double sum = A[r][3];
    for (int c = r + 1; c < 3; ++c) sum -= A[r][c] * coefficient[c];
    coefficient[r] = sum / A[r][r];
  }
  return coefficient[2];
}

}  // namespace fissure::test
