#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "scene/particles.hpp"
#include "scene/point_cloud.hpp"

namespace fissure {

namespace {

std::uint64_t spread_bits(std::uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

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

// The k-d tree of every particle's reference position, built once per search of the families.
struct FamilySearch {
  explicit FamilySearch(const Particles& particles)
      : cloud{particles.reference}, tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {
    tree.buildIndex();
  }
  PointCloud cloud;
  KdTree tree;
};

// The members of consecutive rows, sorted within each row.
struct RowMembers {
  std::vector<int> size;       // per row
  std::vector<int> members;    // CSR order
  std::vector<int> positions;  // of a trimmed row's kept member: its position in the whole row
};

// Of a split (split_families): the ghosts' rows keep only their members in [begin, end).
struct Trim {
  const std::vector<char>& ghost;
  int begin, end;
};

// The members of rows [first, end); with `trim`, only of the ghosts' rows, trimmed. Each thread
// searches one contiguous block of rows (schedule(static) hands out blocks in thread order) into
// one flat buffer, so the rows join in CSR order. Flat buffers instead of a vector per row: those
// small blocks, once freed, would stay resident for the whole run.
RowMembers search_rows(const FamilySearch& search, const Particles& particles,
                       const std::vector<double>& horizon_of_body, int first, int end,
                       const Trim* trim) {
  RowMembers rows;
  rows.size.assign(end - first, 0);
  std::vector<std::vector<int>> block(omp_get_max_threads()), positions(block.size());
#pragma omp parallel
  {
    std::vector<std::pair<std::uint32_t, double>> matches;
    std::vector<int>& mine = block[omp_get_thread_num()];
    std::vector<int>& my_positions = positions[omp_get_thread_num()];
#pragma omp for schedule(static)
    for (int i = first; i < end; ++i) {
      if (trim && !trim->ghost[i]) continue;
      const std::size_t start = mine.size();
      search_family(search.tree, particles, horizon_of_body, i, matches,
                    [&mine](int j, double) { mine.push_back(j); });
      std::sort(mine.begin() + static_cast<std::ptrdiff_t>(start), mine.end());
      if (trim) {
        std::size_t kept = start;
        for (std::size_t k = start; k < mine.size(); ++k)
          if (mine[k] >= trim->begin && mine[k] < trim->end) {
            my_positions.push_back(static_cast<int>(k - start));
            mine[kept++] = mine[k];
          }
        mine.resize(kept);
      }
      rows.size[i - first] = static_cast<int>(mine.size() - start);
    }
  }
  for (std::vector<int>& part : block) {
    rows.members.insert(rows.members.end(), part.begin(), part.end());
    std::vector<int>().swap(part);
  }
  for (const std::vector<int>& part : positions)
    rows.positions.insert(rows.positions.end(), part.begin(), part.end());
  return rows;
}

// The families of the rows `parts` hold, which follow each other from row 0 to the last, with
// |ξ| and the reverse bonds.
Families assemble(const Particles& particles, std::vector<RowMembers> parts) {
  const int n = particles.count();
  Families f;
  f.offsets.assign(n + 1, 0);
  long long total = 0;
  int i = 0;
  for (const RowMembers& part : parts)
    for (const int size : part.size) {
      total += size;
      if (total > std::numeric_limits<int>::max())
        throw std::length_error(
            "more bonds than the 2^31 this build indexes; coarsen resolution or lower horizon");
      f.offsets[++i] = static_cast<int>(total);
    }
  f.neighbors.reserve(f.offsets[n]);
  for (RowMembers& part : parts) {
    f.neighbors.insert(f.neighbors.end(), part.members.begin(), part.members.end());
    f.trimmed_position.insert(f.trimmed_position.end(), part.positions.begin(),
                              part.positions.end());
    part = {};
  }
  f.reference_length.resize(f.offsets[n]);
#pragma omp parallel for schedule(static)
  for (int r = 0; r < n; ++r) {
    const double* xi = &particles.reference[3 * r];
    for (int b = f.offsets[r]; b < f.offsets[r + 1]; ++b) {
      const double* xj = &particles.reference[3 * f.neighbors[b]];
      f.reference_length[b] =
          std::sqrt((xj[0] - xi[0]) * (xj[0] - xi[0]) + (xj[1] - xi[1]) * (xj[1] - xi[1]) +
                    (xj[2] - xi[2]) * (xj[2] - xi[2]));
    }
  }
  // every member's row is kept (its whole row, or as a ghost its bonds to the own rows)
  f.reverse.resize(f.offsets[n]);
#pragma omp parallel for schedule(static)
  for (int r = 0; r < n; ++r)
    for (int b = f.offsets[r]; b < f.offsets[r + 1]; ++b) {
      const int j = f.neighbors[b];
      const auto row = f.neighbors.begin();
      f.reverse[b] =
          static_cast<int>(std::lower_bound(row + f.offsets[j], row + f.offsets[j + 1], r) - row);
    }
  return f;
}

// The particles order[0], order[1], … of p, in that order.
Particles select(const Particles& p, const std::vector<int>& order) {
  const std::size_t n = order.size();
  Particles selected;
  selected.reference.resize(3 * n);
  selected.velocity.resize(3 * n);
  selected.volume.resize(n);
  selected.mass.resize(n);
  selected.body.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const int i = order[k];
    for (int d = 0; d < 3; ++d) {
      selected.reference[3 * k + d] = p.reference[3 * i + d];
      selected.velocity[3 * k + d] = p.velocity[3 * i + d];
    }
    selected.volume[k] = p.volume[i];
    selected.mass[k] = p.mass[i];
    selected.body[k] = p.body[i];
  }
  return selected;
}

}  // namespace

Families build_families(const Particles& particles, const std::vector<double>& horizon_of_body) {
  const FamilySearch search(particles);
  std::vector<RowMembers> rows;
  rows.push_back(search_rows(search, particles, horizon_of_body, 0, particles.count(), nullptr));
  return assemble(particles, std::move(rows));
}

FamilySizes count_families(const Particles& particles, const std::vector<double>& horizon_of_body,
                           int first, int end) {
  const int n = particles.count();
  const FamilySearch search(particles);
  FamilySizes sizes;
  sizes.members.assign(n, 0);
  sizes.nearest.assign(n, std::numeric_limits<double>::infinity());
#pragma omp parallel
  {
    std::vector<std::pair<std::uint32_t, double>> matches;
#pragma omp for schedule(static)
    for (int i = first; i < end; ++i) {
      double nearest = std::numeric_limits<double>::infinity();
      search_family(search.tree, particles, horizon_of_body, i, matches, [&](int, double squared) {
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

// The own rows are searched once: their members name the ghosts, whose rows are searched next.
Families split_families(const Particles& particles, const std::vector<double>& horizon_of_body,
                        const std::vector<int>& offsets, int begin, int end) {
  const int n = particles.count();
  const FamilySearch search(particles);
  RowMembers own = search_rows(search, particles, horizon_of_body, begin, end, nullptr);
  for (int i = begin; i < end; ++i)
    if (own.size[i - begin] != offsets[i + 1] - offsets[i])
      throw std::logic_error("split_families: a family's size differs from its count");
  std::vector<char> ghost(n, 0);
  for (const int j : own.members)
    if (j < begin || j >= end) ghost[j] = 1;
  const Trim trim{ghost, begin, end};
  std::vector<RowMembers> rows;
  rows.push_back(search_rows(search, particles, horizon_of_body, 0, begin, &trim));
  rows.push_back(std::move(own));
  rows.push_back(search_rows(search, particles, horizon_of_body, end, n, &trim));
  Families f = assemble(particles, std::move(rows));
  f.global_offsets = offsets;
  f.own_begin = begin;
  f.own_end = end;
  return f;
}

// The kept rows are the non-empty ones: dropping the empty rows leaves every bond where it was,
// and numbers the members in the order of their ids, so each row keeps its order (and a row's
// forces their order of summation).
Families number_locally(Families split, Particles& particles) {
  if (split.whole() || !split.global_id.empty())
    throw std::logic_error("number_locally: the families are not split_families'");
  const int n = split.rows();
  Families f;
  std::vector<int> local_of(n, -1);
  for (int r = 0; r < n; ++r)
    if (split.offsets[r + 1] > split.offsets[r] ||
        (r >= split.first_own_row() && r < split.end_own_row())) {
      local_of[r] = static_cast<int>(f.global_id.size());
      f.global_id.push_back(r);
    }
  const int rows = static_cast<int>(f.global_id.size());
  f.offsets.resize(rows + 1);
  f.global_offsets.resize(rows + 1);
  for (int i = 0; i < rows; ++i) {
    f.offsets[i] = split.offsets[f.global_id[i]];
    f.global_offsets[i] = split.global_offsets[f.global_id[i]];
  }
  f.offsets[rows] = split.offsets[n];
  f.global_offsets[rows] = split.global_offsets[n];
  // the bonds stay where they are: only their members are renumbered
  f.neighbors = std::move(split.neighbors);
#pragma omp parallel for schedule(static)
  for (std::size_t b = 0; b < f.neighbors.size(); ++b) f.neighbors[b] = local_of[f.neighbors[b]];
  f.reference_length = std::move(split.reference_length);
  f.reverse = std::move(split.reverse);
  f.trimmed_position = std::move(split.trimmed_position);
  f.own_begin = static_cast<int>(
      std::lower_bound(f.global_id.begin(), f.global_id.end(), split.first_own_row()) -
      f.global_id.begin());
  f.own_end = f.own_begin + split.end_own_row() - split.first_own_row();
  f.whole_rows = n;
  particles = select(particles, f.global_id);
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
  Particles sorted = select(p, order);
  p = std::move(sorted);
  return order;
}

}  // namespace fissure
