#include "fracture/fragments.hpp"

#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

namespace fissure {

namespace {

// Union-find with path halving and union by size.
class DisjointSets {
 public:
  explicit DisjointSets(int n) : parent_(n), size_(n, 1) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  int find(int i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  // Returns true if a and b were in different sets.
  bool unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    if (size_[a] < size_[b]) std::swap(a, b);
    parent_[b] = a;
    size_[a] += size_[b];
    return true;
  }

 private:
  std::vector<int> parent_, size_;
};

// Joins the particles the intact bonds (`intact(b)`) of rows [first, end) connect; returns how
// many joins merged two sets.
template <class Intact>
long join_rows(const Families& families, int first, int end, Intact intact, DisjointSets& sets) {
  long joined = 0;
  for (int i = first; i < end; ++i)
    for (int b = families.offsets[i]; b < families.offsets[i + 1]; ++b) {
      const int j = families.neighbors[b];
      if (j > i && intact(b) && sets.unite(i, j)) ++joined;
    }
  return joined;
}

// The components of the graph of the bonds `intact(b)` keeps.
template <class Intact>
long components(const Families& families, Intact intact) {
  const int n = static_cast<int>(families.offsets.size()) - 1;
  DisjointSets sets(n);
  return n - join_rows(families, 0, n, intact, sets);
}

void check(int code, const char* what) {
  if (code != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + what + " failed");
}

}  // namespace

long count_fragments(const Families& families, const Model& model) {
  return components(families, [&model](int b) { return model.bond_intact(b); });
}

long count_fragments(const Families& families, const std::vector<std::uint8_t>& broken) {
  return components(families, [&broken](int b) { return broken.empty() || broken[b] == 0; });
}

long count_fragments(MPI_Comm comm, const Families& families,
                     const std::vector<std::uint8_t>& broken) {
  int rank = 0, size = 1;
  check(MPI_Comm_rank(comm, &rank), "MPI_Comm_rank");
  check(MPI_Comm_size(comm, &size), "MPI_Comm_size");
  const int n = static_cast<int>(families.offsets.size()) - 1;
  DisjointSets sets(n);
  join_rows(
      families, families.first_own_row(), families.end_own_row(),
      [&broken](int b) { return broken.empty() || broken[b] == 0; }, sets);
  // (particle, its representative) where they differ, by their ids in the whole scene
  std::vector<int> pairs;
  for (int k = 0; k < n; ++k)
    if (const int root = sets.find(k); root != k)
      pairs.insert(pairs.end(), {families.global_row(k), families.global_row(root)});
  const int count = static_cast<int>(pairs.size());
  std::vector<int> counts(rank == 0 ? size : 0), displacements(counts.size());
  check(MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm), "MPI_Gather");
  long total = 0;
  for (int r = 0; r < static_cast<int>(counts.size()); ++r) {
    displacements[r] = static_cast<int>(total);
    total += counts[r];
  }
  std::vector<int> all(static_cast<std::size_t>(total));
  check(MPI_Gatherv(pairs.data(), count, MPI_INT, all.data(), counts.data(), displacements.data(),
                    MPI_INT, 0, comm),
        "MPI_Gatherv");
  if (rank != 0) return 0;
  DisjointSets whole(families.total_rows());
  long fragments = families.total_rows();
  for (std::size_t k = 0; k + 1 < all.size(); k += 2)
    if (whole.unite(all[k], all[k + 1])) --fragments;
  return fragments;
}

}  // namespace fissure
