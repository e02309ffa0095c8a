#include "integrators/implicit_scheme.hpp"

#include <algorithm>

namespace fissure {

ImplicitScheme::ImplicitScheme(Scheme scheme, double rho_infinity) {
  switch (scheme) {
    case Scheme::backward_euler:
      kind_ = Kind::backward_euler;
      return;
    case Scheme::static_equilibrium:
      kind_ = Kind::static_equilibrium;
      return;
    case Scheme::sdirk3:
    case Scheme::sdirk4:
    case Scheme::esdirk4:
      kind_ = Kind::sdirk;
      tableau_ = sdirk_tableau(scheme);
      return;
    case Scheme::alpha: {
      const double r = rho_infinity;  // Chung & Hulbert (1993), Eqs 25 and 17
      alpha_m_ = (2 * r - 1) / (r + 1);
      alpha_f_ = r / (r + 1);
      gamma_ = 0.5 - alpha_m_ + alpha_f_;
      beta_ = 0.25 * (1 - alpha_m_ + alpha_f_) * (1 - alpha_m_ + alpha_f_);
      break;
    }
    case Scheme::newmark:
      break;
  }
  kind_ = Kind::newmark_alpha;
  held_fraction_ = 1 - alpha_f_;
}

void ImplicitScheme::predict(const State& state, const std::vector<double>& acceleration, double c,
                             double h, int stage) {
  const std::size_t n = state.position.size();
  target_.resize(n);
  const double* y = state.position.data();
  const double* v = state.velocity.data();
  const double* a = acceleration.data();
  potential_weight_ = 1;
  switch (kind_) {
    case Kind::static_equilibrium:
      inertia_ = 0;
      for (std::size_t k = 0; k < n; ++k) target_[k] = y[k];
      return;
    case Kind::sdirk: {
      // Stage i of y' = v, v' = M⁻¹(F + f) − c v: Y_i = Ŷ_i + γh V_i, V_i = V̂_i + γh V'_i with
      // Ŷ_i = y_n + h Σ_{j<i} a_ij V_j, V̂_i = v_n + h Σ_{j<i} a_ij V'_j. Eliminating V_i,
      // A M (Y_i − ỹ) = F(Y_i) + f with A = (1 + γhc)/(γh)², ỹ = Ŷ_i + γh V̂_i / (1 + γhc).
      const SdirkTableau& t = *tableau_;
      stage_ = stage;
      if (stage == 0) {
        stage_velocity_.assign(t.stages, std::vector<double>(n));
        stage_acceleration_.assign(t.stages, std::vector<double>(n));
      }
      if (t.explicit_stage(stage)) {
        // An ESDIRK's first stage: Y_1 = y_n, V_1 = v_n, V'_1 = a_n; no minimisation.
        stage_velocity_[stage].assign(v, v + n);
        stage_acceleration_[stage].assign(a, a + n);
        return;
      }
      explicit_position_.assign(y, y + n);
      explicit_velocity_.assign(v, v + n);
      for (int j = 0; j < stage; ++j) {
        const double w = h * t.a[stage * t.stages + j];
        const double* vj = stage_velocity_[j].data();
        const double* aj = stage_acceleration_[j].data();
#pragma omp parallel for schedule(static)
        for (std::size_t k = 0; k < n; ++k) {
          explicit_position_[k] += w * vj[k];
          explicit_velocity_[k] += w * aj[k];
        }
      }
      const double gh = t.gamma * h;
      // B's share of the explicit first stage, h a_i1 V'_1, taken at this stage's end point
      if (t.explicit_stage(0)) potential_weight_ = (t.gamma + t.a[stage * t.stages]) / t.gamma;
      damping_ = c;
      inertia_ = (1 + gh * c) / (gh * gh);
      held_fraction_ = t.c(stage);
      for (std::size_t k = 0; k < n; ++k)
        target_[k] = explicit_position_[k] + gh * explicit_velocity_[k] / (1 + gh * c);
      return;
    }
    case Kind::backward_euler:
      // M (v_{n+1} − v_n)/h = F + f − c M v_{n+1},  v_{n+1} = (z − y_n)/h
      inertia_ = (1 + c * h) / (h * h);
      for (std::size_t k = 0; k < n; ++k) target_[k] = y[k] + h * v[k] / (1 + c * h);
      return;
    case Kind::newmark_alpha: {
      // M a_{n+1−α_m} + c M v_{n+1−α_f} = F(z) + f with z = y_{n+1−α_f}, and Newmark's
      // y_{n+1} = y_n + h v_n + h²((½ − β) a_n + β a_{n+1}), v_{n+1} = v_n + h((1 − γ) a_n + γ
      // a_{n+1}). The left side is affine in z, A z + k, so ỹ = −k/A with k its value at z = 0.
      // B's acceleration a_B enters a_{n+1} as a_B/γ and is not carried into a_n: it changes the
      // velocity by h a_B, an impulse at the step's end. For Newmark the position then moves by
      // h(v_n + v_{n+1})/2, and with a_B contact's secant from y_n (contact_secant) the work
      // M a_B·Δy is −ΔB exactly: the contact neither gains nor loses energy (a discrete
      // gradient, Gonzalez 1996). Generalized-α takes a_B at y_{n+1} (at z it created
      // energy at every bounce): the equation gains (1 − α_m) a_B(y_{n+1})/γ, the gradient of
      // (1 − α_m)(1 − α_f)/γ B(y_n + (z − y_n)/(1 − α_f)).
      potential_weight_ = (1 - alpha_m_) * (1 - alpha_f_) / gamma_;
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

void ImplicitScheme::stage_velocity(const State& state, const std::vector<double>& acceleration,
                                    double h, std::vector<double>& anchor, double& span) const {
  const std::size_t n = state.position.size();
  const double* y = state.position.data();
  const double* v = state.velocity.data();
  const double* a = acceleration.data();
  anchor.resize(n);
  switch (kind_) {
    case Kind::static_equilibrium:
      span = 0;
      std::copy(y, y + n, anchor.begin());
      return;
    case Kind::sdirk:  // V_i = (Y_i − Ŷ_i)/(γh)
      span = tableau_->gamma * h;
      std::copy(explicit_position_.begin(), explicit_position_.end(), anchor.begin());
      return;
    case Kind::backward_euler:  // v_{n+1} = (z − y_n)/h
      span = h;
      std::copy(y, y + n, anchor.begin());
      return;
    case Kind::newmark_alpha: {
      // v_{n+1} of correct(): its coefficient of z is γ/(β h (1 − α_f)); at z = y_n it is
      // v_n (1 − γ/β) + h a_n (1 − γ − γ(½ − β)/β)
      span = beta_ * h * (1 - alpha_f_) / gamma_;
      const double cv = 1 - gamma_ / beta_, ca = h * (1 - gamma_ - gamma_ * (0.5 - beta_) / beta_);
      for (std::size_t k = 0; k < n; ++k) anchor[k] = y[k] - span * (cv * v[k] + ca * a[k]);
      return;
    }
  }
}

std::vector<double> ImplicitScheme::guess(const State& state, double h) const {
  std::vector<double> z(state.position.size());
  if (kind_ == Kind::sdirk && stage_ > 0) {
    // Y_i = ỹ + M⁻¹(F + f)(Y_i)/A, with M⁻¹(F + f) = V' + cV taken from the previous stage,
    // contact's share as this stage weighs it: V'_{i−1} holds a_B once, but the explicit first
    // stage's a_n holds none, and after it a_B is the one at the last step's end
    const double* v = stage_velocity_[stage_ - 1].data();
    const double* a = stage_acceleration_[stage_ - 1].data();
    const double* b = stage_contact_.empty() ? nullptr : stage_contact_.data();
    const bool after_explicit = stage_ == 1 && tableau_->explicit_stage(0);
    const double moved = potential_weight_ - (after_explicit ? 0 : 1);
#pragma omp parallel for schedule(static)
    for (std::size_t k = 0; k < z.size(); ++k)
      z[k] = target_[k] + (a[k] + damping_ * v[k] + (b ? moved * b[k] : 0.0)) / inertia_;
    return z;
  }
  const double step = kind_ == Kind::static_equilibrium ? 0.0
                      : kind_ == Kind::sdirk            ? tableau_->c(stage_) * h
                                                        : (1 - alpha_f_) * h;
  for (std::size_t k = 0; k < z.size(); ++k) z[k] = state.position[k] + step * state.velocity[k];
  return z;
}

void ImplicitScheme::finish_stage(const std::vector<double>& z, const std::vector<double>& contact,
                                  double h) {
  if (kind_ != Kind::sdirk) return;
  // V_i = (Y_i − Ŷ_i)/(γh), V'_i = (V_i − V̂_i)/(γh); V'_i holds w a_B, of which the later stages
  // take a_B (the share w − 1 was the first stage's)
  const double gh = tableau_->gamma * h, moved = potential_weight_ - 1;
  double* velocity = stage_velocity_[stage_].data();
  double* acceleration = stage_acceleration_[stage_].data();
  const double* b = contact.empty() ? nullptr : contact.data();
  stage_contact_ = contact;
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < z.size(); ++k) {
    velocity[k] = (z[k] - explicit_position_[k]) / gh;
    acceleration[k] = (velocity[k] - explicit_velocity_[k]) / gh - (b ? moved * b[k] : 0.0);
  }
}

ImplicitScheme::ErrorSums ImplicitScheme::local_error(double h, const std::vector<double>& mass,
                                                      const std::vector<char>& fixed,
                                                      std::size_t first, std::size_t end) const {
  const SdirkTableau& t = *tableau_;
  ErrorSums sums;
  double position = 0, velocity = 0, free_mass = 0;
#pragma omp parallel for schedule(static) reduction(+ : position, velocity, free_mass)
  for (std::size_t k = first; k < end; ++k) {
    if (fixed[k]) continue;
    double dy = 0, dv = 0;  // h Σ (b_i − b̂_i) V_i and h Σ (b_i − b̂_i) V'_i
    for (int i = 0; i < t.stages; ++i) {
      const double w = h * (t.b[i] - t.b_embedded[i]);
      dy += w * stage_velocity_[i][k];
      dv += w * stage_acceleration_[i][k];
    }
    position += mass[k] * dy * dy;
    velocity += mass[k] * dv * dv;
    free_mass += mass[k];
  }
  sums.position = position;
  sums.velocity = velocity;
  sums.mass = free_mass;
  return sums;
}

void ImplicitScheme::correct(const std::vector<double>& z, const std::vector<double>& contact,
                             State& state, std::vector<double>& acceleration, double h) const {
  const std::size_t n = z.size();
  double* y = state.position.data();
  double* v = state.velocity.data();
  double* a = acceleration.data();
  const double* b = contact.empty() ? nullptr : contact.data();
  switch (kind_) {
    case Kind::static_equilibrium:
      // Inertia is ignored: the body is at rest in each equilibrium.
      for (std::size_t k = 0; k < n; ++k) y[k] = z[k], v[k] = 0, a[k] = 0;
      return;
    case Kind::sdirk: {
      // y_{n+1} = y_n + h Σ b_i V_i, v_{n+1} = v_n + h Σ b_i V'_i; for a stiffly accurate scheme
      // y_{n+1}, v_{n+1} are the last stage's Y_s, V_s exactly.
      const SdirkTableau& t = *tableau_;
      if (t.stiffly_accurate) {
        std::copy(z.begin(), z.end(), y);
        std::copy(stage_velocity_.back().begin(), stage_velocity_.back().end(), v);
      } else {
        for (int i = 0; i < t.stages; ++i) {
          const double w = h * t.b[i];
          const double* vi = stage_velocity_[i].data();
          const double* ai = stage_acceleration_[i].data();
#pragma omp parallel for schedule(static)
          for (std::size_t k = 0; k < n; ++k) y[k] += w * vi[k], v[k] += w * ai[k];
        }
      }
      const double* last = stage_acceleration_[t.stages - 1].data();
      for (std::size_t k = 0; k < n; ++k) a[k] = last[k] - (b ? b[k] : 0.0);
      return;
    }
    case Kind::backward_euler:
#pragma omp parallel for schedule(static)
      for (std::size_t k = 0; k < n; ++k) {
        const double v1 = (z[k] - y[k]) / h;
        a[k] = (v1 - v[k]) / h - (b ? b[k] : 0.0);
        v[k] = v1;
        y[k] = z[k];
      }
      return;
    case Kind::newmark_alpha: {
      const double bh2 = beta_ * h * h;
#pragma omp parallel for schedule(static)
      for (std::size_t k = 0; k < n; ++k) {
        const double y1 = y[k] + (z[k] - y[k]) / (1 - alpha_f_);
        const double a1 = (y1 - y[k] - h * v[k] - h * h * (0.5 - beta_) * a[k]) / bh2;
        v[k] += h * ((1 - gamma_) * a[k] + gamma_ * a1);
        a[k] = a1 - (b ? b[k] / gamma_ : 0.0);  // a_{n+1} without a_B/γ
        y[k] = y1;
      }
      return;
    }
  }
}

}  // namespace fissure
