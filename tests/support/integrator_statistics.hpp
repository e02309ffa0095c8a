#pragma once
// An integrator's named counters (Integrator::statistics) for tests: one by name, all printed,
// and the factor refreshes summed over their reasons.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "integrators/integrator.hpp"

namespace fissure::test {

inline double statistic(const Integrator& integrator, const std::string& name) {
  for (const auto& [key, value] : integrator.statistics())
    if (key == name) return value;
  ADD_FAILURE() << "no statistic " << name;
  return -1;
}

inline void print_statistics(const char* label, const Integrator& integrator) {
  std::printf("%s:", label);
  for (const auto& [name, value] : integrator.statistics())
    if (value != 0) std::printf(" %s %.0f", name.c_str(), value);
  std::printf("\n");
}

// Every factorization after the first is one refresh, counted under one reason.
inline double refreshes(const Integrator& integrator) {
  double sum = 0;
  for (const char* reason :
       {"refreshes_step_size", "refreshes_bonds_broken", "refreshes_convergence",
        "refreshes_fallback", "refreshes_every_iteration"})
    sum += statistic(integrator, reason);
  return sum;
}

}  // namespace fissure::test
