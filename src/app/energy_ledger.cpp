#include "app/energy_ledger.hpp"

#include <algorithm>
#include <cmath>

#include "app/energy.hpp"

namespace fissure {

EnergyLedger::EnergyLedger(const Dynamics& dynamics) {
  for (const auto& [name, booking] : dynamics.ledger_entries()) entries_.push_back({name, booking});
  loads_ = entries_.size();
  entries_.push_back({"plastic_dissipation", Booking::loss});
  entries_.push_back({"fracture_release", Booking::loss});
}

void EnergyLedger::before_step(const RunParts& run) { before_ = run.state.position; }

void EnergyLedger::after_step(const RunParts& run, const Step& step) {
  const std::vector<double>& after = run.state.position;
  if (run.ranks.distributed()) {
    // Each rank books its own rows' share: elsewhere the step moves nothing in its books.
    const std::size_t first = 3 * std::size_t(run.ranks.begin()),
                      end = 3 * std::size_t(run.ranks.end());
    std::copy(after.begin(), after.begin() + first, before_.begin());
    std::copy(after.begin() + end, after.end(), before_.begin() + end);
  }
  const BookedStep booked{before_.data(), after.data(), step.h(),
                          [&step] { return step.own_kinetic(); }};
  std::vector<double> amounts = run.dynamics.booked(booked);
  run.ranks.sum(amounts);
  for (std::size_t e = 0; e < loads_; ++e) entries_[e].value += amounts[e];
  entries_[loads_].value = run.post_step.released().plastic;
  entries_[loads_ + 1].value = run.post_step.released().fracture;
}

void EnergyLedger::sample(const RunParts& run) {
  const RunRanks& ranks = run.ranks;
  kinetic_ = ranks.sum(
      kinetic_energy(run.scene.particles.mass, run.state.velocity, ranks.begin(), ranks.end()));
  elastic_ = ranks.distributed()
                 ? ranks.sum(run.model.rows_energy(run.state.position.data(), ranks.rows()))
                 : run.model.elastic_energy(run.state.position.data());
  stored_ = ranks.sum(run.dynamics.stored_energy(run.state.position.data()));
  if (!sampled_) {
    initial_ = kinetic_ + elastic_ + stored_;
    sampled_ = true;
  }
  scale_ = std::max({scale_, kinetic_ + std::abs(elastic_) + stored_, absolute_work()});
}

double EnergyLedger::sum(Booking booking) const {
  double total = -0.0;
  for (const Entry& e : entries_)
    if (e.booking == booking) total += e.value;
  return total;
}

double EnergyLedger::work() const { return sum(Booking::work); }

double EnergyLedger::losses() const { return sum(Booking::loss); }

double EnergyLedger::absolute_work(double from) const {
  for (const Entry& e : entries_)
    if (e.booking == Booking::work) from += std::abs(e.value);
  return from;
}

double EnergyLedger::balance() const {
  return kinetic_ + elastic_ + stored_ + losses() - (initial_ + work());
}

double EnergyLedger::balance_error() const { return scale_ > 0 ? balance() / scale_ : 0.0; }

std::vector<std::pair<std::string, double>> EnergyLedger::entries() const {
  std::vector<std::pair<std::string, double>> all;
  for (const Entry& e : entries_) all.emplace_back(e.name, e.value);
  all.emplace_back("balance_error", balance_error());
  all.emplace_back("stored_energy", stored_);
  return all;
}

std::vector<std::string> EnergyLedger::names() const {
  std::vector<std::string> names;
  for (const auto& [name, value] : entries()) names.push_back(name);
  return names;
}

void EnergyLedger::summarize(RunSummary& summary) const {
  summary.energy_drift = balance_error();
  summary.energy = {{"kinetic", kinetic_},
                    {"elastic", elastic_},
                    {"initial", initial_},
                    {"scale", scale_},
                    {"balance", balance()}};
  for (const auto& entry : entries()) summary.energy.push_back(entry);
}

NamedArrays EnergyLedger::saved_state() const {
  NamedArrays state = {{"ledger.kinetic", {kinetic_}},
                       {"ledger.elastic", {elastic_}},
                       {"ledger.stored", {stored_}},
                       {"ledger.initial", {initial_}},
                       {"ledger.scale", {scale_}}};
  for (const Entry& e : entries_) state.push_back({"ledger." + e.name, {e.value}});
  return state;
}

void EnergyLedger::resume(const RunParts&, const NamedArrays& state) {
  kinetic_ = saved_number(state, "ledger.kinetic");
  elastic_ = saved_number(state, "ledger.elastic");
  const std::vector<double>* stored = find_array(state, "ledger.stored");
  stored_ = stored ? stored->at(0) : 0.0;  // a checkpoint from before the colliders' energy
  initial_ = saved_number(state, "ledger.initial");
  scale_ = saved_number(state, "ledger.scale");
  for (Entry& e : entries_) e.value = saved_number(state, "ledger." + e.name);
  sampled_ = true;  // a checkpoint comes after the sample at t = 0
}

}  // namespace fissure
