#include "contact/self_contact.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "contact/contact_particles.hpp"

namespace fissure {

SelfContact::SelfContact(const Scene& scene, const Model& model)
    : families_(scene.families), model_(model) {
  auto particles = contact_particles(scene);
  radius_ = std::move(particles.radius);
  stiffness_ = std::move(particles.stiffness);
  for (double r : radius_) reach_ = std::max(reach_, 2 * r);
  // Skin 0.3 of the largest reach, a trade between the two costs. Each evaluation goes through
  // the pairs within about 1.3 reach, some 1.3³ ≈ 2.2 times those within reach; a rebuild
  // (about one elastic force evaluation) is due once particles moved skin/2 = 0.15 of the
  // largest reach (about 0.1 λ on tet-sampled bodies, r = ½V^(1/3)) relative to each other. A
  // larger skin lengthens every evaluation and every rebuild; a smaller one rebuilds more often.
  skin_ = 0.3 * reach_;
  start_at_rest(scene.particles.reference.data());
}

void SelfContact::start_at_rest(const double* y) {
  if (radius_.empty()) return;
  build_list(y);
  // Each pair without a bond closer than r_i + r_j at load caps both radii at half its distance,
  // so that r_i + r_j ≤ d for it; capping only shortens reaches, so no other pair comes to
  // overlap. Pairs of a broken bond are left out, so that a resumed run, whose model holds the
  // bonds broken since, caps the same radii.
  std::vector<double> capped = radius_;
  const int n = static_cast<int>(radius_.size());
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i)
    for (int s = list_start_[i]; s < list_start_[i + 1]; ++s) {
      if (candidates_[s].bond >= 0) continue;
      const int j = candidates_[s].j;
      double d2 = 0;
      for (int k = 0; k < 3; ++k) d2 += std::pow(y[3 * i + k] - y[3 * j + k], 2);
      const double distance = std::sqrt(d2);
      if (distance < radius_[i] + radius_[j]) capped[i] = std::min(capped[i], 0.5 * distance);
    }
  radius_ = std::move(capped);
  // The first evaluation builds the list afresh, at its own positions.
  built_at_.clear();
  builds_ = 0;
}

void SelfContact::build_grid(const double* y) {
  const int n = static_cast<int>(radius_.size());
  double lo[3] = {y[0], y[1], y[2]}, hi[3] = {y[0], y[1], y[2]};
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], y[3 * i + k]);
      hi[k] = std::max(hi[k], y[3 * i + k]);
    }
  // Cells at least the largest list cutoff; coarser when the particles are spread so far apart
  // that a fine grid would cost more memory than the particles themselves.
  const double budget = 8.0 * n + 27;
  size_ = reach_ + skin_;
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
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    int c[3];
    for (int k = 0; k < 3; ++k)
      c[k] = std::min(dims_[k] - 1, static_cast<int>((y[3 * i + k] - origin_[k]) / size_));
    cell_of_[i] = (c[2] * dims_[1] + c[1]) * dims_[0] + c[0];
  }
  for (int i = 0; i < n; ++i) ++cell_start_[cell_of_[i] + 1];
  for (long long c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
  cell_particles_.resize(n);
  std::vector<int> next(cell_start_.begin(), cell_start_.end() - 1);
  for (int i = 0; i < n; ++i) cell_particles_[next[cell_of_[i]]++] = i;
}

void SelfContact::build_list(const double* y) {
  build_grid(y);
  const int n = static_cast<int>(radius_.size());
  const double largest_radius = 0.5 * reach_;
  // Calls visit(j) for every other particle within r_i + r_j + skin of particle i. Of the 27
  // cells around i's, those farther from particle i than r_i + max r + skin are skipped: most of
  // them when the grid was coarsened (cells many times the cutoff, e.g. once fragments flew
  // apart), and the corners of the block otherwise.
  auto for_each_candidate = [&](int i, auto&& visit) {
    const int c = cell_of_[i];
    const int ci[3] = {c % dims_[0], (c / dims_[0]) % dims_[1], c / (dims_[0] * dims_[1])};
    // Squared distances from particle i to the planes of its cell's lower and upper faces, and
    // the largest squared distance a candidate may have (1e-9 more, so that round-off in the
    // face positions never skips a cell holding one).
    double below[3], above[3];
    for (int k = 0; k < 3; ++k) {
      const double face = origin_[k] + ci[k] * size_;
      below[k] = std::pow(std::max(0.0, y[3 * i + k] - face), 2);
      above[k] = std::pow(std::max(0.0, face + size_ - y[3 * i + k]), 2);
    }
    const double limit = std::pow((radius_[i] + largest_radius + skin_) * (1 + 1e-9), 2);
    auto gap = [&](int k, int step) { return step < 0 ? below[k] : step > 0 ? above[k] : 0.0; };
    for (int dz = -1; dz <= 1; ++dz) {
      const int z = ci[2] + dz;
      const double gz = gap(2, dz);
      if (z < 0 || z >= dims_[2] || gz > limit) continue;
      for (int dy = -1; dy <= 1; ++dy) {
        const int yy = ci[1] + dy;
        const double gzy = gz + gap(1, dy);
        if (yy < 0 || yy >= dims_[1] || gzy > limit) continue;
        for (int dx = -1; dx <= 1; ++dx) {
          const int x = ci[0] + dx;
          if (x < 0 || x >= dims_[0] || gzy + gap(0, dx) > limit) continue;
          const int cell = (z * dims_[1] + yy) * dims_[0] + x;
          for (int s = cell_start_[cell]; s < cell_start_[cell + 1]; ++s) {
            const int j = cell_particles_[s];
            if (j == i) continue;
            double d[3];
            for (int k = 0; k < 3; ++k) d[k] = y[3 * i + k] - y[3 * j + k];
            const double cutoff = radius_[i] + radius_[j] + skin_;
            if (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < cutoff * cutoff) visit(j);
          }
        }
      }
    }
  };
  // One pass over the grid, parallel over particles: each thread finds the rows of its block
  // of particles into a buffer of its own, then copies it to its place in the list.
  list_start_.assign(n + 1, 0);
  const auto& off = families_.offsets;
  const auto& nbr = families_.neighbors;
  std::vector<std::vector<Candidate>> found(omp_get_max_threads());
#pragma omp parallel
  {
    std::vector<Candidate>& mine = found[omp_get_thread_num()];
    int first_row = -1;
    // One block of rows per thread (static schedule, no chunk size): the rows of `mine` are
    // consecutive in the list.
#pragma omp for schedule(static)
    for (int i = 0; i < n; ++i) {
      if (first_row < 0) first_row = i;
      const std::size_t start = mine.size();
      for_each_candidate(i, [&](int j) { mine.push_back({j, -1}); });
      Candidate* row = mine.data() + start;
      const int count = static_cast<int>(mine.size() - start);
      // In increasing j, an order independent of the grid and of when the list was built; the
      // family row is sorted by j too, so each search starts where the previous one ended.
      std::sort(row, row + count, [](const Candidate& a, const Candidate& b) { return a.j < b.j; });
      auto bond = nbr.begin() + off[i];
      const auto end = nbr.begin() + off[i + 1];
      for (int s = 0; s < count; ++s) {
        bond = std::lower_bound(bond, end, row[s].j);
        if (bond != end && *bond == row[s].j) row[s].bond = static_cast<int>(bond - nbr.begin());
      }
      list_start_[i + 1] = count;
    }
#pragma omp single
    {
      for (int i = 0; i < n; ++i) list_start_[i + 1] += list_start_[i];
      candidates_.resize(list_start_[n]);
    }
    if (first_row >= 0)
      std::copy(mine.begin(), mine.end(), candidates_.begin() + list_start_[first_row]);
  }
  built_at_.assign(y, y + 3 * radius_.size());
  ++builds_;
  split_rows();
}

void SelfContact::split_rows() {
  const int n = static_cast<int>(radius_.size());
  touching_end_.resize(n);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    // Moving each touching candidate forward in turn keeps their order; sorting again restores
    // increasing j where an earlier split had moved a now broken bond's pair behind.
    Candidate* row = candidates_.data() + list_start_[i];
    const int count = list_start_[i + 1] - list_start_[i];
    int touching = 0;
    for (int s = 0; s < count; ++s)
      if (row[s].bond < 0 || !model_.bond_intact(row[s].bond)) std::swap(row[touching++], row[s]);
    std::sort(row, row + touching,
              [](const Candidate& a, const Candidate& b) { return a.j < b.j; });
    touching_end_[i] = list_start_[i] + touching;
  }
  split_revision_ = model_.revision();
}

namespace {

// How far n particles moved by Δ_k = to_k − from_k (Δ_k = to_k where from is null), not counting
// what they moved together: a pair's separation changed by |Δ_i − Δ_j| = |(Δ_i − u) − (Δ_j − u)|
// ≤ 2 max_k |Δ_k − u| for any common vector u. Returned: max_k |Δ_k − u|² for the better of u = 0
// (max_k |Δ_k|) and u the centre of the box around the Δ_k (at most half its diagonal from each),
// and whether `to` is finite. The second u keeps a body in flight from counting (drop_shatter's
// falling ball moves more than skin/2 at every step).
struct Spread {
  bool finite;
  double squared;
};
Spread spread(int n, const double* to, const double* from) {
  bool finite = true;
  double moved = 0;  // max_k |Δ_k|²
  constexpr double inf = std::numeric_limits<double>::infinity();
  double lo[3] = {inf, inf, inf}, hi[3] = {-inf, -inf, -inf};  // the box around the Δ_k
#pragma omp parallel for schedule(static) reduction(&& : finite) reduction(max : moved, hi[:3]) \
    reduction(min : lo[:3])
  for (int i = 0; i < n; ++i) {
    double d2 = 0;
    for (int k = 0; k < 3; ++k) {
      finite = finite && std::isfinite(to[3 * i + k]);
      const double d = from ? to[3 * i + k] - from[3 * i + k] : to[3 * i + k];
      d2 += d * d;
      lo[k] = std::min(lo[k], d);
      hi[k] = std::max(hi[k], d);
    }
    moved = std::max(moved, d2);
  }
  double half_diagonal = 0;  // squared
  for (int k = 0; k < 3; ++k) half_diagonal += 0.25 * (hi[k] - lo[k]) * (hi[k] - lo[k]);
  return {finite, std::min(moved, half_diagonal)};
}

}  // namespace

bool SelfContact::update_list(const double* y) {
  const int n = static_cast<int>(radius_.size());
  // The list is exact while the particles moved by at most skin/2 from a common motion since it
  // was built (spread above).
  const bool have_list = !built_at_.empty();
  const Spread moved = spread(n, y, have_list ? built_at_.data() : y);
  // A non-finite state has no geometry to search; the run loop stops on it after this step.
  if (!moved.finite) return false;
  if (!have_list || moved.squared > 0.25 * skin_ * skin_)
    build_list(y);
  else if (model_.revision() != split_revision_)
    split_rows();
  return true;
}

template <class Pair, class Finish>
void SelfContact::for_each_touching(const double* y, Pair&& pair, Finish&& finish) const {
  const int n = static_cast<int>(radius_.size());
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    double sum[3] = {0, 0, 0};
    for (int s = list_start_[i]; s < touching_end_[i]; ++s) {
      const int j = candidates_[s].j;
      double d[3];
      for (int k = 0; k < 3; ++k) d[k] = y[3 * i + k] - y[3 * j + k];
      const double distance = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      const double reach = radius_[i] + radius_[j];
      if (distance >= reach || distance == 0) continue;
      pair(i, j, d, distance, reach - distance, 0.5 * (stiffness_[i] + stiffness_[j]), sum);
    }
    finish(i, sum);
  }
}

void SelfContact::add_forces(const double* y, double* f) {
  if (radius_.empty() || !update_list(y)) return;
  for_each_touching(
      y,
      [](int, int, const double* d, double distance, double overlap, double k, double* push) {
        for (int c = 0; c < 3; ++c) push[c] += k * overlap * d[c] / distance;  // k (d_c − d) n
      },
      [&](int i, const double* push) {
        for (int c = 0; c < 3; ++c) f[3 * i + c] += push[c];
      });
}

double SelfContact::potential(const double* z, double* gradient, double* blocks) {
  if (radius_.empty() || !update_list(z)) return 0;
  std::vector<double> row_energy(radius_.size(), 0.0);
  // Per pair ½ k p², p = d_c − d the overlap; each row takes half, as both rows visit the pair.
  // ∂/∂y_i = −k p n (the push's negative); the Hessian's (i, i) block is k n nᵀ + k (p/d)
  // (n nᵀ − I), of which the projection keeps k n nᵀ (the second term is negative semidefinite).
  for_each_touching(
      z,
      [&](int i, int, const double* d, double distance, double overlap, double k, double* push) {
        const double n[3] = {d[0] / distance, d[1] / distance, d[2] / distance};
        row_energy[i] += 0.25 * k * overlap * overlap;
        for (int c = 0; c < 3; ++c) push[c] += k * overlap * n[c];
        if (blocks)
          for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) blocks[9 * i + 3 * a + b] += k * n[a] * n[b];
      },
      [&](int i, const double* push) {
        if (gradient)
          for (int c = 0; c < 3; ++c) gradient[3 * i + c] -= push[c];
      });
  double energy = 0;
  for (double e : row_energy) energy += e;
  return energy;
}

void SelfContact::add_coupling(const double* z, const double* v, double* out) const {
  if (radius_.empty() || built_at_.empty()) return;
  // −k n nᵀ v_j for each partner j of row i
  for_each_touching(
      z,
      [&](int, int j, const double* d, double distance, double, double k, double* sum) {
        const double n[3] = {d[0] / distance, d[1] / distance, d[2] / distance};
        const double along = n[0] * v[3 * j] + n[1] * v[3 * j + 1] + n[2] * v[3 * j + 2];
        for (int c = 0; c < 3; ++c) sum[c] -= k * along * n[c];
      },
      [&](int i, const double* sum) {
        for (int c = 0; c < 3; ++c) out[3 * i + c] += sum[c];
      });
}

double SelfContact::max_step(const double* dz) const {
  // the update's motion from a common one, as update_list measures it
  const double largest = std::sqrt(spread(static_cast<int>(radius_.size()), dz, nullptr).squared);
  return largest > 0.5 * skin_ ? 0.5 * skin_ / largest : 1.0;
}

}  // namespace fissure
