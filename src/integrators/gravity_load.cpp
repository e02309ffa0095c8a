// Gravity: the acceleration g on every particle; its work over a step is exact, Σ m g·Δy = −ΔU.
#include "integrators/load_registry.hpp"

namespace fissure {

namespace {

class GravityLoad : public Load {
 public:
  explicit GravityLoad(const Scene& scene)
      : mass_(scene.particles.mass), g_(scene.config.gravity) {}
  Form form() const override { return Form::acceleration; }
  void add(double, const double*, const double*, double* a) override {
    const int n = static_cast<int>(mass_.size());
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) a[3 * i + k] += g_[k];
  }
  double booked(const BookedStep& step) const override {
    if (g_[0] == 0 && g_[1] == 0 && g_[2] == 0) return 0;
    const int n = static_cast<int>(mass_.size());
    double sum = 0;
#pragma omp parallel for reduction(+ : sum) schedule(static)
    for (int i = 0; i < n; ++i)
      for (int d = 0; d < 3; ++d)
        sum += mass_[i] * g_[d] * (step.after[3 * i + d] - step.before[3 * i + d]);
    return sum;
  }

 private:
  const std::vector<double>& mass_;  // the scene's, which outlives the dynamics
  Vec3 g_;
};

}  // namespace

std::unique_ptr<Load> make_gravity_load(const Scene& scene) {
  return std::make_unique<GravityLoad>(scene);
}

}  // namespace fissure
