// Mass-proportional damping (config damping: c): the acceleration −c v on every particle, stiff
// (implicit integrators take it into their equations through Dynamics::damping()). It takes
// 2cK per unit time out of the particles: the ledger books h · 2c K(end of step).
#include "integrators/load_registry.hpp"

namespace fissure {

namespace {

class DampingLoad : public Load {
 public:
  DampingLoad(double c, std::size_t count) : c_(c), count_(count) {}
  Form form() const override { return Form::acceleration; }
  bool stiff() const override { return true; }
  bool scheme_coefficient() const override { return true; }
  void add(double, const double*, const double* v, double* a) override {
    const int n = static_cast<int>(count_);
#pragma omp parallel for schedule(static)
    for (int k = 0; k < n; ++k) a[k] -= c_ * v[k];
  }
  double booked(const BookedStep& step) const override {
    return c_ > 0 ? step.h * 2.0 * c_ * step.kinetic() : 0.0;
  }

 private:
  double c_;
  std::size_t count_;  // 3N
};

}  // namespace

std::unique_ptr<Load> make_damping_load(const Scene& scene) {
  // Present with c = 0 too, as a − 0·v: the accelerations keep their bits (a NaN velocity stays
  // NaN in them).
  return std::make_unique<DampingLoad>(scene.config.damping, 3 * scene.particles.mass.size());
}

}  // namespace fissure
