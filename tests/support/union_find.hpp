#pragma once
// Connected pieces by union–find with path halving.
#include <numeric>
#include <vector>

namespace fissure::test {

struct UnionFind {
  std::vector<int> parent;

  explicit UnionFind(int count) : parent(count) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
  // Puts a's piece into b's.
  void join(int a, int b) {
    const int root = find(b);
    parent[find(a)] = root;
  }
  // The root of each of the first `count` elements: equal roots, one piece.
  std::vector<int> roots(int count) {
    std::vector<int> root(count);
    for (int i = 0; i < count; ++i) root[i] = find(i);
    return root;
  }
};

}  // namespace fissure::test
