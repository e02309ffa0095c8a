#include "model/second_order_model.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/error.hpp"
#include "mesh/tet_geometry.hpp"
#include "model/deviatoric_calibration.hpp"
#include "model/dilatation_calibration.hpp"
#include "scene/scene.hpp"

namespace fissure {

SecondOrderModel::SecondOrderModel(const Particles& particles, const Families& families,
                                   MaterialPoints materials,
                                   const std::vector<double>& horizon_of_body,
                                   FictitiousParticles images,
                                   std::vector<std::array<double, 6>> cell_moment,
                                   double stabilization)
    : Model(particles, families, std::move(materials)),
      images_(std::move(images)),
      cell_moment_(std::move(cell_moment)),
      stabilization_(stabilization) {
  const int n = particles.count(), count = images_.count();
  if (!(stabilization_ >= 0))
    throw std::invalid_argument(
        fmt::format("the second-order stabilisation must be ≥ 0, not {}", stabilization_));
  if (!materials_.anisotropy.empty())
    throw std::invalid_argument(
        "the second-order model is isotropic only (no material.anisotropy)");
  if (static_cast<int>(cell_moment_.size()) != n)
    throw std::invalid_argument("the second-order model needs a cell moment per particle");
  extended_ = with_images(particles, images_);
  extended_families_ = build_families(extended_, horizon_of_body);
  const int total = extended_.count();
  const auto& off = extended_families_.offsets;
  const auto& member = extended_families_.neighbors;
  const auto& length = extended_families_.reference_length;

  // both calibrations over the completed families; an image's moduli are those of its body,
  // which its stencil's particles share
  const FamilyWeights weights =
      isotropic_family_weights(extended_, extended_families_, horizon_of_body);
  std::vector<double> shear(total);
  for (int i = 0; i < total; ++i)
    shear[i] = materials_.shear_modulus[i < n ? i : images_.particle[images_.offsets[i - n]]];
  const std::vector<DeviatoricShape> shapes(horizon_of_body.size(), isotropic_deviatoric_shape());
  const DeviatoricCalibration calibration = deviatoric_weights(
      extended_, extended_families_, weights.omega, shear, weights.weighted_volume, shapes);

  // the particles' rows: what second_order_row.hpp reads per bond, and the fit over the family
  const int bonds = off[n];
  xi_.resize(3 * bonds);
  dilatation_weight_.resize(bonds);
  deviatoric_weight_.resize(bonds);
  member_volume_.resize(bonds);
  fit_.resize(bonds);
  scale_.resize(n);
  deviatoric_modulus_.resize(n);
  std::vector<std::string> failure(n);
#pragma omp parallel for schedule(dynamic, 32)
  for (int i = 0; i < n; ++i) {
    const double delta = horizon_of_body[particles.body[i]];
    std::vector<Eigen::Vector3d> xi;
    std::vector<double> fit_weight;
    for (int b = off[i]; b < off[i + 1]; ++b) {
      const int j = member[b];
      Eigen::Vector3d v;
      for (int a = 0; a < 3; ++a)
        xi_[3 * b + a] = v[a] = extended_.reference[3 * j + a] - extended_.reference[3 * i + a];
      dilatation_weight_[b] = weights.dilatation[b];
      deviatoric_weight_[b] = calibration.weights[b];
      member_volume_[b] = extended_.volume[j];
      xi.push_back(v), fit_weight.push_back(delta / length[b] * extended_.volume[j]);
    }
    std::vector<QuadraticBasis> a;
    if (!quadratic_fit(xi, fit_weight, delta, a)) {
      failure[i] = fmt::format(
          "the family of particle {} ({} members) does not determine a quadratic displacement", i,
          xi.size());
      continue;
    }
    std::copy(a.begin(), a.end(), fit_.begin() + off[i]);
    scale_[i] = delta;
    deviatoric_modulus_[i] = weights.weighted_volume[i] > 0
                                 ? 15 * materials_.shear_modulus[i] / weights.weighted_volume[i]
                                 : 0;
  }
  for (const std::string& f : failure)
    if (!f.empty()) throw std::invalid_argument("second-order model: " + f);
  for (int i = 0; i < n; ++i) largest_row_ = std::max(largest_row_, off[i + 1] - off[i]);

  int exact = 0;
  double largest_residual = 0;
  for (int i = 0; i < n; ++i) {
    exact += calibration.residual[i] <= kExactDeviatoricResidual;
    largest_residual = std::max(largest_residual, calibration.residual[i]);
  }
  const auto [largest, mean] = stencil_amplification(images_);
  statistics_ = {{"fictitious_particles", count},
                 {"stencil_amplification_mean", mean},
                 {"stencil_amplification_largest", largest},
                 {"deviatoric_exact_rows", exact},
                 {"deviatoric_largest_residual", largest_residual}};
  positions_.resize(3 * total);
  stable_time_step_ = reference_time_step();
}

void SecondOrderModel::extended_positions(const double* y, std::vector<double>& extended) const {
  const int n = particles_.count();
  extended.resize(3 * extended_.count());
  std::copy(y, y + 3 * n, extended.begin());
#pragma omp parallel for schedule(static)
  for (int g = 0; g < images_.count(); ++g)
    for (int a = 0; a < 3; ++a) {
      double u = 0;  // Σ_s w_gs (y_s − x_s)
      for (int s = images_.offsets[g]; s < images_.offsets[g + 1]; ++s) {
        const int p = images_.particle[s];
        u += images_.weight[s] * (y[3 * p + a] - particles_.reference[3 * p + a]);
      }
      extended[3 * (n + g) + a] = images_.position[3 * g + a] + u;
    }
}

SecondOrderRow SecondOrderModel::row(int i) const {
  const int b = extended_families_.offsets[i];
  return {.bonds = extended_families_.offsets[i + 1] - b,
          .xi = xi_.data() + 3 * b,
          .length = extended_families_.reference_length.data() + b,
          .dilatation_weight = dilatation_weight_.data() + b,
          .deviatoric_weight = deviatoric_weight_.data() + b,
          .member_volume = member_volume_.data() + b,
          .fit = fit_.data() + b,
          .scale = scale_[i],
          .volume = particles_.volume[i],
          .bulk = materials_.bulk_modulus[i],
          .shear = materials_.shear_modulus[i],
          .deviatoric_modulus = deviatoric_modulus_[i],
          .cell_moment = cell_moment_[i],
          .stabilization = stabilization_};
}

void SecondOrderModel::bond_vectors(int i, const double* y, double* d) const {
  const auto& off = extended_families_.offsets;
  for (int b = off[i]; b < off[i + 1]; ++b) {
    const int j = extended_families_.neighbors[b];
    for (int a = 0; a < 3; ++a) d[3 * (b - off[i]) + a] = y[3 * j + a] - y[3 * i + a];
  }
}

double SecondOrderModel::row_energy(int i, const double* y, double* d, double* gradient,
                                    double* theta) const {
  bond_vectors(i, y, d);
  return second_order_row_energy(row(i), d, gradient, theta);
}

double SecondOrderModel::forces_and_energy(const double* y, double* f) {
  const int n = particles_.count(), total = extended_.count();
  extended_positions(y, positions_);
  const auto& off = extended_families_.offsets;
  const auto& member = extended_families_.neighbors;
  const std::size_t threads = static_cast<std::size_t>(omp_get_max_threads());
  if (thread_forces_.size() < threads) thread_forces_.resize(threads);
  int used = 1;
  double energy = 0;
#pragma omp parallel reduction(+ : energy)
  {
#pragma omp single
    used = omp_get_num_threads();
    std::vector<double>& force = thread_forces_[omp_get_thread_num()];
    force.assign(3 * static_cast<std::size_t>(total), 0.0);
    std::vector<double> d(3 * largest_row_), gradient(3 * largest_row_);
#pragma omp for schedule(dynamic, 32)
    for (int i = 0; i < n; ++i) {
      energy += row_energy(i, positions_.data(), d.data(), gradient.data(), nullptr);
      // −∂Π/∂y: d_b = y_j − y_i
      for (int b = off[i]; b < off[i + 1]; ++b)
        for (int a = 0; a < 3; ++a) {
          const double g = gradient[3 * (b - off[i]) + a];
          force[3 * i + a] += g;
          force[3 * member[b] + a] -= g;
        }
    }
  }
#pragma omp parallel for schedule(static)
  for (int k = 0; k < 3 * n; ++k) {
    double sum = 0;
    for (int t = 0; t < used; ++t) sum += thread_forces_[t][k];
    f[k] = sum;
  }
  // an image's force onto its stencil: y_g = x_g + Σ_s w_gs (y_s − x_s)
  for (int g = 0; g < images_.count(); ++g)
    for (int a = 0; a < 3; ++a) {
      double image_force = 0;
      for (int t = 0; t < used; ++t) image_force += thread_forces_[t][3 * (n + g) + a];
      for (int s = images_.offsets[g]; s < images_.offsets[g + 1]; ++s)
        f[3 * images_.particle[s] + a] += images_.weight[s] * image_force;
    }
  return energy;
}

void SecondOrderModel::energy_density(const double* y, double* w) {
  extended_positions(y, positions_);
#pragma omp parallel
  {
    std::vector<double> d(3 * largest_row_);
#pragma omp for schedule(dynamic, 32)
    for (int i = 0; i < particles_.count(); ++i)
      w[i] = row_energy(i, positions_.data(), d.data(), nullptr, nullptr) / particles_.volume[i];
  }
}

void SecondOrderModel::dilatation(const double* y, double* theta) const {
  extended_positions(y, positions_);
#pragma omp parallel
  {
    std::vector<double> d(3 * largest_row_), gradient(3 * largest_row_);
#pragma omp for schedule(dynamic, 32)
    for (int i = 0; i < particles_.count(); ++i)
      row_energy(i, positions_.data(), d.data(), gradient.data(), &theta[i]);
  }
}

double SecondOrderModel::reference_time_step() const {
  const int n = particles_.count();
  const auto& off = extended_families_.offsets;
  const auto& member = extended_families_.neighbors;
  std::vector<double> amplification(images_.count());  // Σ_s |w_gs|
  for (int g = 0; g < images_.count(); ++g)
    for (int s = images_.offsets[g]; s < images_.offsets[g + 1]; ++s)
      amplification[g] += std::abs(images_.weight[s]);
  std::vector<double> row_sum(3 * n, 0.0);  // bounds on Σ_c |K_rc|
#pragma omp parallel
  {
    std::vector<double> local(3 * n, 0.0);
    Eigen::MatrixXd H;
#pragma omp for schedule(dynamic, 16)
    for (int i = 0; i < n; ++i) {
      const SecondOrderRow r = row(i);
      second_order_row_hessian(r, r.xi, H);  // at the reference, d = ξ
      Eigen::VectorXd spread(3 * r.bonds);   // |P| 1 per bond component
      for (int b = 0; b < r.bonds; ++b) {
        const int j = member[off[i] + b];
        spread.segment<3>(3 * b).setConstant(1 + (j < n ? 1.0 : amplification[j - n]));
      }
      const Eigen::VectorXd z = H.cwiseAbs() * spread;
      for (int b = 0; b < r.bonds; ++b) {
        const int j = member[off[i] + b];
        for (int a = 0; a < 3; ++a) {
          local[3 * i + a] += z(3 * b + a);
          if (j < n) {
            local[3 * j + a] += z(3 * b + a);
            continue;
          }
          const int g = j - n;
          for (int s = images_.offsets[g]; s < images_.offsets[g + 1]; ++s)
            local[3 * images_.particle[s] + a] += std::abs(images_.weight[s]) * z(3 * b + a);
        }
      }
    }
#pragma omp critical
    for (int k = 0; k < 3 * n; ++k) row_sum[k] += local[k];
  }
  double largest = 0;  // λmax(M⁻¹K) ≤ max_r Σ_c |K_rc| / m_r (Gershgorin)
  for (int k = 0; k < 3 * n; ++k)
    if (particles_.mass[k / 3] > 0)
      largest = std::max(largest, row_sum[k] / particles_.mass[k / 3]);
  return largest > 0 ? 2 / std::sqrt(largest) : std::numeric_limits<double>::infinity();
}

void SecondOrderModel::break_bond(int, std::size_t) {
  throw std::logic_error("the second-order model has no fracture");
}

std::size_t SecondOrderModel::bytes_per_bond() const {
  // the families (neighbour, |ξ|, reverse) and ξ, c, w, V_j and the fit's 9 coefficients
  return sizeof(int) + sizeof(double) + sizeof(int) + 7 * sizeof(double) + sizeof(QuadraticBasis);
}

std::size_t SecondOrderModel::bytes_read_per_bond() const {
  return sizeof(int) + sizeof(double) + 7 * sizeof(double) + sizeof(QuadraticBasis);
}

void SecondOrderModel::distribute(const Halo&) {
  throw std::invalid_argument(
      "the second-order model (fictitious particles) cannot run over several ranks yet");
}

namespace {

// A clamped face must be a face of the bodies: no particle behind its plane (beyond half a
// horizon: a particle sits inside its tet, a fraction of λ from the face), and some within a
// horizon of it, else its images would clamp the field of other faces' images or nothing.
void check_clamp_face(const Scene& scene, std::size_t k) {
  const Constraint& c = scene.config.constraints[k];
  const Particles& p = scene.particles;
  bool near = false;
  for (int i = 0; i < p.count(); ++i) {
    double distance = 0;  // along the normal, out of the body
    for (int a = 0; a < 3; ++a)
      distance += c.clamp_normal[a] * (p.reference[3 * i + a] - c.clamp_point[a]);
    const double delta = scene.horizon_of_body[p.body[i]];
    if (distance > 0.5 * delta)
      throw InputError(scene.config.file, fmt::format("constraints[{}].clamp", k),
                       fmt::format("particle {} lies {:.3g} m behind the clamped face: put the "
                                   "plane on a face of the body, its normal pointing out of it",
                                   i, distance));
    near = near || distance > -delta;
  }
  if (!near)
    throw InputError(scene.config.file, fmt::format("constraints[{}].clamp", k),
                     "no particle lies within a horizon of the clamped face: put the plane on a "
                     "face of the body");
}

}  // namespace

std::unique_ptr<SecondOrderModel> make_second_order_model(const Scene& scene, MaterialPoints m,
                                                          double fit_radius, double stabilization) {
  const Particles& particles = scene.particles;
  std::vector<std::array<double, 6>> moments(particles.count());
  std::vector<char> has_cell(particles.count(), 0);
  FictitiousParticles images;
  for (const BodyTetMesh& body : scene.tet_meshes) {
    for (int t = 0; t < body.mesh.tet_count(); ++t)
      if (body.particle[t] >= 0)
        moments[body.particle[t]] = tet_second_moment(body.mesh, t), has_cell[body.particle[t]] = 1;
    add_mirror_images(particles, body.body, boundary_triangles(body.mesh),
                      scene.horizon_of_body[body.body], images);
  }
  for (int i = 0; i < particles.count(); ++i)
    if (!has_cell[i])
      throw std::invalid_argument(fmt::format(
          "the second-order model needs every body's tet mesh; particle {} has none", i));
  fit_stencils(particles, scene.horizon_of_body, fit_radius, images);
  for (std::size_t k = 0; k < scene.config.constraints.size(); ++k) {
    const Constraint& c = scene.config.constraints[k];
    if (!c.clamp) continue;
    check_clamp_face(scene, k);
    clamp_stencils(particles, scene.horizon_of_body, fit_radius, {c.clamp_point, c.clamp_normal},
                   images);
  }
  return std::make_unique<SecondOrderModel>(particles, scene.families, std::move(m),
                                            scene.horizon_of_body, std::move(images),
                                            std::move(moments), stabilization);
}

}  // namespace fissure
