#pragma once
// An optional capability of a model (Model::plastic_flow()): plastic extensions e^p per bond
// (paper §4.2), present only when the scene asks for plasticity.
#include <cstddef>
#include <vector>

namespace fissure {

class PlasticFlow {
 public:
  virtual ~PlasticFlow() = default;
  // The return map the post-step runs after a completed step at positions y; returns how many
  // bonds yielded.
  virtual std::size_t update_plasticity(const double* y) = 0;
  // e^p per directed bond.
  virtual const std::vector<double>& plastic_extension() const = 0;
};

}  // namespace fissure
