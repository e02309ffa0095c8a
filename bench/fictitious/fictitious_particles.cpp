#include "fictitious/fictitious_particles.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace fissure::bench {

namespace {

double squared_distance_to_box(const double* x, const BoxFaces& box) {
  double d2 = 0;
  for (int a = 0; a < 3; ++a) {
    const double e = std::max({box.min[a] - x[a], 0.0, x[a] - box.max[a]});
    d2 += e * e;
  }
  return d2;
}

// The fit's basis at offset d: ξ (order 1), then ½ξ_a², ξ_aξ_b (order 2).
int basis(const double* d, int order, double* phi) {
  phi[0] = d[0], phi[1] = d[1], phi[2] = d[2];
  if (order == 1) return 3;
  phi[3] = 0.5 * d[0] * d[0], phi[4] = 0.5 * d[1] * d[1], phi[5] = 0.5 * d[2] * d[2];
  phi[6] = d[0] * d[1], phi[7] = d[0] * d[2], phi[8] = d[1] * d[2];
  return 9;
}

int nearest_particle(const Particles& particles, const double* x) {
  int best = -1;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (int j = 0; j < particles.count(); ++j) {
    double d2 = 0;
    for (int a = 0; a < 3; ++a) d2 += std::pow(particles.reference[3 * j + a] - x[a], 2);
    if (d2 < best_d2) best_d2 = d2, best = j;
  }
  return best;
}

}  // namespace

Mirrors mirror_images(const Particles& particles, const BoxFaces& box, double horizon) {
  Mirrors mirrors;
  for (int s = 0; s < particles.count(); ++s) {
    const double* x = &particles.reference[3 * s];
    std::vector<std::array<int, 2>> near;
    for (const auto& face : box.free) {
      const double plane = face[1] ? box.max[face[0]] : box.min[face[0]];
      if (std::abs(x[face[0]] - plane) < horizon) near.push_back(face);
    }
    const int faces = static_cast<int>(near.size());
    for (int subset = 1; subset < (1 << faces); ++subset) {
      double image[3] = {x[0], x[1], x[2]};
      int axes = 0;
      bool distinct_axes = true;
      for (int f = 0; f < faces; ++f) {
        if (!(subset & (1 << f))) continue;
        const int axis = near[f][0];
        distinct_axes = distinct_axes && !(axes & (1 << axis));
        axes |= 1 << axis;
        const double plane = near[f][1] ? box.max[axis] : box.min[axis];
        image[axis] = 2 * plane - image[axis];
      }
      if (!distinct_axes || squared_distance_to_box(image, box) >= horizon * horizon) continue;
      mirrors.position.insert(mirrors.position.end(), image, image + 3);
      mirrors.volume.push_back(particles.volume[s]);
    }
  }
  return mirrors;
}

Mirrors lattice_images(const Particles& particles, const BoxFaces& box, double horizon) {
  double mean_volume = 0;
  for (double v : particles.volume) mean_volume += v / particles.count();
  const double spacing = std::cbrt(mean_volume);
  // beyond a free face: outside the box across it; the held faces get no points
  auto beyond_free_face = [&](const double* x) {
    for (const auto& face : box.free) {
      const int axis = face[0];
      if (face[1] ? x[axis] > box.max[axis] : x[axis] < box.min[axis]) return true;
    }
    return false;
  };
  auto beyond_held_face = [&](const double* x) {
    for (int axis = 0; axis < 3; ++axis)
      for (int side = 0; side < 2; ++side) {
        bool free = false;
        for (const auto& face : box.free) free = free || (face[0] == axis && face[1] == side);
        if (!free && (side ? x[axis] > box.max[axis] : x[axis] < box.min[axis])) return true;
      }
    return false;
  };
  Mirrors lattice;
  int steps[3];
  for (int a = 0; a < 3; ++a)
    steps[a] = static_cast<int>(std::ceil((box.max[a] - box.min[a] + 2 * horizon) / spacing)) + 1;
  for (int i = 0; i < steps[0]; ++i)
    for (int j = 0; j < steps[1]; ++j)
      for (int k = 0; k < steps[2]; ++k) {
        const int index[3] = {i, j, k};
        double x[3];
        for (int a = 0; a < 3; ++a) x[a] = box.min[a] - horizon + (index[a] + 0.5) * spacing;
        const double d2 = squared_distance_to_box(x, box);
        if (d2 == 0 || d2 >= horizon * horizon || !beyond_free_face(x) || beyond_held_face(x))
          continue;
        const int near = nearest_particle(particles, x);
        double r2 = 0;
        for (int a = 0; a < 3; ++a) r2 += std::pow(particles.reference[3 * near + a] - x[a], 2);
        if (r2 < 0.25 * spacing * spacing) continue;
        lattice.position.insert(lattice.position.end(), x, x + 3);
        lattice.volume.push_back(mean_volume);
      }
  return lattice;
}

Extrapolation extrapolation(const Particles& particles, const Mirrors& mirrors, double horizon,
                            double fit_radius, int order) {
  const int images = mirrors.count();
  std::vector<std::vector<std::pair<int, double>>> stencil(images);
  std::vector<double> conditioning(images, 1);
  const double radius = fit_radius * horizon;
#pragma omp parallel for schedule(dynamic, 16)
  for (int g = 0; g < images; ++g) {
    const double* x = &mirrors.position[3 * g];
    const int k = nearest_particle(particles, x);
    const double* xk = &particles.reference[3 * k];
    std::vector<int> members;
    std::vector<std::array<double, 9>> phis;
    std::vector<double> weights;
    Eigen::Matrix<double, 9, 9> moments = Eigen::Matrix<double, 9, 9>::Zero();
    int size = 3;
    for (int j = 0; j < particles.count(); ++j) {
      if (j == k) continue;
      double d[3], r2 = 0;
      for (int a = 0; a < 3; ++a) d[a] = particles.reference[3 * j + a] - xk[a], r2 += d[a] * d[a];
      if (r2 >= radius * radius) continue;
      std::array<double, 9> phi{};
      size = basis(d, order, phi.data());
      const double w = horizon / std::sqrt(r2) * particles.volume[j];
      for (int a = 0; a < size; ++a)
        for (int b = 0; b < size; ++b) moments(a, b) += w * phi[a] * phi[b];
      members.push_back(j), phis.push_back(phi), weights.push_back(w);
    }
    const Eigen::MatrixXd m = moments.topLeftCorner(size, size);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(m);
    if (eigen.info() != Eigen::Success || eigen.eigenvalues()(0) <= 0)
      throw std::runtime_error("a fictitious particle's fit has a singular moment matrix");
    conditioning[g] = eigen.eigenvalues()(0) / eigen.eigenvalues()(size - 1);
    double d[3];
    for (int a = 0; a < 3; ++a) d[a] = x[a] - xk[a];
    std::array<double, 9> psi{};
    basis(d, order, psi.data());
    const Eigen::VectorXd z = m.ldlt().solve(Eigen::Map<const Eigen::VectorXd>(psi.data(), size));
    double sum = 0;
    for (std::size_t t = 0; t < members.size(); ++t) {
      const double a = weights[t] * Eigen::Map<const Eigen::VectorXd>(phis[t].data(), size).dot(z);
      stencil[g].push_back({members[t], a});
      sum += a;
    }
    stencil[g].push_back({k, 1.0 - sum});  // u_g = u_k + Σ a_j (u_j − u_k)
  }
  Extrapolation e;
  e.offsets.push_back(0);
  for (int g = 0; g < images; ++g) {
    double l1 = 0;
    for (const auto& [j, a] : stencil[g])
      e.particle.push_back(j), e.weight.push_back(a), l1 += std::abs(a);
    e.offsets.push_back(static_cast<int>(e.particle.size()));
    e.largest_l1 = std::max(e.largest_l1, l1);
    e.mean_l1 += l1 / images;
    e.smallest_conditioning = std::min(e.smallest_conditioning, conditioning[g]);
  }
  return e;
}

}  // namespace fissure::bench
