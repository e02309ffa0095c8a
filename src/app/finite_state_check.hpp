#pragma once
// Stops the run (status nonfinite) at the first step that leaves a position or velocity that is
// not finite, naming the particle, its body and reference position. The first check of the run
// loop (app/observer.hpp).
#include "app/observer.hpp"

namespace fissure {

class FiniteStateCheck : public Observer {
 public:
  std::string name() const override { return "finite_state"; }
  void after_step(const RunParts& run, const Step& step) override;
};

}  // namespace fissure
