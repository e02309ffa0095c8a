#pragma once
// The LPS elastic force kernel with no effect code at all, for an isotropic, unbreakable, purely
// elastic block: the model's row passes (model/lps_rows.hpp) with no plasticity template
// parameter, no plastic arrays and no anisotropic influence function, so that bench_effects can
// show what the effect machinery costs the elastic kernel; and the same forces summed in bond
// order, as the kernel summed them before its eight-lane rows, to show how far those moved.
#include <vector>

#include "model/lps_rows.hpp"
#include "scene/scene.hpp"

namespace fissure::bench {

class PureElasticKernel {
 public:
  explicit PureElasticKernel(const Scene& scene);
  void forces(const double* y, double* f);
  void sequential_forces(const double* y, double* f);

 private:
  using NeighbourTerms = lps::NeighbourTerms;
  void set_terms(int i, double theta, double moment);
  const Families& families_;
  std::vector<double> bulk_modulus_, weighted_volume_, volume_;
  std::vector<float> omega_, weight_, reverse_weight_;
  std::vector<NeighbourTerms> terms_;
  lps::RowKernels kernels_ = lps::row_kernels();
};

}  // namespace fissure::bench
