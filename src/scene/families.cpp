#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <nanoflann.hpp>
#include <numeric>
#include <stdexcept>

#include "scene/particles.hpp"

namespace fissure {

namespace {

struct PointCloud {
  const std::vector<double>& xyz;
  std::size_t kdtree_get_point_count() const { return xyz.size() / 3; }
  double kdtree_get_pt(std::size_t i, std::size_t dim) const { return xyz[3 * i + dim]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};

using KdTree = nanoflann::KDTreeSingleIndexAdaptor<
    nanoflann::L2_Simple_Adaptor<double, PointCloud, double, std::uint32_t>, PointCloud, 3,
    std::uint32_t>;

std::uint64_t spread_bits(std::uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

}  // namespace

namespace {

// The members of particle i: every other particle of its body within its horizon, passed to
// visit(j, squared distance) in the k-d tree's order.
template <class Visit>
void search_family(const KdTree& tree, const Particles& particles,
                   const std::vector<double>& horizon_of_body, int i,
                   std::vector<std::pair<std::uint32_t, double>>& matches, Visit visit) {
  const int body = particles.body[i];
  const double delta = horizon_of_body[body];
  matches.clear();
  tree.radiusSearch(&particles.reference[3 * i], delta * delta, matches,
                    nanoflann::SearchParams(32, 0, false));
  for (const auto& match : matches) {
    const int j = static_cast<int>(match.first);
    if (j != i && particles.body[j] == body) visit(j, match.second);
  }
}

// How families_of keeps a row.
enum Keep : char { absent = 0, whole_row = 1, own_members = 2 };

// The families of the rows `keep` marks (every row whole when it is empty), the others empty; a
// row marked own_members keeps only its members in [own_begin, own_end), and each such bond's
// position in its whole row goes to trimmed_position.
Families families_of(const Particles& particles, const std::vector<double>& horizon_of_body,
                     const std::vector<char>& keep, int own_begin = 0, int own_end = 0) {
  const int n = particles.count();
  PointCloud cloud{particles.reference};
  KdTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  tree.buildIndex();
  const auto kept = [&keep](int i) { return keep.empty() || keep[i] != absent; };

  // Each thread searches one contiguous block of rows (schedule(static) hands out blocks in
  // thread order) into one flat buffer, so the rows join in CSR order. Flat buffers instead of a
  // vector per row: those small blocks, once freed, would stay resident for the whole run.
  std::vector<int> row_size(n, 0);
  std::vector<std::vector<int>> block(omp_get_max_threads()), positions(block.size());
#pragma omp parallel
  {
    std::vector<std::pair<std::uint32_t, double>> matches;
    std::vector<int>& mine = block[omp_get_thread_num()];
    std::vector<int>& my_positions = positions[omp_get_thread_num()];
#pragma omp for schedule(static)
    for (int i = 0; i < n; ++i) {
      if (!kept(i)) continue;
      const std::size_t start = mine.size();
      search_family(tree, particles, horizon_of_body, i, matches,
                    [&mine](int j, double) { mine.push_back(j); });
      std::sort(mine.begin() + static_cast<std::ptrdiff_t>(start), mine.end());
      if (!keep.empty() && keep[i] == own_members) {
        std::size_t end = start;
        for (std::size_t k = start; k < mine.size(); ++k)
          if (mine[k] >= own_begin && mine[k] < own_end) {
            my_positions.push_back(static_cast<int>(k - start));
            mine[end++] = mine[k];
          }
        mine.resize(end);
      }
      row_size[i] = static_cast<int>(mine.size() - start);
    }
  }

  long long total = 0;
  for (const int size : row_size) total += size;
  if (total > std::numeric_limits<int>::max())
    throw std::length_error(fmt::format(
        "{} bonds exceed the 2^31 this build indexes; coarsen resolution or lower horizon", total));
  Families f;
  f.offsets.assign(n + 1, 0);
  for (int i = 0; i < n; ++i) f.offsets[i + 1] = f.offsets[i] + row_size[i];
  f.neighbors.reserve(f.offsets[n]);
  for (std::vector<int>& rows : block) {
    f.neighbors.insert(f.neighbors.end(), rows.begin(), rows.end());
    std::vector<int>().swap(rows);
  }
  for (const std::vector<int>& rows : positions)
    f.trimmed_position.insert(f.trimmed_position.end(), rows.begin(), rows.end());
  f.reference_length.resize(f.offsets[n]);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    const double* xi = &particles.reference[3 * i];
    for (int b = f.offsets[i]; b < f.offsets[i + 1]; ++b) {
      const double* xj = &particles.reference[3 * f.neighbors[b]];
      f.reference_length[b] =
          std::sqrt((xj[0] - xi[0]) * (xj[0] - xi[0]) + (xj[1] - xi[1]) * (xj[1] - xi[1]) +
                    (xj[2] - xi[2]) * (xj[2] - xi[2]));
    }
  }
  f.reverse.resize(f.offsets[n]);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i)
    for (int b = f.offsets[i]; b < f.offsets[i + 1]; ++b) {
      const int j = f.neighbors[b];
      const auto row = f.neighbors.begin();
      f.reverse[b] =
          kept(j) ? static_cast<int>(
                        std::lower_bound(row + f.offsets[j], row + f.offsets[j + 1], i) - row)
                  : -1;
    }
  return f;
}

}  // namespace

Families build_families(const Particles& particles, const std::vector<double>& horizon_of_body) {
  return families_of(particles, horizon_of_body, {});
}

FamilySizes count_families(const Particles& particles, const std::vector<double>& horizon_of_body,
                           int first, int end) {
  const int n = particles.count();
  PointCloud cloud{particles.reference};
  KdTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  tree.buildIndex();
  FamilySizes sizes;
  sizes.members.assign(n, 0);
  sizes.nearest.assign(n, std::numeric_limits<double>::infinity());
#pragma omp parallel
  {
    std::vector<std::pair<std::uint32_t, double>> matches;
#pragma omp for schedule(static)
    for (int i = first; i < end; ++i) {
      double nearest = std::numeric_limits<double>::infinity();
      search_family(tree, particles, horizon_of_body, i, matches, [&](int, double squared) {
        ++sizes.members[i];
        nearest = std::min(nearest, squared);
      });
      sizes.nearest[i] = std::sqrt(nearest);
    }
  }
  return sizes;
}

std::vector<int> FamilySizes::offsets() const {
  std::vector<int> offsets(members.size() + 1, 0);
  long long total = 0;
  for (std::size_t i = 0; i < members.size(); ++i) {
    total += members[i];
    if (total > std::numeric_limits<int>::max())
      throw std::length_error(
          "more bonds than the 2^31 this build indexes; coarsen resolution or lower horizon");
    offsets[i + 1] = static_cast<int>(total);
  }
  return offsets;
}

Families split_families(const Particles& particles, const std::vector<double>& horizon_of_body,
                        const std::vector<int>& offsets, int begin, int end) {
  const int n = particles.count();
  std::vector<char> keep(n, absent);
  std::fill(keep.begin() + begin, keep.begin() + end, whole_row);
  {
    const Families own = families_of(particles, horizon_of_body, keep);
    for (int b = own.offsets[begin]; b < own.offsets[end]; ++b)
      if (keep[own.neighbors[b]] == absent) keep[own.neighbors[b]] = own_members;
  }
  Families f = families_of(particles, horizon_of_body, keep, begin, end);
  for (int i = begin; i < end; ++i)
    if (f.offsets[i + 1] - f.offsets[i] != offsets[i + 1] - offsets[i])
      throw std::logic_error("split_families: a family's size differs from its count");
  f.global_offsets = offsets;
  f.own_begin = begin;
  f.own_end = end;
  return f;
}

std::vector<int> sort_spatially(Particles& p, double cell) {
  const int n = p.count();
  if (n == 0) return {};
  double lo[3] = {p.reference[0], p.reference[1], p.reference[2]};
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) lo[d] = std::min(lo[d], p.reference[3 * i + d]);
  std::vector<std::uint64_t> code(n);
  for (int i = 0; i < n; ++i) {
    std::uint64_t c = 0;
    for (int d = 0; d < 3; ++d)
      c |= spread_bits(static_cast<std::uint64_t>((p.reference[3 * i + d] - lo[d]) / cell)) << d;
    code[i] = c;
  }
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return code[a] < code[b]; });
  Particles sorted;
  sorted.reference.resize(3 * n);
  sorted.velocity.resize(3 * n);
  sorted.volume.resize(n);
  sorted.mass.resize(n);
  sorted.body.resize(n);
  for (int k = 0; k < n; ++k) {
    const int i = order[k];
    for (int d = 0; d < 3; ++d) {
      sorted.reference[3 * k + d] = p.reference[3 * i + d];
      sorted.velocity[3 * k + d] = p.velocity[3 * i + d];
    }
    sorted.volume[k] = p.volume[i];
    sorted.mass[k] = p.mass[i];
    sorted.body[k] = p.body[i];
  }
  p = std::move(sorted);
  return order;
}

}  // namespace fissure
