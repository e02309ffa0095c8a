// Issue 15, an exploration: can fictitious particles outside the free faces remove the bending
// error that neither surface correction removes? For the cantilever of tests/support/beam.hpp
// (1.0 × 0.1 × 0.1 m, clamped behind x = 0) sampled with 2, 3 and 4 tets through its thickness,
// from the linearised LPS energy (fictitious/linear_lps_stiffness.hpp), assembled densely:
//   dilatation: the default model;
//   full:       the deviatoric calibration (docs/model.md, deviation 8);
//   fictitious: full, each family near a free face completed by mirror images of the particles
//               across it (model/fictitious_particles.hpp), each moved as the quadratic
//               displacement fitted around its nearest real particle; the calibrations then run
//               over the completed families.
// Prints per resolution and variant: the static tip deflection under gravity over Timoshenko's
// (as test_cantilever_convergence.cpp), the first bending frequency over Timoshenko's (as
// test_cantilever_frequency.cpp; inverse iteration), and the highest frequency √λmax(M⁻¹K)
// (power iteration, a lower bound), which the explicit stable step is inversely proportional to.
// Dense: about 7 GB and 10 minutes at 4 tets through the thickness.
// `lattice` instead of `mirror` fills the same shell with a cubic lattice (lattice_images).
//   bench_fictitious_particles [tets through the thickness, e.g. 2,3,4] [fit radius / δ]
//                              [mirror|lattice]
#include <fmt/format.h>

#include <Eigen/Dense>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "fictitious/lattice_images.hpp"
#include "fictitious/linear_lps_stiffness.hpp"
#include "model/deviatoric_calibration.hpp"
#include "model/dilatation_calibration.hpp"
#include "model/fictitious_particles.hpp"
#include "support/beam.hpp"

namespace {

using namespace fissure;
using test::Cantilever;

enum class Variant { dilatation, full, fictitious };
const char* name(Variant v) {
  return v == Variant::dilatation ? "dilatation" : v == Variant::full ? "full" : "fictitious";
}

struct Figures {
  int particles = 0, images = 0;
  double static_ratio = 0, frequency_ratio = 0, highest_frequency = 0;
  double largest_l1 = 0, mean_l1 = 0;
};

// The real particles followed by the fictitious ones, all in body 0.
Particles extended(const Particles& real, const FictitiousParticles& images) {
  Particles p = real;
  for (int g = 0; g < images.count(); ++g) {
    p.reference.insert(p.reference.end(), &images.position[3 * g], &images.position[3 * g + 3]);
    p.velocity.insert(p.velocity.end(), {0.0, 0.0, 0.0});
    p.volume.push_back(images.volume[g]);
    p.mass.push_back(0);
    p.body.push_back(0);
  }
  return p;
}

Figures run(int tets, Variant variant, double fit_radius, bool lattice) {
  const double resolution = Cantilever::side / tets, gravity = 9.81;
  const Scene scene = test::cantilever_scene(resolution, gravity);
  const Particles& real = scene.particles;
  const int n = real.count();
  const double delta = scene.horizon_of_body[0];
  Figures f;
  f.particles = n;

  FictitiousParticles images;
  if (variant == Variant::fictitious) {
    const bench::BoxFaces box{{-1.45 * resolution, 0, 0},
                              {Cantilever::length, Cantilever::side, Cantilever::side},
                              {{1, 0}, {1, 1}, {2, 0}, {2, 1}, {0, 1}}};
    if (lattice)
      images = bench::lattice_images(real, box, delta);
    else
      add_mirror_images(real, 0, bench::free_face_triangles(box), delta, images);
    fit_stencils(real, scene.horizon_of_body, fit_radius, images);
    const auto [largest, mean] = stencil_amplification(images);
    f.images = images.count(), f.largest_l1 = largest, f.mean_l1 = mean;
  }
  const Particles particles = extended(real, images);
  const Families families =
      images.count() ? build_families(particles, scene.horizon_of_body) : scene.families;
  const auto& off = families.offsets;
  std::vector<float> omega(families.directed_bonds());
  std::vector<double> m(particles.count(), 0.0);
  for (int i = 0; i < particles.count(); ++i)
    for (int b = off[i]; b < off[i + 1]; ++b) {
      const double length = families.reference_length[b];
      omega[b] = static_cast<float>(delta / length);  // Eq 5
      m[i] += double(omega[b]) * length * length * particles.volume[families.neighbors[b]];
    }
  const std::vector<float> c = dilatation_weights(particles, families, omega, m);
  std::vector<float> w = omega;
  if (variant != Variant::dilatation)
    w = deviatoric_weights(particles, families, omega,
                           std::vector<double>(particles.count(), Cantilever::shear), m,
                           {isotropic_deviatoric_shape()})
            .weights;

  std::vector<int> dof(n, -1);
  int free = 0;
  for (int i = 0; i < n; ++i)
    if (real.reference[3 * i] >= 0) dof[i] = free++;
  const bench::LinearLps lps{particles, families, n, c, w, m, Cantilever::bulk, Cantilever::shear};
  Eigen::MatrixXd K = bench::linear_lps_stiffness(
      lps, variant == Variant::fictitious ? &images : nullptr, dof, 3 * free);
  Eigen::VectorXd mass(3 * free), load = Eigen::VectorXd::Zero(3 * free);
  for (int i = 0; i < n; ++i)
    if (dof[i] >= 0) {
      mass.segment<3>(3 * dof[i]).setConstant(Cantilever::density * real.volume[i]);
      load(3 * dof[i] + 2) = -Cantilever::density * gravity * real.volume[i];
    }

  // highest frequency: power iteration on M⁻¹K
  Eigen::VectorXd v = Eigen::VectorXd::Ones(3 * free);
  for (int k = 0; k < 3 * free; ++k) v(k) += std::sin(12.9898 * k);
  double highest = 0;
  for (int it = 0; it < 150; ++it) {
    const Eigen::VectorXd z = (K * v).cwiseQuotient(mass);
    highest = z.norm() / v.norm();
    v = z / z.norm();
  }
  f.highest_frequency = std::sqrt(highest);

  Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>> llt(K);
  if (llt.info() != Eigen::Success)
    throw std::runtime_error(
        fmt::format("{}: the stiffness is not positive definite", name(variant)));
  const Eigen::VectorXd u = llt.solve(load);

  const double E = test::youngs_modulus(Cantilever::bulk, Cantilever::shear);
  const double ks =
      test::shear_coefficient(test::poisson_ratio(Cantilever::bulk, Cantilever::shear));
  const double A = Cantilever::side * Cantilever::side, L = Cantilever::length;
  double sum_x = 0, sum_w = 0;
  int tip = 0;
  for (int i : test::tip_particles(real, resolution))
    sum_x += real.reference[3 * i], sum_w -= u(3 * dof[i] + 2), ++tip;
  const double x = sum_x / tip, q = Cantilever::density * gravity * A;
  const double theory = test::euler_bernoulli_deflection(q, E, x) +
                        q * (L * x - 0.5 * x * x) / (ks * Cantilever::shear * A);
  f.static_ratio = sum_w / tip / theory;

  // first bending frequency: inverse iteration z = K⁻¹Mv, ω² = zᵀMv / zᵀMz
  for (int i = 0; i < n; ++i)
    if (dof[i] >= 0) v.segment<3>(3 * dof[i]) << 0, 0, std::pow(real.reference[3 * i], 2);
  double omega2 = 0;
  for (int it = 0; it < 40; ++it) {
    const Eigen::VectorXd Mv = mass.cwiseProduct(v);
    const Eigen::VectorXd z = llt.solve(Mv);
    omega2 = z.dot(Mv) / z.dot(mass.cwiseProduct(z));
    v = z / z.norm();
  }
  const double I = std::pow(Cantilever::side, 4) / 12, beta = 1.8751040687 / L;
  const double euler_bernoulli = beta * beta * std::sqrt(E * I / (Cantilever::density * A));
  const double timoshenko =
      euler_bernoulli * (1 - 0.5 * beta * beta * I / A * (1 + E / (ks * Cantilever::shear)));
  f.frequency_ratio = std::sqrt(omega2) / timoshenko;
  return f;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> tets = {2, 3, 4};
  if (argc > 1) {
    tets.clear();
    std::stringstream list(argv[1]);
    for (std::string item; std::getline(list, item, ',');) tets.push_back(std::atoi(item.c_str()));
  }
  const double fit_radius = argc > 2 ? std::atof(argv[2]) : 1.5;
  const std::string images = argc > 3 ? argv[3] : "mirror";
  if (tets.empty() || fit_radius <= 0 || (images != "mirror" && images != "lattice")) {
    fmt::print(stderr,
               "usage: bench_fictitious_particles [2,3,4] [fit radius / horizon > 0] "
               "[mirror|lattice]\n");
    return 2;
  }
  fmt::print(
      "tets  lambda_m  variant     particles  images  static/timoshenko  "
      "frequency/timoshenko  highest_frequency_over_full  stencil_l1_mean  stencil_l1_max  "
      "seconds\n");
  for (int t : tets) {
    double full_highest = 0;
    for (Variant v : {Variant::dilatation, Variant::full, Variant::fictitious}) {
      const auto start = std::chrono::steady_clock::now();
      const Figures f = run(t, v, fit_radius, images == "lattice");
      if (v == Variant::full) full_highest = f.highest_frequency;
      fmt::print(
          "{:4d}  {:8.5f}  {:10s}  {:9d}  {:6d}  {:17.4f}  {:20.4f}  {:27.3f}  {:15.2f}  {:14.2f}  "
          "{:7.1f}\n",
          t, Cantilever::side / t, name(v), f.particles, f.images, f.static_ratio,
          f.frequency_ratio, full_highest > 0 ? f.highest_frequency / full_highest : NAN, f.mean_l1,
          f.largest_l1,
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      std::fflush(stdout);
    }
  }
}
