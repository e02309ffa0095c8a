#include "integrators/implicit_scheme.hpp"

namespace fissure {

ImplicitScheme::ImplicitScheme(const std::string& scheme, double rho_infinity) {
  if (scheme == "backward_euler") {
    kind_ = Kind::backward_euler;
  } else if (scheme == "static") {
    kind_ = Kind::static_equilibrium;
  } else {
    kind_ = Kind::newmark_alpha;
    if (scheme == "alpha") {
      const double r = rho_infinity;  // Chung & Hulbert (1993), Eqs 25 and 17
      alpha_m_ = (2 * r - 1) / (r + 1);
      alpha_f_ = r / (r + 1);
      gamma_ = 0.5 - alpha_m_ + alpha_f_;
      beta_ = 0.25 * (1 - alpha_m_ + alpha_f_) * (1 - alpha_m_ + alpha_f_);
    }
  }
}

void ImplicitScheme::predict(const State& state, const std::vector<double>& acceleration, double c,
                             double h) {
  const std::size_t n = state.position.size();
  target_.resize(n);
  const double* y = state.position.data();
  const double* v = state.velocity.data();
  const double* a = acceleration.data();
  switch (kind_) {
    case Kind::static_equilibrium:
      inertia_ = 0;
      for (std::size_t k = 0; k < n; ++k) target_[k] = y[k];
      return;
    case Kind::backward_euler:
      // M (v_{n+1} − v_n)/h = F + f − c M v_{n+1},  v_{n+1} = (z − y_n)/h
      inertia_ = (1 + c * h) / (h * h);
      for (std::size_t k = 0; k < n; ++k) target_[k] = y[k] + h * v[k] / (1 + c * h);
      return;
    case Kind::newmark_alpha: {
      // M a_{n+1−α_m} + c M v_{n+1−α_f} = F(z) + f with z = y_{n+1−α_f}, and Newmark's
      // y_{n+1} = y_n + h v_n + h²((½ − β) a_n + β a_{n+1}), v_{n+1} = v_n + h((1 − γ) a_n + γ
      // a_{n+1}). The left side is affine in z, A z + k, so ỹ = −k/A with k its value at z = 0.
      const double b = beta_ * h * h;
      inertia_ = (1 - alpha_m_) / (b * (1 - alpha_f_)) + c * gamma_ / (beta_ * h);
#pragma omp parallel for schedule(static)
      for (std::size_t k = 0; k < n; ++k) {
        const double y1 = y[k] - y[k] / (1 - alpha_f_);  // y_{n+1} at z = 0
        const double a1 = (y1 - y[k] - h * v[k] - h * h * (0.5 - beta_) * a[k]) / b;
        const double v1 = v[k] + h * ((1 - gamma_) * a[k] + gamma_ * a1);
        const double at_zero =
            (1 - alpha_m_) * a1 + alpha_m_ * a[k] + c * ((1 - alpha_f_) * v1 + alpha_f_ * v[k]);
        target_[k] = -at_zero / inertia_;
      }
      return;
    }
  }
}

std::vector<double> ImplicitScheme::guess(const State& state, double h) const {
  std::vector<double> z(state.position.size());
  const double step = kind_ == Kind::static_equilibrium ? 0.0 : (1 - alpha_f_) * h;
  for (std::size_t k = 0; k < z.size(); ++k) z[k] = state.position[k] + step * state.velocity[k];
  return z;
}

void ImplicitScheme::correct(const std::vector<double>& z, State& state,
                             std::vector<double>& acceleration, double h) const {
  const std::size_t n = z.size();
  double* y = state.position.data();
  double* v = state.velocity.data();
  double* a = acceleration.data();
  switch (kind_) {
    case Kind::static_equilibrium:
      // Inertia is ignored: the body is at rest in each equilibrium.
      for (std::size_t k = 0; k < n; ++k) y[k] = z[k], v[k] = 0, a[k] = 0;
      return;
    case Kind::backward_euler:
#pragma omp parallel for schedule(static)
      for (std::size_t k = 0; k < n; ++k) {
        const double v1 = (z[k] - y[k]) / h;
        a[k] = (v1 - v[k]) / h;
        v[k] = v1;
        y[k] = z[k];
      }
      return;
    case Kind::newmark_alpha: {
      const double b = beta_ * h * h;
#pragma omp parallel for schedule(static)
      for (std::size_t k = 0; k < n; ++k) {
        const double y1 = y[k] + (z[k] - y[k]) / (1 - alpha_f_);
        const double a1 = (y1 - y[k] - h * v[k] - h * h * (0.5 - beta_) * a[k]) / b;
        v[k] += h * ((1 - gamma_) * a[k] + gamma_ * a1);
        a[k] = a1;
        y[k] = y1;
      }
      return;
    }
  }
}

}  // namespace fissure
