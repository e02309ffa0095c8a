#include "app/observer.hpp"

#include <fmt/format.h>

#include "app/energy.hpp"
#include "core/error.hpp"

namespace fissure {

double Step::kinetic() const {
  if (!kinetic_) kinetic_ = run_.ranks.sum(own_kinetic());
  return *kinetic_;
}

double Step::own_kinetic() const {
  if (!own_kinetic_)
    own_kinetic_ = kinetic_energy(run_.scene.particles.mass, run_.state.velocity,
                                  run_.ranks.begin(), run_.ranks.end());
  return *own_kinetic_;
}

const std::vector<double>& saved_array(const NamedArrays& state, const std::string& name) {
  const std::vector<double>* values = find_array(state, name);
  if (!values) throw InputError("", name, "missing from the checkpoint");
  return *values;
}

double saved_number(const NamedArrays& state, const std::string& name) {
  const std::vector<double>& values = saved_array(state, name);
  if (values.size() != 1)
    throw InputError("", name, fmt::format("expected 1 number, got {}", values.size()));
  return values[0];
}

}  // namespace fissure
