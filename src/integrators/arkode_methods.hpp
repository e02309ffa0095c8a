#pragma once
// The ARKODE methods Fissure exposes (integrator.method), each with its Butcher tables and
// nominal order. Every one is advanced by ARKStep, explicit ones included: SUNDIALS 6.4.1's
// ERKStep treats any table whose last stage has c = 1 as first-same-as-last and loses up to
// three orders on some of them (docs/integrators.md).
// clang-format off
#include <cstdio>  // first: arkode_butcher.h uses FILE without including <cstdio>
#include <arkode/arkode_butcher_dirk.h>
#include <arkode/arkode_butcher_erk.h>
// clang-format on

#include <string>
#include <vector>

namespace fissure {

struct ArkodeMethod {
  enum class Kind { explicit_rk, implicit_rk, imex } kind;
  std::string name;  // as the config spells it
  ARKODE_ERKTableID explicit_table;
  ARKODE_DIRKTableID implicit_table;
  int order;
};

const std::vector<ArkodeMethod>& arkode_methods();
// The method called `name`; throws InputError naming the valid ones otherwise.
const ArkodeMethod& arkode_method(const std::string& name, const std::string& file);

// Throws RunError naming `what` and ARKStep's flag when flag < 0 (an ARKStep call failed).
void arkode_check(int flag, const char* what);

}  // namespace fissure
