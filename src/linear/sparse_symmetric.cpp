#include "linear/sparse_symmetric.hpp"

#include <algorithm>

namespace fissure {

int SparseSymmetric::find(int r, int c) const {
  const auto begin = columns.begin() + offsets[r], end = columns.begin() + offsets[r + 1];
  const auto it = std::lower_bound(begin, end, c);
  return it != end && *it == c ? static_cast<int>(it - columns.begin()) : -1;
}

void SparseSymmetric::multiply(const double* x, double* y) const {
#pragma omp parallel for schedule(static)
  for (int r = 0; r < rows; ++r) {
    double s = 0;
    for (int k = offsets[r]; k < offsets[r + 1]; ++k) s += values[k] * x[columns[k]];
    y[r] = s;
  }
}

int self_position(const Families& families, int i) {
  const auto begin = families.neighbors.begin() + families.offsets[i];
  const auto end = families.neighbors.begin() + families.offsets[i + 1];
  return static_cast<int>(std::lower_bound(begin, end, i) - begin);
}

SparseSymmetric expand_blocks(const std::vector<std::vector<int>>& adjacency) {
  const int n = static_cast<int>(adjacency.size());
  SparseSymmetric a;
  a.rows = 3 * n;
  a.offsets.assign(3 * n + 1, 0);
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d)
      a.offsets[3 * i + d + 1] = a.offsets[3 * i + d] + 3 * static_cast<int>(adjacency[i].size());
  a.columns.resize(a.offsets.back());
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) {
      int k = a.offsets[3 * i + d];
      for (int j : adjacency[i])
        for (int e = 0; e < 3; ++e) a.columns[k++] = 3 * j + e;
    }
  a.values.assign(a.columns.size(), 0.0);
  return a;
}

namespace {

std::vector<int> closed_family(const Families& families, int i) {
  std::vector<int> row(families.neighbors.begin() + families.offsets[i],
                       families.neighbors.begin() + families.offsets[i + 1]);
  row.insert(row.begin() + self_position(families, i), i);
  return row;
}

}  // namespace

SparseSymmetric bond_pattern(const Families& families) {
  return bond_pattern(families, 0, static_cast<int>(families.offsets.size()) - 1);
}

SparseSymmetric bond_pattern(const Families& families, int first, int end) {
  std::vector<std::vector<int>> adjacency(families.offsets.size() - 1);
#pragma omp parallel for schedule(static)
  for (int i = first; i < end; ++i) adjacency[i] = closed_family(families, i);
  return expand_blocks(adjacency);
}

SparseSymmetric scalar_bond_pattern(const Families& families) {
  const int n = static_cast<int>(families.offsets.size()) - 1;
  SparseSymmetric a;
  a.rows = n;
  a.offsets.assign(n + 1, 0);
  for (int i = 0; i < n; ++i)
    a.offsets[i + 1] = a.offsets[i] + families.offsets[i + 1] - families.offsets[i] + 1;
  a.columns.resize(a.offsets.back());
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    const std::vector<int> row = closed_family(families, i);
    std::copy(row.begin(), row.end(), a.columns.begin() + a.offsets[i]);
  }
  a.values.assign(a.columns.size(), 0.0);
  return a;
}

SparseSymmetric two_hop_pattern(const Families& families) {
  const int n = static_cast<int>(families.offsets.size()) - 1;
  std::vector<std::vector<int>> adjacency(n);
#pragma omp parallel
  {
    std::vector<char> seen(n, 0);
#pragma omp for schedule(dynamic, 64)
    for (int i = 0; i < n; ++i) {
      std::vector<int>& row = adjacency[i];
      for (int k : closed_family(families, i))
        for (int j : closed_family(families, k))
          if (!seen[j]) {
            seen[j] = 1;
            row.push_back(j);
          }
      for (int j : row) seen[j] = 0;
      std::sort(row.begin(), row.end());
    }
  }
  return expand_blocks(adjacency);
}

}  // namespace fissure
