#include "fracture/fragments.hpp"

#include <numeric>
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

// The components of the graph of the bonds `intact(b)` keeps.
template <class Intact>
long components(const Families& families, Intact intact) {
  const int n = static_cast<int>(families.offsets.size()) - 1;
  DisjointSets sets(n);
  long count = n;
  for (int i = 0; i < n; ++i)
    for (int b = families.offsets[i]; b < families.offsets[i + 1]; ++b) {
      const int j = families.neighbors[b];
      if (j > i && intact(b) && sets.unite(i, j)) --count;
    }
  return count;
}

}  // namespace

long count_fragments(const Families& families, const Model& model) {
  return components(families, [&model](int b) { return model.bond_intact(b); });
}

long count_fragments(const Families& families, const std::vector<std::uint8_t>& broken) {
  return components(families, [&broken](int b) { return broken.empty() || broken[b] == 0; });
}

}  // namespace fissure
