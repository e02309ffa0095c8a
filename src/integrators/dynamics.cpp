#include "integrators/dynamics.hpp"

#include <algorithm>
#include <stdexcept>

#include "integrators/collider_load.hpp"
#include "integrators/load_registry.hpp"
#include "parallel/halo.hpp"

namespace fissure {

namespace {

constexpr int kConstraints = -1, kAbsent = -2;

}  // namespace

Dynamics::Dynamics(const Scene& scene, Model& model)
    : model_(model),
      mass_(scene.particles.mass),
      damping_(scene.config.damping),
      constraints_(scene),
      force_(3 * mass_.size()),
      scratch_(3 * mass_.size()) {
  for (const LoadKind& kind : load_kinds()) {
    entries_.emplace_back(kind.entry, kind.booking);
    std::unique_ptr<Load> load = kind.make ? kind.make(scene, model) : nullptr;
    entry_load_.push_back(!kind.make ? kConstraints : load ? int(loads_.size()) : kAbsent);
    if (load) loads_.push_back(std::move(load));
  }
}

void Dynamics::distribute(const Halo& halo) {
  for (const auto& load : loads_)
    if (const std::string key = load->not_distributable(); !key.empty())
      throw std::invalid_argument(key + " cannot run over several ranks yet (docs/mpi.md)");
  model_.distribute(halo);
  for (const auto& load : loads_) load->distribute(halo);
  halo_ = &halo;
}

int Dynamics::first_row() const { return halo_ ? halo_->begin() : 0; }

int Dynamics::end_row() const { return halo_ ? halo_->end() : static_cast<int>(mass_.size()); }

void Dynamics::share(double* y) const { share(y, 3); }

void Dynamics::share(double* values, int width) const {
  if (halo_) halo_->fill(values, width);
}

void Dynamics::end_step(double h) {
  for (auto& load : loads_) load->end_step(h);
}

const Colliders* Dynamics::colliders() const {
  for (const auto& load : loads_)
    if (const auto* c = dynamic_cast<const ColliderLoad*>(load.get())) return &c->colliders();
  return nullptr;
}

void Dynamics::internal_forces(const double* y, double* f) {
  model_.forces(y, f);
  ++force_evaluations_;
}

void Dynamics::add_loads(Load::Form form, bool stiff_only, double t, const double* y,
                         const double* v, double* out, bool without_contact) {
  for (auto& load : loads_)
    if (load->form() == form && (!stiff_only || load->stiff()) &&
        !(without_contact && load->potential() && load->potential()->contact()))
      load->add(t, y, v, out);
}

// Each sum below keeps the order of a = F_int/m + g − c v as written: the forces first, then
// the accelerations in load order, so every integrator's bits stay those of Eq 2 summed left to
// right.
void Dynamics::acceleration(double t, const double* y, const double* v, double* a,
                            bool without_contact) {
  internal_forces(y, force_.data());
  add_loads(Load::Form::force, false, t, y, v, force_.data(), without_contact);
  const int n = static_cast<int>(mass_.size());
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    const double inv_m = 1.0 / mass_[i];
    for (int k = 0; k < 3; ++k) a[3 * i + k] = force_[3 * i + k] * inv_m;
  }
  add_loads(Load::Form::acceleration, false, t, y, v, a, without_contact);
  constraints_.hold(t, a, Constraints::Part::whole);
}

void Dynamics::implicit_acceleration(double t, const double* y, const double* v, double* a) {
  internal_forces(y, force_.data());
  add_loads(Load::Form::force, true, t, y, v, force_.data());
  const int n = static_cast<int>(mass_.size());
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) a[3 * i + k] = force_[3 * i + k] / mass_[i];
  add_loads(Load::Form::acceleration, true, t, y, v, a);
  constraints_.hold(t, a, Constraints::Part::implicit);
}

void Dynamics::explicit_acceleration(double t, const double* y, const double* v, double* a) {
  external_forces(t, y, v, a);
  const int n = static_cast<int>(mass_.size());
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) a[3 * i + k] /= mass_[i];
  constraints_.hold(t, a, Constraints::Part::explicit_);
}

std::vector<LoadPotential*> Dynamics::potentials() const {
  std::vector<LoadPotential*> out;
  for (const auto& load : loads_)
    if (LoadPotential* p = load->potential()) out.push_back(p);
  return out;
}

double Dynamics::stored_energy(const double* y) const {
  double sum = 0;
  for (const auto& load : loads_) sum += load->stored_energy(y);
  return sum;
}

std::string Dynamics::implicit_refusal() const {
  for (std::size_t e = 0; e < entry_load_.size(); ++e) {
    if (entry_load_[e] < 0) continue;
    Load& load = *loads_[entry_load_[e]];
    if (load.stiff() && !load.potential() && !load.scheme_coefficient()) return entries_[e].first;
  }
  return {};
}

void Dynamics::external_forces(double t, const double* y, const double* v, double* f,
                               bool without_potentials) {
  // −0 is the exact additive identity (x + −0 = x for every x, +0 included), so the first load
  // adds its force unchanged.
  const std::size_t n = mass_.size();
  std::fill(f, f + 3 * n, -0.0);
  for (auto& load : loads_) {
    if (load->stiff() || (without_potentials && load->potential())) continue;
    if (load->form() == Load::Form::force) {
      load->add(t, y, v, f);
      continue;
    }
    std::fill(scratch_.begin(), scratch_.end(), -0.0);
    load->add(t, y, v, scratch_.data());
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) f[3 * i + k] += mass_[i] * scratch_[3 * i + k];
  }
}

std::vector<double> Dynamics::booked(const BookedStep& step) const {
  std::vector<double> amounts;
  for (int load : entry_load_)
    amounts.push_back(load == kConstraints ? constraints_.work(step.before, step.after)
                      : load == kAbsent    ? 0.0
                                           : loads_[load]->booked(step));
  return amounts;
}

NamedArrays Dynamics::saved_state() const {
  NamedArrays state = {{"dynamics.force_evaluations", {double(force_evaluations_)}}};
  for (const auto& load : loads_)
    for (auto& array : load->saved_state()) state.push_back(std::move(array));
  return state;
}

void Dynamics::restore_state(const NamedArrays& state) {
  if (const std::vector<double>* n = find_array(state, "dynamics.force_evaluations"))
    force_evaluations_ = static_cast<long>(n->at(0));
  for (auto& load : loads_) load->restore_state(state);
}

}  // namespace fissure
