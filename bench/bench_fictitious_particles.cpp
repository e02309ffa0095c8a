// An exploration: can fictitious particles outside the free faces remove the bending
// error that neither surface correction removes? For the cantilever of tests/support/beam.hpp
// (1.0 × 0.1 × 0.1 m, clamped behind x = 0) sampled with 2, 3 and 4 tets through its thickness,
// from the linearised LPS energy (fictitious/linear_lps_stiffness.hpp), assembled densely:
//   dilatation: the default model;
//   full:       the deviatoric calibration (docs/model.md, deviation 8);
//   fictitious: full, each family near a free face completed by mirror images of the particles
//               across it (model/fictitious_particles.hpp), each moved as the quadratic
//               displacement fitted around its nearest real particle; the calibrations then run
//               over the completed families;
//   second:     fictitious with the second-order rows (model/second_order_row.hpp), each
//               particle's tet its cell.
// Prints per resolution and variant: the static tip deflection under gravity over Timoshenko's
// (as test_cantilever_convergence.cpp), the first bending frequency over Timoshenko's (as
// test_cantilever_frequency.cpp; inverse iteration), and the highest frequency √λmax(M⁻¹K)
// (power iteration, a lower bound), which the explicit stable step is inversely proportional to.
// Dense: about 7 GB and 10 minutes at 4 tets through the thickness.
// `lattice` instead of `mirror` fills the same shell with a cubic lattice (lattice_images);
// `clamped` runs fictitious and second on the beam alone (x ≥ 0, no held block), its clamp face
// mirrored too, those images moved by clamp_stencils.
//   bench_fictitious_particles [tets through the thickness, e.g. 2,3,4] [fit radius / δ]
//                              [mirror|lattice|clamped|bending|equilibrium] [α]
// `bending` prints instead the energy of pure bending of a free bar (see bending()),
// `equilibrium` a free bar's compliance in bending and stretch under end loads (see
// equilibrium()). α is the second-order rows' stabilisation (default kSecondOrderStabilization).

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
#include "mesh/tet_geometry.hpp"
#include "model/deviatoric_calibration.hpp"
#include "model/dilatation_calibration.hpp"
#include "model/fictitious_particles.hpp"
#include "model/second_order_row.hpp"
#include "support/beam.hpp"
#include "support/scenes.hpp"

namespace {

using namespace fissure;
using test::Cantilever;

// second: fictitious with the second-order correction (linear_lps_stiffness.hpp)
enum class Variant { dilatation, full, fictitious, second };
// How the fictitious variant completes the families: mirror images beyond the free faces, a
// lattice there, or mirror images beyond every face, the clamp face's clamped (clamp_stencils)
// instead of a held block behind it.
enum class Images { mirror, lattice, clamped };
const char* name(Variant v) {
  return v == Variant::dilatation ? "dilatation"
         : v == Variant::full     ? "full"
         : v == Variant::second   ? "second"
                                  : "fictitious";
}

struct Figures {
  int particles = 0, images = 0;
  double static_ratio = 0, beyond_clamp_ratio = 0, frequency_ratio = 0, highest_frequency = 0;
  double largest_l1 = 0, mean_l1 = 0;
};

// M_i, the second moment of particle i's tet about its barycentre (mesh/tet_geometry.hpp); the
// scene must keep its tet mesh.
std::vector<std::array<double, 6>> cell_moments(const Scene& scene) {
  std::vector<std::array<double, 6>> moments(scene.particles.count());
  for (const BodyTetMesh& body : scene.tet_meshes)
    for (int t = 0; t < body.mesh.tet_count(); ++t)
      if (body.particle[t] >= 0) moments[body.particle[t]] = tet_second_moment(body.mesh, t);
  return moments;
}

// A scene's particles with the variant's fictitious particles (beyond the box's free faces) and
// weights over the families they complete.
struct Discretisation {
  FictitiousParticles images;
  Particles particles;  // real, then fictitious
  Families families;
  std::vector<float> c, w;
  std::vector<double> m;
};

Discretisation discretise(const Scene& scene, Variant variant, const bench::BoxFaces& box,
                          double fit_radius, Images kind) {
  const Particles& real = scene.particles;
  const double delta = scene.horizon_of_body[0];
  Discretisation d;
  if (variant == Variant::fictitious || variant == Variant::second) {
    if (kind == Images::lattice)
      d.images = bench::lattice_images(real, box, delta);
    else
      add_mirror_images(real, 0, bench::free_face_triangles(box), delta, d.images);
    fit_stencils(real, scene.horizon_of_body, fit_radius, d.images);
    if (kind == Images::clamped)
      clamp_stencils(real, scene.horizon_of_body, fit_radius, {{0, 0, 0}, {-1, 0, 0}}, d.images);
  }
  d.particles = with_images(real, d.images);
  d.families =
      d.images.count() ? build_families(d.particles, scene.horizon_of_body) : scene.families;
  FamilyWeights weights = isotropic_family_weights(d.particles, d.families, scene.horizon_of_body);
  d.c = std::move(weights.dilatation);
  d.m = std::move(weights.weighted_volume);
  d.w = variant == Variant::dilatation
            ? weights.omega
            : deviatoric_weights(d.particles, d.families, weights.omega,
                                 std::vector<double>(d.particles.count(), Cantilever::shear), d.m,
                                 {isotropic_deviatoric_shape()})
                  .weights;
  return d;
}

// The linearised energy of a discretisation over its first `real` particles, with the
// second-order rows (their cells' moments and stabilisation α) for `second` only.
bench::LinearLps linear_lps(const Discretisation& d, int real, Variant v,
                            const std::vector<std::array<double, 6>>& moments,
                            double stabilization) {
  const bool second = v == Variant::second;
  return {d.particles,
          d.families,
          real,
          d.c,
          d.w,
          d.m,
          Cantilever::bulk,
          Cantilever::shear,
          second ? &moments : nullptr,
          second ? stabilization : 0.0};
}

Figures run(int tets, Variant variant, double fit_radius, Images kind, double stabilization) {
  const double resolution = Cantilever::side / tets, gravity = 9.81;
  // clamped: the beam alone, x ≥ 0, its clamp face x = 0 a face with images behind it
  const bool clamped = kind == Images::clamped;
  const Scene scene =
      clamped ? test::block_scene({.size = {Cantilever::length, Cantilever::side, Cantilever::side},
                                   .resolution = resolution,
                                   .bulk = Cantilever::bulk,
                                   .shear = Cantilever::shear,
                                   .scene = "output: {surface: true}\n"})
              : test::cantilever_scene(resolution, gravity, "", "output: {surface: true}\n");
  const Particles& real = scene.particles;
  const int n = real.count();
  Figures f;
  f.particles = n;
  const bench::BoxFaces box{{clamped ? 0.0 : -1.45 * resolution, 0, 0},
                            {Cantilever::length, Cantilever::side, Cantilever::side},
                            {{1, 0}, {1, 1}, {2, 0}, {2, 1}, {0, 1}}};
  bench::BoxFaces faces = box;
  if (clamped) faces.free.push_back({0, 0});
  const Discretisation d = discretise(scene, variant, faces, fit_radius, kind);
  const FictitiousParticles& images = d.images;
  if (images.count()) {
    const auto [largest, mean] = stencil_amplification(images);
    f.images = images.count(), f.largest_l1 = largest, f.mean_l1 = mean;
  }
  std::vector<int> dof(n, -1);
  int free = 0;
  for (int i = 0; i < n; ++i)
    if (real.reference[3 * i] >= 0) dof[i] = free++;
  const auto moments =
      variant == Variant::second ? cell_moments(scene) : std::vector<std::array<double, 6>>{};
  const bench::LinearLps lps = linear_lps(d, n, variant, moments, stabilization);
  Eigen::MatrixXd K =
      bench::linear_lps_stiffness(lps, images.count() ? &images : nullptr, dof, 3 * free);
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

  double sum_x = 0, sum_w = 0;
  int tip = 0;
  for (int i : test::tip_particles(real, resolution))
    sum_x += real.reference[3 * i], sum_w -= u(3 * dof[i] + 2), ++tip;
  f.static_ratio = sum_w / tip / test::timoshenko_deflection(gravity, sum_x / tip);
  std::vector<double> xs, ws;
  for (int i = 0; i < n; ++i)
    if (dof[i] >= 0) xs.push_back(real.reference[3 * i]), ws.push_back(-u(3 * dof[i] + 2));
  f.beyond_clamp_ratio = test::deflection_over_theory_beyond_clamp(
      xs, ws, [gravity](double s) { return test::timoshenko_deflection(gravity, s); }, 0.25, 0.9);

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
  f.frequency_ratio = std::sqrt(omega2) / test::timoshenko_first_frequency();
  return f;
}

// A free bar `length` × 0.1 × 0.1 m sampled with `tets` tets through its thickness, every
// face free, with its cells' moments.
struct FreeBar {
  Scene scene;
  std::vector<std::array<double, 6>> moments;
  bench::BoxFaces box;
};
FreeBar free_bar(double length, int tets) {
  const double side = Cantilever::side;
  FreeBar bar{test::block_scene({.size = {length, side, side},
                                 .resolution = side / tets,
                                 .bulk = Cantilever::bulk,
                                 .shear = Cantilever::shear,
                                 .scene = "output: {surface: true}\n"}),
              {},
              {{0, 0, 0}, {length, side, side}, {{0, 0}, {0, 1}, {1, 0}, {1, 1}, {2, 0}, {2, 1}}}};
  bar.moments = cell_moments(bar.scene);
  return bar;
}

// Pure bending of a free 0.4 × 0.1 × 0.1 m bar (every face free), by Saint-Venant's solution
// u_x = κxz, u_y = −νκyz, u_z = −κ(x² + ν(z² − y²))/2 about its centre: the energy the model
// stores over ½EIκ² per length, the bending stiffness without clamp, load or tip, and the
// particles' own quadrature Σ V_i ½Eκ²z_i² over the same.
void bending(const std::vector<int>& tets, double fit_radius, double stabilization) {
  const double length = 0.4, side = Cantilever::side, curvature = 1e-3;
  const double E = test::youngs_modulus(Cantilever::bulk, Cantilever::shear);
  const double nu = test::poisson_ratio(Cantilever::bulk, Cantilever::shear);
  const double continuum = 0.5 * E * std::pow(side, 4) / 12 * curvature * curvature * length;
  fmt::print(
      "tets  lambda_m  variant     particles  images  energy/continuum  quadrature/continuum\n");
  for (int t : tets) {
    const auto [scene, moments, box] = free_bar(length, t);
    double quadrature = 0;
    for (int i = 0; i < scene.particles.count(); ++i)
      quadrature += scene.particles.volume[i] * 0.5 * E * curvature * curvature *
                    std::pow(scene.particles.reference[3 * i + 2] - 0.5 * side, 2);
    for (Variant v : {Variant::dilatation, Variant::full, Variant::fictitious, Variant::second}) {
      const Discretisation d = discretise(scene, v, box, fit_radius, Images::mirror);
      std::vector<double> u(d.particles.reference.size());
      for (int i = 0; i < d.particles.count(); ++i) {
        const double x = d.particles.reference[3 * i] - 0.5 * length;
        const double y = d.particles.reference[3 * i + 1] - 0.5 * side;
        const double z = d.particles.reference[3 * i + 2] - 0.5 * side;
        u[3 * i] = curvature * x * z;
        u[3 * i + 1] = -nu * curvature * y * z;
        u[3 * i + 2] = -0.5 * curvature * (x * x + nu * (z * z - y * y));
      }
      const bench::LinearLps lps =
          linear_lps(d, scene.particles.count(), v, moments, stabilization);
      fmt::print("{:4d}  {:8.5f}  {:10s}  {:9d}  {:6d}  {:16.4f}  {:20.4f}\n", t, side / t, name(v),
                 scene.particles.count(), d.images.count(),
                 bench::linear_lps_energy(lps, u) / continuum, quadrature / continuum);
      std::fflush(stdout);
    }
  }
}

// A free 1.0 × 0.1 × 0.1 m bar (every face free) loaded over its end zones x < 0.1 m and
// x > 0.9 m by axial forces proportional to z V_i (a moment M on each end) or to V_i (a force
// N): the compliance of its middle, 0.3 ≤ x ≤ 0.7 m, where by Saint-Venant the continuum is in
// pure bending or uniaxial stress, over the continuum's, from the fit u_x ≈ a + b x + c z + k xz:
// k/(M/EI) and b/(N/EA). Every variant with images stores the continuum's energy of both fields
// (`bending` above; the calibrations), but its particles may relax away from them under load,
// which these figures measure. Dense, with the rigid motions penalised: seconds at 2 tets, a
// minute at 3, about 3 GB and a few minutes per variant at 4.
void equilibrium(const std::vector<int>& tets, double fit_radius, double stabilization) {
  const double length = 1.0, side = Cantilever::side, zone = 0.1;
  const double E = test::youngs_modulus(Cantilever::bulk, Cantilever::shear);
  fmt::print(
      "tets  lambda_m  variant     particles  images  bending_compliance/continuum  "
      "stretch_compliance/continuum\n");
  for (int t : tets) {
    const auto [scene, moments, box] = free_bar(length, t);
    const int n = scene.particles.count();
    const auto& x = scene.particles.reference;
    std::vector<int> dof(n);
    for (int i = 0; i < n; ++i) dof[i] = i;
    // the six rigid motions about the centre, each a column
    Eigen::MatrixXd rigid = Eigen::MatrixXd::Zero(3 * n, 6);
    for (int i = 0; i < n; ++i) {
      const double px = x[3 * i] - 0.5 * length, py = x[3 * i + 1] - 0.5 * side,
                   pz = x[3 * i + 2] - 0.5 * side;
      for (int a = 0; a < 3; ++a) rigid(3 * i + a, a) = 1;
      rigid(3 * i + 1, 3) = -pz, rigid(3 * i + 2, 3) = py;
      rigid(3 * i, 4) = pz, rigid(3 * i + 2, 4) = -px;
      rigid(3 * i, 5) = -py, rigid(3 * i + 1, 5) = px;
    }
    for (Variant v : {Variant::dilatation, Variant::full, Variant::fictitious, Variant::second}) {
      const Discretisation d = discretise(scene, v, box, fit_radius, Images::mirror);
      const bench::LinearLps lps = linear_lps(d, n, v, moments, stabilization);
      Eigen::MatrixXd K =
          bench::linear_lps_stiffness(lps, d.images.count() ? &d.images : nullptr, dof, 3 * n);
      // the loads below do no work on a rigid motion, so penalising those changes nothing else
      K += 1e-3 * K.diagonal().mean() * rigid * rigid.transpose();
      const Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>> llt(K);
      if (llt.info() != Eigen::Success)
        throw std::runtime_error(fmt::format("{}: the stiffness is singular", name(v)));
      double compliance[2];
      for (int mode = 0; mode < 2; ++mode) {
        // mode 0: f_x ∝ ±z V_i, a moment M = EI κ per end; mode 1: f_x ∝ ±V_i, N = EA ε
        const double strain = 1e-3, I = std::pow(side, 4) / 12, A = side * side;
        Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * n);
        double resultant = 0;  // Σ over both ends of shape² V: twice one end's moment or force
        for (int i = 0; i < n; ++i) {
          if (x[3 * i] > zone && x[3 * i] < length - zone) continue;
          const double shape = mode == 0 ? x[3 * i + 2] - 0.5 * side : 1.0;
          f(3 * i) = (x[3 * i] < zone ? -1 : 1) * shape * scene.particles.volume[i];
          resultant += shape * shape * scene.particles.volume[i];
        }
        f *= 2 * (mode == 0 ? E * I * strain : E * A * strain) / resultant;
        const Eigen::VectorXd u = llt.solve(f);
        Eigen::Matrix4d normal = Eigen::Matrix4d::Zero();
        Eigen::Vector4d right = Eigen::Vector4d::Zero();
        for (int i = 0; i < n; ++i) {
          const double px = x[3 * i] - 0.5 * length, pz = x[3 * i + 2] - 0.5 * side;
          if (std::abs(px) > 0.2 * length) continue;
          const Eigen::Vector4d basis(1, px, pz, px * pz);
          normal += basis * basis.transpose(), right += basis * u(3 * i);
        }
        const Eigen::Vector4d c = normal.ldlt().solve(right);
        compliance[mode] = (mode == 0 ? c(3) : c(1)) / strain;
      }
      fmt::print("{:4d}  {:8.5f}  {:10s}  {:9d}  {:6d}  {:28.4f}  {:28.4f}\n", t, side / t, name(v),
                 n, d.images.count(), compliance[0], compliance[1]);
      std::fflush(stdout);
    }
  }
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
  const double stabilization = argc > 4 ? std::atof(argv[4]) : kSecondOrderStabilization;
  if (tets.empty() || fit_radius <= 0 || !(stabilization >= 0) ||
      (images != "mirror" && images != "lattice" && images != "clamped" && images != "bending" &&
       images != "equilibrium")) {
    fmt::print(stderr,
               "usage: bench_fictitious_particles [2,3,4] [fit radius / horizon > 0] "
               "[mirror|lattice|clamped|bending|equilibrium] [stabilisation α ≥ 0]\n");
    return 2;
  }
  if (images == "bending") {
    bending(tets, fit_radius, stabilization);
    return 0;
  }
  if (images == "equilibrium") {
    equilibrium(tets, fit_radius, stabilization);
    return 0;
  }
  const Images kind = images == "lattice"   ? Images::lattice
                      : images == "clamped" ? Images::clamped
                                            : Images::mirror;
  fmt::print(
      "tets  lambda_m  variant     particles  images  static/timoshenko  beyond_clamp/timoshenko  "
      "frequency/timoshenko  highest_frequency_over_full  stencil_l1_mean  stencil_l1_max  "
      "seconds\n");
  for (int t : tets) {
    double full_highest = 0;
    for (Variant v : {Variant::dilatation, Variant::full, Variant::fictitious, Variant::second}) {
      // without a held block only the images hold the beam; the second order needs its cells
      if (kind == Images::clamped && v != Variant::fictitious && v != Variant::second) continue;
      const auto start = std::chrono::steady_clock::now();
      const Figures f = run(t, v, fit_radius, kind, stabilization);
      if (v == Variant::full) full_highest = f.highest_frequency;
      fmt::print(
          "{:4d}  {:8.5f}  {:10s}  {:9d}  {:6d}  {:17.4f}  {:23.4f}  {:20.4f}  {:27.3f}  {:15.2f}  "
          "{:14.2f}  "
          "{:7.1f}\n",
          t, Cantilever::side / t, name(v), f.particles, f.images, f.static_ratio,
          f.beyond_clamp_ratio, f.frequency_ratio,
          full_highest > 0 ? f.highest_frequency / full_highest : NAN, f.mean_l1, f.largest_l1,
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      std::fflush(stdout);
    }
  }
}
