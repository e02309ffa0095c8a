#include "app/energy_ledger.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/error.hpp"

namespace fissure {

double EnergyLedger::balance() const {
  const double losses = damping_loss + contact_loss + plastic_dissipation + fracture_release;
  const double work = gravity_work + constraint_work + collider_work;
  return kinetic + elastic + losses - (initial + work);
}

double EnergyLedger::balance_error() const { return scale > 0 ? balance() / scale : 0.0; }

std::vector<std::pair<std::string, double>> EnergyLedger::entries() const {
  return {{"gravity_work", gravity_work},         {"constraint_work", constraint_work},
          {"collider_work", collider_work},       {"damping_loss", damping_loss},
          {"contact_loss", contact_loss},         {"plastic_dissipation", plastic_dissipation},
          {"fracture_release", fracture_release}, {"balance_error", balance_error()}};
}

std::vector<std::string> EnergyLedger::names() {
  std::vector<std::string> names;
  for (const auto& [name, value] : EnergyLedger().entries()) names.push_back(name);
  return names;
}

std::vector<double> EnergyLedger::numbers() const {
  return {kinetic,          elastic,      gravity_work, constraint_work,
          collider_work,    damping_loss, contact_loss, plastic_dissipation,
          fracture_release, initial,      scale};
}

EnergyLedger EnergyLedger::from_numbers(const std::vector<double>& n) {
  if (n.size() != 11)
    throw InputError("", "run.ledger", fmt::format("expected 11 numbers, got {}", n.size()));
  return {n[0], n[1], n[2], n[3], n[4], n[5], n[6], n[7], n[8], n[9], n[10]};
}

}  // namespace fissure
