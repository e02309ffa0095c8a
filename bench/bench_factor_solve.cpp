// What one back-solve with the tangent's factor costs, and what it costs in accuracy: the glass
// cantilever of bench_implicit_step sampled with about N particles, its two-hop tangent at rest
// shifted by A M for an SDIRK4 stage at `factor` times the explicit stable estimate, factorized
// once, then solved `solves` times for a random right-hand side by:
//   cholmod:        CHOLMOD's own solve (double, one thread; what PETSc's PC called before);
//   double, single, half: SupernodalCholesky in that precision, on 1 thread and on all threads.
// Prints one line per solver: seconds per solve, the ratio to cholmod's, the bytes the factor
// holds, and the solution's relative error against cholmod's (docs/accuracy.md).
//   bench_factor_solve [particles] [solves] [factor]
#include <fmt/format.h>
#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <random>
#include <string>

#include "linear/cholmod_factor.hpp"
#include "linear/shifted_system.hpp"
#include "linear/supernodal_cholesky.hpp"
#include "model/model.hpp"
#include "model/stiffness.hpp"
#include "scene/scene.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

double relative_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0, n = 0;
  for (std::size_t k = 0; k < a.size(); ++k) d += (a[k] - b[k]) * (a[k] - b[k]), n += b[k] * b[k];
  return std::sqrt(d / n);
}

}  // namespace

int main(int argc, char** argv) {
  const double target = argc > 1 ? std::atof(argv[1]) : 1.0e3;
  const int solves = argc > 2 ? std::atoi(argv[2]) : 50;
  const double factor = argc > 3 ? std::atof(argv[3]) : 350;
  // TetGen gives about 14.8 tets per λ³ at its quality settings; the bar is 0.01 m³.
  const double lambda = std::cbrt(14.8 * 0.01 / target);
  const std::string yaml = fmt::format(
      "time: {{end: 1.0}}\nbodies:\n  - geometry: {{box: {{min: [0, 0, 0], max: [1.0, 0.1, "
      "0.1]}}}}\n    resolution: {0}\n    horizon: 1.45\n    material: {{model: lps, density: "
      "2200, bulk_modulus: 3.3e10, shear_modulus: 2.0e10}}\nconstraints:\n  - {{region: {{box: "
      "{{min: [-1, -1, -1], max: [{1}, 1, 1]}}}}, fix: true}}\n",
      lambda, 0.6 * lambda);
  const fissure::Config config = fissure::parse_config(yaml, "bench_factor_solve.yaml");
  const fissure::Scene scene = fissure::build_scene(config);
  auto model = fissure::make_model(scene);
  const int n = scene.particles.count();
  // SDIRK4's diagonal coefficient is 1/4: the stage matrix is M / (h/4)² + K.
  const double h = factor * model->stable_time_step();
  const double inertia = 16 / (h * h);
  fissure::SparseSymmetric a = fissure::two_hop_pattern(scene.families);
  model->stiffness()->assemble_tangent(scene.particles.reference.data(), a, false);
  std::vector<double> mass(3 * n);
  std::vector<char> fixed(3 * n, 0);
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) mass[3 * i + d] = scene.particles.mass[i];
  for (int i = 0; i < n; ++i)
    if (scene.particles.reference[3 * i] < 0.6 * lambda)
      fixed[3 * i] = fixed[3 * i + 1] = fixed[3 * i + 2] = 1;
  fissure::shift_and_fix(a, fissure::diagonal_positions(a), mass, inertia, fixed);

  std::mt19937 random(7);
  std::normal_distribution<double> normal;
  std::vector<double> b(3 * n), reference(3 * n), x(3 * n);
  for (double& v : b) v = normal(random);
  fmt::print("particles {}\nunknowns {}\nmatrix_entries {}\ndt {:.4g}\nthreads {}\n", n, 3 * n,
             a.values.size(), h, omp_get_max_threads());
  fmt::print("{:<10} {:>8} {:>14} {:>10} {:>12} {:>12} {:>10}\n", "solver", "threads",
             "factorize_s", "solve_ms", "vs_cholmod", "factor_mb", "rel_error");

  fissure::CholmodFactor cholmod;
  auto start = Clock::now();
  cholmod.factorize(a);
  const double cholmod_factorize = seconds_since(start);
  start = Clock::now();
  for (int k = 0; k < solves; ++k) cholmod.solve(b.data(), reference.data());
  const double cholmod_solve = seconds_since(start) / solves;
  fmt::print("{:<10} {:>8} {:>14.3f} {:>10.3f} {:>12.2f} {:>12} {:>10}\n", "cholmod", 1,
             cholmod_factorize, 1e3 * cholmod_solve, 1.0, "-", "0");

  const int all = omp_get_max_threads();
  for (auto precision : {fissure::FactorPrecision::full, fissure::FactorPrecision::single,
                         fissure::FactorPrecision::half}) {
    for (int threads : {1, all}) {
      omp_set_num_threads(threads);
      fissure::SupernodalCholesky factor_of_a(precision, 0);  // threaded whatever its size
      start = Clock::now();
      if (!factor_of_a.factorize(a)) {
        fmt::print(stderr, "the stage matrix is not positive definite\n");
        return 1;
      }
      const double factorize = seconds_since(start);
      start = Clock::now();
      for (int k = 0; k < solves; ++k) factor_of_a.solve(b.data(), x.data());
      const double solve = seconds_since(start) / solves;
      fmt::print("{:<10} {:>8} {:>14.3f} {:>10.3f} {:>12.2f} {:>12.1f} {:>10.2e}\n",
                 fissure::factor_precision_name(factor_of_a.precision()), factor_of_a.threads(),
                 factorize, 1e3 * solve, solve / cholmod_solve, factor_of_a.solve_bytes() / 2 / 1e6,
                 relative_difference(x, reference));
    }
  }
  omp_set_num_threads(all);
  return 0;
}
