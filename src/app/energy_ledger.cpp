#include "app/energy_ledger.hpp"

#include <cmath>

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

}  // namespace fissure
