// An independent reference for the cantilever of the verification tests (tests/support/beam.hpp):
// its static deflection under gravity by linear elasticity in 3D, with quadratic
// (10-node) tetrahedra, against Timoshenko's beam theory, which the tests compare to.
// The 1.0 × 0.1 × 0.1 m box is cut into nx × n × n cubes (nx = 10 n), each into the 6 tets
// around its main diagonal (Kuhn), so the mesh conforms and every quadratic node lies on the
// grid of half the cube edge. The face x = 0 is held (the particles' clamp holds the block
// behind it). Stiffness by the 4-point rule (exact for the quadratic integrand), the load by
// the element's exact ∫N ρg, the solve by CHOLMOD. Prints per refinement the mean vertical
// displacement of the end face x = L over Timoshenko's (bending plus Cowper's shear term),
// and the same at x = L − λ/2 for λ = b/4 (the tests' finest tip band's mean x).
//   bench_fem_cantilever [n, e.g. 2,4,8]
#include <fmt/format.h>

#include <Eigen/CholmodSupport>
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <array>
#include <chrono>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "support/beam.hpp"

namespace {

using namespace fissure;
using test::Cantilever;

// The Kuhn tets of the unit cube: for each order of the axes, the path from (0,0,0) to (1,1,1).
std::vector<std::array<std::array<int, 3>, 4>> kuhn_tets() {
  std::vector<std::array<std::array<int, 3>, 4>> tets;
  const int orders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (const auto& order : orders) {
    std::array<std::array<int, 3>, 4> t;
    std::array<int, 3> corner = {0, 0, 0};
    t[0] = corner;
    for (int k = 0; k < 3; ++k) corner[order[k]] = 1, t[k + 1] = corner;
    tets.push_back(t);
  }
  return tets;
}

struct Result {
  int dofs;
  double end_ratio, band_ratio, beyond_clamp_ratio;
};

double timoshenko(double x) { return test::timoshenko_deflection(9.81, x); }

Result solve(int n) {
  const int nx = 10 * n, ny = n, nz = n;
  const int Nx = 2 * nx + 1, Ny = 2 * ny + 1, Nz = 2 * nz + 1;  // quadratic node grid
  const double h[3] = {Cantilever::length / (2 * nx), Cantilever::side / (2 * ny),
                       Cantilever::side / (2 * nz)};
  auto node = [&](int i, int j, int k) { return (i * Ny + j) * Nz + k; };
  const int nodes = Nx * Ny * Nz;
  std::vector<int> dof(nodes, -1);
  int dofs = 0;
  for (int i = 1; i < Nx; ++i)  // i = 0: the held face
    for (int j = 0; j < Ny; ++j)
      for (int k = 0; k < Nz; ++k) dof[node(i, j, k)] = dofs, dofs += 3;

  const double mu = Cantilever::shear, lame = Cantilever::bulk - 2 * mu / 3;
  Eigen::Matrix<double, 6, 6> D = Eigen::Matrix<double, 6, 6>::Zero();
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) D(a, b) = lame;
    D(a, a) += 2 * mu, D(a + 3, a + 3) = mu;
  }
  const double qa = 0.5854101966249685, qb = 0.1381966011250105;  // 4-point rule, degree 2
  const double weight_g = -Cantilever::density * 9.81;
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::VectorXd load = Eigen::VectorXd::Zero(dofs);
  const auto tets = kuhn_tets();
  const int edges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (int ci = 0; ci < nx; ++ci)
    for (int cj = 0; cj < ny; ++cj)
      for (int ck = 0; ck < nz; ++ck)
        for (const auto& t : tets) {
          // the 10 nodes on the doubled grid: corners, then edge midpoints
          std::array<std::array<int, 3>, 10> g;
          for (int v = 0; v < 4; ++v)
            g[v] = {2 * (ci + t[v][0]), 2 * (cj + t[v][1]), 2 * (ck + t[v][2])};
          for (int e = 0; e < 6; ++e)
            for (int a = 0; a < 3; ++a) g[4 + e][a] = (g[edges[e][0]][a] + g[edges[e][1]][a]) / 2;
          Eigen::Matrix<double, 4, 4> X;  // rows (1, x, y, z) per corner
          for (int v = 0; v < 4; ++v) X.col(v) << 1, g[v][0] * h[0], g[v][1] * h[1], g[v][2] * h[2];
          const double volume = std::abs(X.determinant()) / 6;
          const Eigen::Matrix<double, 4, 4> inverse = X.inverse();  // row v: (c, ∇L_v)
          Eigen::Matrix<double, 30, 30> K = Eigen::Matrix<double, 30, 30>::Zero();
          for (int q = 0; q < 4; ++q) {
            double L[4];
            for (int v = 0; v < 4; ++v) L[v] = v == q ? qa : qb;
            Eigen::Matrix<double, 3, 10> grad;  // ∇N of the 10 shape functions
            for (int v = 0; v < 4; ++v)
              grad.col(v) = (4 * L[v] - 1) * inverse.row(v).tail<3>().transpose();
            for (int e = 0; e < 6; ++e) {
              const int a = edges[e][0], b = edges[e][1];
              grad.col(4 + e) =
                  4 *
                  (L[b] * inverse.row(a).tail<3>() + L[a] * inverse.row(b).tail<3>()).transpose();
            }
            Eigen::Matrix<double, 6, 30> B = Eigen::Matrix<double, 6, 30>::Zero();
            for (int s = 0; s < 10; ++s) {
              for (int a = 0; a < 3; ++a) B(a, 3 * s + a) = grad(a, s);
              B(3, 3 * s + 1) = grad(2, s), B(3, 3 * s + 2) = grad(1, s);  // γ_yz
              B(4, 3 * s + 0) = grad(2, s), B(4, 3 * s + 2) = grad(0, s);  // γ_xz
              B(5, 3 * s + 0) = grad(1, s), B(5, 3 * s + 1) = grad(0, s);  // γ_xy
            }
            K.noalias() += volume / 4 * B.transpose() * D * B;
          }
          int index[10];
          for (int s = 0; s < 10; ++s) index[s] = dof[node(g[s][0], g[s][1], g[s][2])];
          for (int s = 0; s < 10; ++s) {
            if (index[s] < 0) continue;
            load(index[s] + 2) += weight_g * volume * (s < 4 ? -1.0 / 20 : 1.0 / 5);  // ∫N ρg
            for (int r = 0; r < 10; ++r)
              if (index[r] >= 0)
                for (int a = 0; a < 3; ++a)
                  for (int b = 0; b < 3; ++b)
                    triplets.emplace_back(index[s] + a, index[r] + b, K(3 * s + a, 3 * r + b));
          }
        }
  Eigen::SparseMatrix<double> K(dofs, dofs);
  K.setFromTriplets(triplets.begin(), triplets.end());
  triplets.clear();
  triplets.shrink_to_fit();
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>> cholesky(K);
  if (cholesky.info() != Eigen::Success)
    throw std::runtime_error("CHOLMOD failed on the FEM stiffness");
  const Eigen::VectorXd u = cholesky.solve(load);

  // mean vertical displacement of the cross-section of doubled-grid column i
  auto mean_w = [&](int i) {
    double sum = 0;
    for (int j = 0; j < Ny; ++j)
      for (int k = 0; k < Nz; ++k) sum -= u(dof[node(i, j, k)] + 2);
    return sum / (Ny * Nz);
  };
  const double band_x = Cantilever::length - Cantilever::side / 8;  // L − λ/2, λ = b/4
  const double column = band_x / h[0];
  const int i0 = static_cast<int>(std::floor(column));
  const double t = column - i0;
  const double band_w = (1 - t) * mean_w(i0) + t * mean_w(std::min(i0 + 1, Nx - 1));
  std::vector<double> xs, ws;
  for (int i = 1; i < Nx; ++i) xs.push_back(i * h[0]), ws.push_back(mean_w(i));
  return {dofs, mean_w(Nx - 1) / timoshenko(Cantilever::length), band_w / timoshenko(band_x),
          test::deflection_over_theory_beyond_clamp(xs, ws, timoshenko, 0.25, 0.9)};
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> refinements = {2, 4, 8};
  if (argc > 1) {
    refinements.clear();
    std::stringstream list(argv[1]);
    for (std::string item; std::getline(list, item, ',');) refinements.push_back(std::stoi(item));
  }
  fmt::print(
      "cubes_through_thickness  dofs  end_w_over_timoshenko  band_w_over_timoshenko  "
      "beyond_clamp_over_timoshenko  seconds\n");
  for (int n : refinements) {
    const auto start = std::chrono::steady_clock::now();
    const Result r = solve(n);
    fmt::print("{:23d}  {:7d}  {:21.5f}  {:22.5f}  {:28.5f}  {:7.1f}\n", n, r.dofs, r.end_ratio,
               r.band_ratio, r.beyond_clamp_ratio,
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    std::fflush(stdout);
  }
}
