#include "contact/self_contact.hpp"

#include <algorithm>
#include <cmath>

#include "contact/contact_particles.hpp"

namespace fissure {

SelfContact::SelfContact(const Scene& scene, const Model& model)
    : families_(scene.families), model_(model) {
  auto particles = contact_particles(scene);
  radius_ = std::move(particles.radius);
  stiffness_ = std::move(particles.stiffness);
  for (double r : radius_) cell_ = std::max(cell_, 2 * r);
}

void SelfContact::build_grid(const double* y) {
  const int n = static_cast<int>(radius_.size());
  double lo[3] = {y[0], y[1], y[2]}, hi[3] = {y[0], y[1], y[2]};
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], y[3 * i + k]);
      hi[k] = std::max(hi[k], y[3 * i + k]);
    }
  // Cells at least the largest contact reach; coarser when the particles are spread so far
  // apart that a fine grid would cost more memory than the particles themselves.
  const double budget = 8.0 * n + 27;
  size_ = cell_;
  auto count = [&] {
    double total = 1;
    for (int k = 0; k < 3; ++k) total *= std::floor((hi[k] - lo[k]) / size_) + 1;
    return total;
  };
  while (count() > budget) size_ *= 2;
  long long cells = 1;
  for (int k = 0; k < 3; ++k) {
    origin_[k] = lo[k];
    dims_[k] = static_cast<int>((hi[k] - lo[k]) / size_) + 1;
    cells *= dims_[k];
  }
  cell_of_.resize(n);
  cell_start_.assign(cells + 1, 0);
  for (int i = 0; i < n; ++i) {
    int c[3];
    for (int k = 0; k < 3; ++k)
      c[k] = std::min(dims_[k] - 1, static_cast<int>((y[3 * i + k] - origin_[k]) / size_));
    cell_of_[i] = (c[2] * dims_[1] + c[1]) * dims_[0] + c[0];
    ++cell_start_[cell_of_[i] + 1];
  }
  for (long long c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
  cell_particles_.resize(n);
  std::vector<int> next(cell_start_.begin(), cell_start_.end() - 1);
  for (int i = 0; i < n; ++i) cell_particles_[next[cell_of_[i]]++] = i;
}

void SelfContact::add_forces(const double* y, double* f) {
  // A non-finite state has no geometry to search; the run loop stops on it after this step.
  for (std::size_t k = 0; k < 3 * radius_.size(); ++k)
    if (!std::isfinite(y[k])) return;
  build_grid(y);
  const int n = static_cast<int>(radius_.size());
  const auto& off = families_.offsets;
  const auto& nbr = families_.neighbors;
#pragma omp parallel for schedule(dynamic, 256)
  for (int i = 0; i < n; ++i) {
    const int c = cell_of_[i];
    const int ci[3] = {c % dims_[0], (c / dims_[0]) % dims_[1], c / (dims_[0] * dims_[1])};
    double force[3] = {0, 0, 0};
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int x = ci[0] + dx, yy = ci[1] + dy, z = ci[2] + dz;
          if (x < 0 || yy < 0 || z < 0 || x >= dims_[0] || yy >= dims_[1] || z >= dims_[2])
            continue;
          const int cell = (z * dims_[1] + yy) * dims_[0] + x;
          for (int s = cell_start_[cell]; s < cell_start_[cell + 1]; ++s) {
            const int j = cell_particles_[s];
            if (j == i) continue;
            double d[3];
            for (int k = 0; k < 3; ++k) d[k] = y[3 * i + k] - y[3 * j + k];
            const double distance = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            const double reach = radius_[i] + radius_[j];
            if (distance >= reach || distance == 0) continue;
            // Bonded pairs interact through the model only.
            const auto row = nbr.begin() + off[i], end = nbr.begin() + off[i + 1];
            const auto it = std::lower_bound(row, end, j);
            if (it != end && *it == j && model_.bond_intact(it - nbr.begin())) continue;
            const double push = 0.5 * (stiffness_[i] + stiffness_[j]) * (reach - distance);
            for (int k = 0; k < 3; ++k) force[k] += push * d[k] / distance;
          }
        }
    for (int k = 0; k < 3; ++k) f[3 * i + k] += force[k];
  }
}

}  // namespace fissure
