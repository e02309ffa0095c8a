// The second-order model's stiffness (second_order_model.hpp): each row's Hessian over its bond
// vectors (second_order_row_hessian.cpp) folded onto the particles through the map P_i from
// their displacements to the row's bonds, d_b = y_j − y_i for a particle j and
// d_b = x_g + Σ_s w_gs (y_s − x_s) − y_i for an image g (fictitious_particles.hpp).
#include <omp.h>

#include <Eigen/Dense>
#include <algorithm>
#include <stdexcept>

#include "linear/sparse_symmetric.hpp"
#include "model/second_order_model.hpp"

namespace fissure {

void SecondOrderModel::fold_row(int i, FoldedRow& row) const {
  const int n = particles_.count();
  const auto& off = extended_families_.offsets;
  std::vector<int> global;  // the particle of each (bond, coefficient) pair
  row.bond_offsets.assign(1, 0);
  row.coefficient.clear();
  for (int b = off[i]; b < off[i + 1]; ++b) {
    const int j = extended_families_.neighbors[b];
    if (j < n) {
      global.push_back(j), row.coefficient.push_back(1);
    } else {
      for (int s = images_.offsets[j - n]; s < images_.offsets[j - n + 1]; ++s)
        global.push_back(images_.particle[s]), row.coefficient.push_back(images_.weight[s]);
    }
    global.push_back(i), row.coefficient.push_back(-1);
    row.bond_offsets.push_back(static_cast<int>(global.size()));
  }
  row.touched = global;
  std::sort(row.touched.begin(), row.touched.end());
  row.touched.erase(std::unique(row.touched.begin(), row.touched.end()), row.touched.end());
  row.local.resize(global.size());
  for (std::size_t k = 0; k < global.size(); ++k)
    row.local[k] = static_cast<int>(
        std::lower_bound(row.touched.begin(), row.touched.end(), global[k]) - row.touched.begin());
}

SparseSymmetric SecondOrderModel::tangent_pattern(const Families&) const {
  const int n = particles_.count();
  // the rows touching each particle, then each particle's columns: the union of their touched
  std::vector<std::vector<int>> touched(n);
#pragma omp parallel
  {
    FoldedRow row;
#pragma omp for schedule(dynamic, 32)
    for (int i = 0; i < n; ++i) fold_row(i, row), touched[i] = row.touched;
  }
  std::vector<std::vector<int>> rows_of(n);
  for (int i = 0; i < n; ++i)
    for (int p : touched[i]) rows_of[p].push_back(i);
  std::vector<std::vector<int>> adjacency(n);
#pragma omp parallel
  {
    std::vector<char> seen(n, 0);
#pragma omp for schedule(dynamic, 32)
    for (int p = 0; p < n; ++p) {
      for (int i : rows_of[p])
        for (int q : touched[i])
          if (!seen[q]) seen[q] = 1, adjacency[p].push_back(q);
      for (int q : adjacency[p]) seen[q] = 0;
      std::sort(adjacency[p].begin(), adjacency[p].end());
    }
  }
  return expand_blocks(adjacency);
}

void SecondOrderModel::assemble_tangent(const double* y, SparseSymmetric& K, bool) {
  const int n = particles_.count();
  extended_positions(y, positions_);
  std::fill(K.values.begin(), K.values.end(), 0.0);
  std::vector<omp_lock_t> lock(n);
  for (omp_lock_t& l : lock) omp_init_lock(&l);
#pragma omp parallel
  {
    FoldedRow folded;
    Eigen::MatrixXd H, HP, PH, K_row;
    std::vector<double> d(3 * largest_row_);
    std::vector<int> position;  // of each touched particle's block in a row of K
#pragma omp for schedule(dynamic, 8)
    for (int i = 0; i < n; ++i) {
      const SecondOrderRow r = row(i);
      bond_vectors(i, positions_.data(), d.data());
      second_order_row_hessian(r, d.data(), H);
      fold_row(i, folded);
      const int u = static_cast<int>(folded.touched.size());
      position.resize(u);
      // H P, then Pᵀ(H P) = (H P)ᵀP (H symmetric): P has a coefficient times I₃ per (bond,
      // particle) pair, so both are sums of whole columns, contiguous in column-major storage
      HP.setZero(3 * r.bonds, 3 * u);
      for (int c = 0; c < r.bonds; ++c)
        for (int k = folded.bond_offsets[c]; k < folded.bond_offsets[c + 1]; ++k)
          HP.middleCols<3>(3 * folded.local[k]) += folded.coefficient[k] * H.middleCols<3>(3 * c);
      PH = HP.transpose();
      K_row.setZero(3 * u, 3 * u);
      for (int b = 0; b < r.bonds; ++b)
        for (int k = folded.bond_offsets[b]; k < folded.bond_offsets[b + 1]; ++k)
          K_row.middleCols<3>(3 * folded.local[k]) +=
              folded.coefficient[k] * PH.middleCols<3>(3 * b);
      // into K's rows, each particle's three under its own lock; touched and each row's
      // columns are sorted, so one pass along the row finds every block
      for (int p = 0; p < u; ++p) {
        const int row_p = 3 * folded.touched[p];
        int e = K.offsets[row_p];
        for (int q = 0; q < u; ++q) {
          while (K.columns[e] != 3 * folded.touched[q]) e += 3;
          position[q] = e - K.offsets[row_p];
        }
        omp_set_lock(&lock[folded.touched[p]]);
        for (int a = 0; a < 3; ++a) {
          double* values = K.values.data() + K.offsets[row_p + a];
          for (int q = 0; q < u; ++q)
            for (int c = 0; c < 3; ++c) values[position[q] + c] += K_row(3 * q + c, 3 * p + a);
        }
        omp_unset_lock(&lock[folded.touched[p]]);
      }
    }
  }
  for (omp_lock_t& l : lock) omp_destroy_lock(&l);
}

void SecondOrderModel::linearize(const double* y, bool) { extended_positions(y, linearized_at_); }

void SecondOrderModel::apply_tangent(const double* v, double* out) const {
  const int n = particles_.count();
  std::fill(out, out + 3 * n, 0.0);
#pragma omp parallel
  {
    FoldedRow folded;
    Eigen::MatrixXd H;
    Eigen::VectorXd Pv, HPv;
    std::vector<double> d(3 * largest_row_), local(3 * static_cast<std::size_t>(n), 0.0);
#pragma omp for schedule(dynamic, 16)
    for (int i = 0; i < n; ++i) {
      const SecondOrderRow r = row(i);
      bond_vectors(i, linearized_at_.data(), d.data());
      second_order_row_hessian(r, d.data(), H);
      fold_row(i, folded);
      Pv.setZero(3 * r.bonds);
      for (int b = 0; b < r.bonds; ++b)
        for (int k = folded.bond_offsets[b]; k < folded.bond_offsets[b + 1]; ++k)
          for (int a = 0; a < 3; ++a)
            Pv(3 * b + a) += folded.coefficient[k] * v[3 * folded.touched[folded.local[k]] + a];
      HPv.noalias() = H * Pv;
      for (int b = 0; b < r.bonds; ++b)
        for (int k = folded.bond_offsets[b]; k < folded.bond_offsets[b + 1]; ++k)
          for (int a = 0; a < 3; ++a)
            local[3 * folded.touched[folded.local[k]] + a] +=
                folded.coefficient[k] * HPv(3 * b + a);
    }
#pragma omp critical(second_order_product)
    for (int k = 0; k < 3 * n; ++k) out[k] += local[k];
  }
}

void SecondOrderModel::assemble_majoriser(const double*, SparseSymmetric&) {
  throw std::logic_error("the second-order model has no bond-wise majoriser");
}

void SecondOrderModel::assemble_nearest_stiffness(const double*, const std::vector<char>&,
                                                  SparseSymmetric&) {
  throw std::logic_error("the second-order model has no nearest members' stiffness");
}

void SecondOrderModel::assemble_scalar_stiffness(SparseSymmetric&) const {
  throw std::logic_error("the second-order model has no scalar stiffness");
}

}  // namespace fissure
