#include "linear/banded_ordering.hpp"

#include <algorithm>

namespace fissure {

namespace {

// Breadth-first search over the rows not yet placed (placed[r] == 0) from `root`: appends the
// component's rows to `order` level by level, each row's new neighbours by increasing degree
// (Cuthill–McKee); returns the first row of the last level, one farthest from the root.
int level_sets(const SparseSymmetric& A, int root, std::vector<char>& placed,
               std::vector<int>& order) {
  const auto degree = [&](int r) { return A.offsets[r + 1] - A.offsets[r]; };
  order.push_back(root);
  placed[root] = 1;
  std::size_t begin = order.size() - 1, end = order.size();
  int farthest = root;
  while (begin < end) {
    farthest = order[begin];
    for (std::size_t k = begin; k < end; ++k) {
      const std::size_t first_new = order.size();
      for (int e = A.offsets[order[k]]; e < A.offsets[order[k] + 1]; ++e) {
        const int c = A.columns[e];
        if (placed[c]) continue;
        placed[c] = 1;
        order.push_back(c);
      }
      std::stable_sort(order.begin() + static_cast<std::ptrdiff_t>(first_new), order.end(),
                       [&](int a, int b) { return degree(a) < degree(b); });
    }
    begin = end;
    end = order.size();
  }
  return farthest;
}

}  // namespace

std::vector<int> reverse_cuthill_mckee(const SparseSymmetric& A) {
  const int n = A.rows;
  std::vector<int> order;
  order.reserve(n);
  std::vector<char> placed(n, 0);
  for (int seed = 0; seed < n; ++seed) {
    if (placed[seed]) continue;
    // A pseudo-peripheral root of the seed's component: the far end of a search from the seed,
    // searched from again (two sweeps find the ends of an elongated body).
    const std::size_t start = order.size();
    int root = seed;
    for (int sweep = 0; sweep < 2; ++sweep) {
      root = level_sets(A, root, placed, order);
      for (std::size_t k = start; k < order.size(); ++k) placed[order[k]] = 0;
      order.resize(start);
    }
    level_sets(A, root, placed, order);
  }
  std::reverse(order.begin(), order.end());
  return order;
}

}  // namespace fissure
