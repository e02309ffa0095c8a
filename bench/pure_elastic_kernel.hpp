#pragma once
// The LPS elastic force kernel with no effect code at all: a copy of LpsModel's two passes
// (dilatation, then forces) for an isotropic, unbreakable, purely elastic block, with no
// plasticity template parameter, no plastic arrays and no anisotropic influence function.
// It exists only so bench_effects can show what the effect machinery costs the elastic kernel.
#include <vector>

#include "scene/scene.hpp"

namespace fissure::bench {

class PureElasticKernel {
 public:
  explicit PureElasticKernel(const Scene& scene);
  void forces(const double* y, double* f);

 private:
  struct NeighbourTerms {
    double pressure, deviatoric, shift, volume;
  };
  const Families& families_;
  std::vector<double> bulk_modulus_, weighted_volume_;
  std::vector<float> omega_, weight_, reverse_weight_;
  std::vector<NeighbourTerms> terms_;
};

}  // namespace fissure::bench
