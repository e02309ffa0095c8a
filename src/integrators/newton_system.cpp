#include "integrators/newton_system.hpp"

#include <cmath>
#include <cstring>

#include "model/stiffness.hpp"
#include "parallel/collective.hpp"
#include "parallel/halo.hpp"

namespace fissure {

NewtonSystem::NewtonSystem(Dynamics& dynamics, Tangent tangent)
    : dynamics_(dynamics), tangent_(tangent) {
  potentials_ = dynamics.potentials();
  const auto& m = dynamics.mass();
  mass_.resize(3 * m.size());
  for (std::size_t i = 0; i < m.size(); ++i)
    for (int d = 0; d < 3; ++d) mass_[3 * i + d] = m[i];
  first_ = 3 * std::size_t(dynamics.first_row());
  end_ = 3 * std::size_t(dynamics.end_row());
  force_.resize(mass_.size());
  external_.resize(mass_.size());
  masked_.resize(mass_.size());
  for (const LoadPotential* p : potentials_) {
    has_contact_ = has_contact_ || p->contact();
    has_coupling_ = has_coupling_ || p->couples();
  }
  if (has_coupling_) coupling_.resize(mass_.size());
  if (!potentials_.empty()) {
    smooth_gradient_.resize(mass_.size());
    contact_gradient_.resize(mass_.size());
  }
  if (tangent == Tangent::majoriser)  // over several ranks the rank's rows only
    majoriser_ =
        bond_pattern(dynamics.model().families(), dynamics.first_row(), dynamics.end_row());
}

std::vector<double> NewtonSystem::begin_step(const ImplicitScheme& scheme, const State& state,
                                             const std::vector<double>& acceleration, double h,
                                             double load_factor) {
  inertia_ = scheme.inertia();
  weight_ = scheme.potential_weight();
  scale_ = scheme.potential_scale();
  if (scale_ != 1) origin_ = state.position;
  target_ = scheme.target();
  dynamics_.external_forces(state.time, state.position.data(), state.velocity.data(),
                            external_.data(), true);
  for (double& f : external_) f *= load_factor;
  if (!potentials_.empty()) {
    std::vector<double> anchor;
    double span = 0;
    scheme.stage_velocity(state, acceleration, h, anchor, span);
    const PotentialStage stage{state.position.data(), anchor.data(), span,
                               scheme.stage_fraction() * h};
    // contact's: the stage's velocity (z − anchor)/span as a function of p = y_n + s (z − y_n)
    std::vector<double> mapped;
    if (scale_ != 1) {
      mapped.resize(anchor.size());
      for (std::size_t k = 0; k < mapped.size(); ++k)
        mapped[k] = state.position[k] + scale_ * (anchor[k] - state.position[k]);
    }
    const PotentialStage at_p{state.position.data(), scale_ != 1 ? mapped.data() : anchor.data(),
                              scale_ * span, scale_ * stage.elapsed, scheme.contact_secant()};
    for (LoadPotential* p : potentials_) p->begin_stage(p->contact() ? at_p : stage);
  }
  cached_ = false;  // the potentials changed with the stage
  // Newton starts from the extrapolation y + (1 − α_f)h v or, where that overshoots (modes with
  // ωh ≫ 1 at large steps carry large velocities), from y: whichever has the lower potential.
  // A later SDIRK stage starts from ỹ plus the previous stage's acceleration (scheme.guess).
  std::vector<double> z = scheme.guess(state, h);
  std::vector<double> stay = state.position;
  fixed_.assign(z.size(), 0);
  std::vector<int> held;
  std::vector<Vec3> displacement;
  dynamics_.held_motion(state.time, scheme.held_time() * h, state.position.data(), held,
                        displacement);
  for (std::size_t k = 0; k < held.size(); ++k)
    for (int d = 0; d < 3; ++d) {
      const int u = 3 * held[k] + d;
      fixed_[u] = 1;
      z[u] = stay[u] = state.position[u] + scheme.held_chord() * displacement[k][d];
    }
  linearized_ = false;
  dynamics_.share(z.data());  // the guess's ghosts from their own ranks' velocities
  if (!potentials_.empty()) {
    // the guess cut back to what the potentials admit (a particle not driven through a collider)
    std::vector<double> update(z.size());
    for (std::size_t k = 0; k < z.size(); ++k) update[k] = z[k] - stay[k];
    const double alpha = max_step(stay.data(), update.data());
    if (alpha < 1)
      for (std::size_t k = 0; k < z.size(); ++k) z[k] = stay[k] + alpha * update[k];
  }
  if (scheme.later_stage()) return z;
  return objective(stay.data()) < objective(z.data()) ? stay : z;
}

const double* NewtonSystem::potential_point(const double* z, std::vector<double>& out) const {
  if (scale_ == 1) return z;
  out.resize(origin_.size());
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < out.size(); ++k) out[k] = origin_[k] + scale_ * (z[k] - origin_[k]);
  return out.data();
}

double NewtonSystem::max_step(const double* z, const double* dz) const {
  double alpha = 1;
  std::vector<double> point, update;
  const double* p = potential_point(z, point);
  const double* dp = dz;
  if (scale_ != 1) {
    update.assign(dz, dz + origin_.size());
    for (double& u : update) u *= scale_;
    dp = update.data();
  }
  for (const LoadPotential* load : potentials_)
    alpha = std::min(alpha, load->contact() ? load->max_step(p, dp) : load->max_step(z, dz));
  return distributed() ? min_over_ranks(dynamics_.halo()->comm(), alpha) : alpha;
}

bool NewtonSystem::add_potential_blocks(const double* z, std::vector<double>& blocks) {
  if (potentials_.empty()) return false;
  blocks.assign(3 * mass_.size(), 0.0);  // 9 per particle
  if (has_contact_) {
    const double* p = potential_point(z, mapped_);
    for (LoadPotential* load : potentials_)
      if (load->contact()) load->evaluate(p, nullptr, blocks.data());
    const double factor = weight_ * scale_ * scale_;
    if (factor != 1)
      for (double& b : blocks) b *= factor;
  }
  for (LoadPotential* load : potentials_)
    if (!load->contact()) load->evaluate(z, nullptr, blocks.data());
  return true;
}

void NewtonSystem::add_coupling(const double* v, double* out) {
  if (!has_coupling_) return;
  // the pair blocks of ∇²S⁺ + w s² ∇²B⁺ at the linearization point, B's at p(z)
  std::fill(coupling_.begin(), coupling_.end(), 0.0);
  const double* p = has_contact_ ? potential_point(linearization_.data(), mapped_) : nullptr;
  for (const LoadPotential* load : potentials_)
    if (load->contact()) load->add_coupling(p, v, coupling_.data());
  const double factor = weight_ * scale_ * scale_;
  for (std::size_t k = first_; k < end_; ++k) coupling_[k] *= factor;
  for (const LoadPotential* load : potentials_)
    if (!load->contact()) load->add_coupling(linearization_.data(), v, coupling_.data());
  for (std::size_t k = first_; k < end_; ++k) out[k] += coupling_[k];
}

void NewtonSystem::potential_acceleration(const double* z, std::vector<double>& out) {
  if (!has_contact_) {
    out.clear();
    return;
  }
  evaluate(z, residual_passes);
  out.assign(mass_.size(), 0.0);
  for (std::size_t k = first_; k < end_; ++k)
    if (!fixed_[k]) out[k] = -contact_gradient_[k] / mass_[k];
}

double NewtonSystem::sum_over_ranks(double value) const {
  return distributed() ? fissure::sum_over_ranks(dynamics_.halo()->comm(), value) : value;
}

void NewtonSystem::evaluate(const double* z, long& passes) {
  const std::size_t n = mass_.size();
  const std::size_t revision = dynamics_.model().revision();
  int same = cached_ && revision == revision_ &&
             std::memcmp(z + first_, point_.data() + first_, (end_ - first_) * sizeof(double)) == 0;
  // the model's evaluation is collective: every rank evaluates when one rank's point changed
  if (distributed()) same = min_over_ranks(dynamics_.halo()->comm(), same);
  if (same) {
    ++cache_hits;
    return;
  }
  elastic_ = dynamics_.model().forces_and_energy(z, force_.data());
  dynamics_.count_force_evaluation();
  if (!potentials_.empty()) {
    std::fill(smooth_gradient_.begin(), smooth_gradient_.end(), 0.0);
    std::fill(contact_gradient_.begin(), contact_gradient_.end(), 0.0);
    smooth_ = contact_ = 0;
    const double* p = has_contact_ ? potential_point(z, mapped_) : z;
    for (LoadPotential* load : potentials_)
      if (load->contact())
        contact_ += load->evaluate(p, contact_gradient_.data(), nullptr);
      else
        smooth_ += load->evaluate(z, smooth_gradient_.data(), nullptr);
  }
  point_.assign(z, z + n);
  cached_ = true;
  revision_ = revision;
  ++passes;
}

// E = (A/2)(z − ỹ)ᵀM(z − ỹ) + Π(z) + S(z) + w B(p(z)) − fᵀ(z − ỹ)
double NewtonSystem::objective(const double* z) {
  evaluate(z, objective_passes);
  double kinetic = 0, work = 0;
#pragma omp parallel for reduction(+ : kinetic, work) schedule(static)
  for (std::size_t k = first_; k < end_; ++k) {
    if (fixed_[k]) continue;
    const double d = z[k] - target_[k];
    kinetic += mass_[k] * d * d;
    work += external_[k] * d;  // fᵀ(z − ỹ): fᵀz up to a constant, without its cancellation
  }
  double elastic = elastic_, potential = smooth_ + weight_ * contact_;  // this rank's share
  if (distributed()) {
    std::vector<double> parts = {kinetic, work, elastic, potential};
    fissure::sum_over_ranks(dynamics_.halo()->comm(), parts);
    kinetic = parts[0], work = parts[1], elastic = parts[2], potential = parts[3];
  }
  magnitude_ = 0.5 * inertia_ * kinetic + std::abs(elastic) + potential + std::abs(work);
  return 0.5 * inertia_ * kinetic + elastic + potential - work;
}

// ∇E = A M (z − ỹ) − F_int(z) + ∇S(z) + w s ∇B(p(z)) − f
void NewtonSystem::residual(const double* z, double* r) {
  evaluate(z, residual_passes);
  const double* s = potentials_.empty() ? nullptr : smooth_gradient_.data();
  const double* b = potentials_.empty() ? nullptr : contact_gradient_.data();
  const double factor = weight_ * scale_;
#pragma omp parallel for schedule(static)
  for (std::size_t k = first_; k < end_; ++k)
    r[k] = fixed_[k] ? 0.0
                     : inertia_ * mass_[k] * (z[k] - target_[k]) - force_[k] +
                           (b ? s[k] + factor * b[k] : 0.0) - external_[k];
}

std::vector<double> NewtonSystem::reactions() const {
  std::vector<double> reaction(fixed_.size(), 0.0);
  for (std::size_t k = 0; k < fixed_.size(); ++k)
    if (fixed_[k])
      reaction[k] =
          -(force_[k] - (potentials_.empty() ? 0.0 : smooth_gradient_[k] + contact_gradient_[k]) +
            external_[k]);
  return reaction;
}

void NewtonSystem::linearize(const double* z) {
  linearization_.assign(z, z + mass_.size());
  linearized_ = false;
}

void NewtonSystem::apply(const double* v, double* out) {
  Stiffness& stiffness = *dynamics_.model().stiffness();  // check() made sure it is there
  if (!linearized_ || linearized_tangent_ != tangent_) {
    if (tangent_ == Tangent::majoriser)
      stiffness.assemble_majoriser(linearization_.data(), majoriser_);
    else
      stiffness.linearize(linearization_.data(), tangent_ == Tangent::projected);
    add_potential_blocks(linearization_.data(), blocks_);
    linearized_ = true;
    linearized_tangent_ = tangent_;
    ++linearizations;
  }
#pragma omp parallel for schedule(static)
  for (std::size_t k = first_; k < end_; ++k) masked_[k] = fixed_[k] ? 0.0 : v[k];
  dynamics_.share(masked_.data());
  if (tangent_ == Tangent::majoriser)
    majoriser_.multiply(masked_.data(), out);
  else
    stiffness.apply_tangent(masked_.data(), out);
  if (!potentials_.empty()) {  // + (∇²S⁺ + w s² ∇²B⁺) v, particle by particle
    const std::ptrdiff_t first = first_ / 3, end = end_ / 3;
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t i = first; i < end; ++i)
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          out[3 * i + a] += blocks_[9 * i + 3 * a + b] * masked_[3 * i + b];
    add_coupling(masked_.data(), out);
  }
#pragma omp parallel for schedule(static)
  for (std::size_t k = first_; k < end_; ++k)
    out[k] = fixed_[k] ? (inertia_ > 0 ? inertia_ * mass_[k] : 1.0) * v[k]
                       : out[k] + inertia_ * mass_[k] * v[k];
  ++tangent_products;
}

}  // namespace fissure
