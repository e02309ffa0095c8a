// Self-contact (contact.self, contact/self_contact.hpp) as a load: the repulsion between unbonded
// particles. The ledger books its negative work, −Σ F·Δy, as a loss: the energy stored in the
// penalty while particles press together.
#include "contact/self_contact.hpp"
#include "integrators/force_sums.hpp"
#include "integrators/load_registry.hpp"

namespace fissure {

namespace {

class SelfContactLoad : public Load {
 public:
  SelfContactLoad(const Scene& scene, const Model& model)
      : contact_(scene, model), force_(3 * scene.particles.mass.size()) {}
  void add(double, const double* y, const double*, double* f) override {
    std::fill(force_.begin(), force_.end(), 0.0);
    contact_.add_forces(y, force_.data());
    add_to(force_, f);
  }
  double booked(const BookedStep& step) const override {
    return -work_of(force_, step.before, step.after);
  }
  std::string not_distributable() const override { return "contact.self"; }

 private:
  SelfContact contact_;
  std::vector<double> force_;  // 3N, at the last add()
};

}  // namespace

std::unique_ptr<Load> make_self_contact_load(const Scene& scene, const Model& model) {
  if (!scene.config.contact.self) return nullptr;
  return std::make_unique<SelfContactLoad>(scene, model);
}

}  // namespace fissure
