#include "model/paper_model.hpp"

#include <cmath>
#include <numbers>

#include "model/stable_time_step.hpp"
#include "scene/scene.hpp"

namespace fissure {

namespace {

constexpr double pi = std::numbers::pi;

// a = 9κ/(8πδ⁴), b = 15μ/(2πδ⁵) (Eq 10); d = 9/(4πδ⁴) (Eq 6).
double a_constant(double kappa, double delta) {
  return 9.0 * kappa / (8.0 * pi * std::pow(delta, 4));
}
double b_constant(double mu, double delta) { return 15.0 * mu / (2.0 * pi * std::pow(delta, 5)); }
double d_constant(double delta) { return 9.0 / (4.0 * pi * std::pow(delta, 4)); }

struct BondGeometry {
  double n[3];    // deformed direction
  double length;  // |y_j − y_i|
  double lambda;  // Λ = n·ξ/|ξ|
};

BondGeometry bond_geometry(const double* x, const double* y, int i, int j, double xi) {
  BondGeometry g{};
  double d[3], r[3];
  for (int k = 0; k < 3; ++k) {
    d[k] = y[3 * j + k] - y[3 * i + k];
    r[k] = x[3 * j + k] - x[3 * i + k];
  }
  g.length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  const double inv = g.length > 0 ? 1.0 / g.length : 0.0;
  for (int k = 0; k < 3; ++k) g.n[k] = d[k] * inv;
  g.lambda = (g.n[0] * r[0] + g.n[1] * r[1] + g.n[2] * r[2]) / xi;
  return g;
}

}  // namespace

PaperModel::PaperModel(const Particles& particles, const Families& families,
                       MaterialPoints materials)
    : Model(particles, families, std::move(materials)) {
  omega_.resize(families.directed_bonds());
  for (int i = 0; i < particles.count(); ++i)
    for (int b = families.offsets[i]; b < families.offsets[i + 1]; ++b)
      omega_[b] =
          influence(materials_, i, reference_vector(particles, i, families.neighbors[b]).data(),
                    families.reference_length[b]);  // Eq 5, 17
  dilatation_.assign(particles.count(), 0.0);
  a_.resize(particles.count());
  b_.resize(particles.count());
  for (int i = 0; i < particles.count(); ++i) {
    a_[i] = a_constant(materials_.bulk_modulus[i], materials_.horizon[i]);
    b_[i] = b_constant(materials_.shear_modulus[i], materials_.horizon[i]);
  }
}

void PaperModel::dilatation(const double* y, double* theta) const {
  const int n = particles_.count();
  const double* x = particles_.reference.data();
  const auto& off = families_.offsets;
  const auto& nbr = families_.neighbors;
  const auto& xi = families_.reference_length;
  const auto& V = particles_.volume;
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    double sum = 0;
    for (int b = off[i]; b < off[i + 1]; ++b) {
      const BondGeometry g = bond_geometry(x, y, i, nbr[b], xi[b]);
      const double stretch = g.length / xi[b] - 1.0;
      sum += omega_[b] * stretch * g.lambda * xi[b] * V[nbr[b]];
    }
    theta[i] = d_constant(materials_.horizon[i]) * sum;
  }
}

void PaperModel::forces(const double* y, double* f) {
  const int n = particles_.count();
  const double* x = particles_.reference.data();
  const auto& off = families_.offsets;
  const auto& nbr = families_.neighbors;
  const auto& xi = families_.reference_length;
  const auto& V = particles_.volume;
  dilatation(y, dilatation_.data());
  // A = 4ωaΛθ + 4ωb(e − δ/4 Λθ) (Eqs 4, 8); F_i = V_i Σ_j ½(A_ij + A_ji) n_ij V_j (Eqs 2, 3).
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    double force[3] = {0, 0, 0};
    for (int b = off[i]; b < off[i + 1]; ++b) {
      const int j = nbr[b];
      const BondGeometry g = bond_geometry(x, y, i, j, xi[b]);
      const double e = g.length - xi[b];
      auto A = [&](int p) {
        const double lt = g.lambda * dilatation_[p];
        return 4.0 * omega_[b] * (a_[p] * lt + b_[p] * (e - 0.25 * materials_.horizon[p] * lt));
      };
      const double t = 0.5 * (A(i) + A(j)) * V[j];
      for (int k = 0; k < 3; ++k) force[k] += t * g.n[k];
    }
    for (int k = 0; k < 3; ++k) f[3 * i + k] = V[i] * force[k];
  }
}

void PaperModel::energy_density(const double* y, double* w) {
  const int n = particles_.count();
  const double* x = particles_.reference.data();
  const auto& off = families_.offsets;
  const auto& nbr = families_.neighbors;
  const auto& xi = families_.reference_length;
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    const double delta = materials_.horizon[i];
    double theta = 0, deviatoric = 0;
    for (int b = off[i]; b < off[i + 1]; ++b) {
      const double e = bond_geometry(x, y, i, nbr[b], xi[b]).length - xi[b];
      const double wv = omega_[b] * particles_.volume[nbr[b]];
      theta += wv * e;
      deviatoric += wv * e * e;
    }
    theta *= d_constant(delta);
    const double alpha =
        0.5 * (materials_.bulk_modulus[i] - 5.0 / 3.0 * materials_.shear_modulus[i]);
    w[i] = alpha * theta * theta + b_constant(materials_.shear_modulus[i], delta) * deviatoric;
  }
}

double PaperModel::stable_time_step() const {
  const int n = particles_.count();
  std::vector<double> b(n), c(omega_.size());
  for (int i = 0; i < n; ++i) {
    b[i] = b_constant(materials_.shear_modulus[i], materials_.horizon[i]);
    for (int k = families_.offsets[i]; k < families_.offsets[i + 1]; ++k)
      c[k] = d_constant(materials_.horizon[i]) * omega_[k];  // c_ij = d ω_ij (notes §3)
  }
  return gershgorin_time_step(particles_, families_, materials_, {b, omega_, c});
}

void PaperModel::break_bond(int, std::size_t b) {
  omega_[b] = 0;
  mark_changed();
}

std::size_t PaperModel::bytes_per_bond() const {
  return 2 * sizeof(int) + 2 * sizeof(double);  // neighbour, |ξ|, reverse index, ω
}

std::size_t PaperModel::bytes_read_per_bond() const {
  return 2 * (sizeof(int) + 2 * sizeof(double));  // neighbour, |ξ|, ω in both passes
}

ModelKind paper_model_kind() {
  return {"paper",
          {},
          [](const OptionReader& r) -> std::shared_ptr<const ModelOptions> {
            if (r.has("plasticity"))
              r.fail("plasticity", "plasticity needs model: lps (the default)");
            return nullptr;
          },
          [](const Scene& scene, MaterialPoints m) {
            return std::make_unique<PaperModel>(scene.particles, scene.families, std::move(m));
          }};
}

}  // namespace fissure
