// Self-contact (contact.self, contact/self_contact.hpp) as a load: the repulsion between unbonded
// particles. The ledger books its negative work over each step by the trapezoidal rule,
// −½ (F(y_n) + F(y_{n+1}))·Δy, as a loss: the energy stored in the penalty while particles press
// together (exact for a pair that stays in contact through the step, whatever the step's size).
// Implicit integrators take it as a potential of the positions (LoadPotential), evaluated at
// every iterate.
#include <cstring>

#include "contact/self_contact.hpp"
#include "integrators/force_sums.hpp"
#include "integrators/load_registry.hpp"

namespace fissure {

namespace {

class SelfContactLoad : public Load, public LoadPotential {
 public:
  SelfContactLoad(const Scene& scene, const Model& model)
      : model_(model), contact_(scene, model), force_(3 * scene.particles.mass.size()) {}
  void add(double, const double* y, const double*, double* f) override {
    force_at(y);
    add_to(force_, f);
  }
  double booked(const BookedStep& step) const override {
    // F(y_n): the previous step's F(y_{n+1}) where nothing changed since (bonds broke between
    // the steps, or a resumed run's first step: computed afresh)
    const std::size_t n = force_.size();
    if (start_revision_ != model_.revision() || start_point_.size() != n ||
        std::memcmp(start_point_.data(), step.before, n * sizeof(double)) != 0) {
      force_at(step.before);
      start_force_ = force_;
    }
    force_at(step.after);
    double sum = 0;
#pragma omp parallel for reduction(+ : sum) schedule(static)
    for (std::size_t k = 0; k < n; ++k)
      sum += (start_force_[k] + force_[k]) * (step.after[k] - step.before[k]);
    // F(y_{n+1}) becomes the next step's F(y_n); force_ then holds no point
    std::swap(start_force_, force_);
    std::swap(start_point_, point_);
    start_revision_ = revision_;
    point_.clear();
    return -0.5 * sum;
  }
  std::string not_distributable() const override { return "contact.self"; }

  LoadPotential* potential() override { return this; }
  void begin_stage(const PotentialStage&) override {}
  double evaluate(const double* z, double* gradient, double* blocks) override {
    if (!gradient) return contact_.potential(z, nullptr, blocks);
    std::fill(force_.begin(), force_.end(), 0.0);  // ∇B, then the force −∇B
    const double energy = contact_.potential(z, force_.data(), blocks);
    add_to(force_, gradient);
    for (double& f : force_) f = -f;
    keep_point(z);
    return energy;
  }
  void add_coupling(const double* z, const double* v, double* out) const override {
    contact_.add_coupling(z, v, out);
  }
  bool couples() const override { return true; }
  double max_step(const double*, const double* dz) const override { return contact_.max_step(dz); }
  bool contact() const override { return true; }

 private:
  // force_ = F(y), unless it already holds it (y the point it was computed at, the bonds the
  // same).
  void force_at(const double* y) const {
    const std::size_t n = force_.size();
    if (revision_ == model_.revision() && point_.size() == n &&
        std::memcmp(point_.data(), y, n * sizeof(double)) == 0)
      return;
    std::fill(force_.begin(), force_.end(), 0.0);
    contact_.add_forces(y, force_.data());
    keep_point(y);
  }
  void keep_point(const double* y) const {
    point_.assign(y, y + force_.size());
    revision_ = model_.revision();
  }

  const Model& model_;
  mutable SelfContact contact_;  // its Verlet list follows the points the ledger asks about
  // F at point_ with the bonds of the model's revision_, and F(y_n) for the step being booked
  mutable std::vector<double> force_, point_, start_force_, start_point_;
  mutable std::size_t revision_ = 0, start_revision_ = 0;
};

}  // namespace

std::unique_ptr<Load> make_self_contact_load(const Scene& scene, const Model& model) {
  if (!scene.config.contact.self) return nullptr;
  return std::make_unique<SelfContactLoad>(scene, model);
}

}  // namespace fissure
