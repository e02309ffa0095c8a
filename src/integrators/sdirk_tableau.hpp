#pragma once
// Butcher tableaux of the singly diagonally implicit Runge–Kutta schemes petsc_newton offers:
// every diagonal entry is γ, so every stage's Newton matrix is M/(γh)² + K; an ESDIRK's first
// stage is explicit (a_11 = 0): Y_1 = y_n, with no Newton solve.
#include <string>
#include <vector>

namespace fissure {

struct SdirkTableau {
  std::string name;
  int stages;
  int order;
  double gamma;           // a_ii
  std::vector<double> a;  // stages × stages, row major, lower triangular
  std::vector<double> b;  // weights
  bool stiffly_accurate;  // b is the last row of a: y_{n+1} is the last stage
  // Weights of an embedded scheme one order lower (empty if the tableau has none): h Σ (b_i −
  // b̂_i) k_i estimates the step's local error.
  std::vector<double> b_embedded = {};
  bool explicit_stage(int i) const { return a[i * stages + i] == 0; }
  double c(int i) const {  // Σ_j a_ij
    double s = 0;
    for (int j = 0; j < stages; ++j) s += a[i * stages + j];
    return s;
  }
};

// sdirk3: Alexander (1977), 3 stages, order 3, L-stable. sdirk4: Hairer & Wanner, Solving ODEs
// II, Table IV.6.5, 5 stages, order 4, L-stable. esdirk4: Kennedy & Carpenter (2003), the same
// stability function as sdirk4 from an explicit and five implicit stages, with weights of at
// most 0.69 in size where sdirk4's reach 7.8: a stage's Newton error is carried into the step
// far less amplified (docs/integrators.md).
const SdirkTableau& sdirk3_tableau();
const SdirkTableau& sdirk4_tableau();
const SdirkTableau& esdirk4_tableau();

}  // namespace fissure
