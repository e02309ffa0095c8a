#include "integrators/arkode_methods.hpp"

#include <arkode/arkode_arkstep.h>
#include <fmt/format.h>

#include "core/error.hpp"
#include "scene/unknown_choice.hpp"

namespace fissure {

const std::vector<ArkodeMethod>& arkode_methods() {
  using K = ArkodeMethod::Kind;
  static const std::vector<ArkodeMethod> methods = {
      {K::explicit_rk, "HEUN_EULER_2_1_2", ARKODE_HEUN_EULER_2_1_2, ARKODE_DIRK_NONE, 2},
      {K::explicit_rk, "BOGACKI_SHAMPINE_4_2_3", ARKODE_BOGACKI_SHAMPINE_4_2_3, ARKODE_DIRK_NONE,
       3},
      {K::explicit_rk, "ZONNEVELD_5_3_4", ARKODE_ZONNEVELD_5_3_4, ARKODE_DIRK_NONE, 4},
      {K::explicit_rk, "DORMAND_PRINCE_7_4_5", ARKODE_DORMAND_PRINCE_7_4_5, ARKODE_DIRK_NONE, 5},
      {K::explicit_rk, "VERNER_8_5_6", ARKODE_VERNER_8_5_6, ARKODE_DIRK_NONE, 6},
      {K::implicit_rk, "SDIRK_2_1_2", ARKODE_ERK_NONE, ARKODE_SDIRK_2_1_2, 2},
      {K::implicit_rk, "KVAERNO_4_2_3", ARKODE_ERK_NONE, ARKODE_KVAERNO_4_2_3, 3},
      {K::implicit_rk, "CASH_5_3_4", ARKODE_ERK_NONE, ARKODE_CASH_5_3_4, 4},
      {K::imex, "ARK324L2SA", ARKODE_ARK324L2SA_ERK_4_2_3, ARKODE_ARK324L2SA_DIRK_4_2_3, 3},
      {K::imex, "ARK436L2SA", ARKODE_ARK436L2SA_ERK_6_3_4, ARKODE_ARK436L2SA_DIRK_6_3_4, 4},
      {K::imex, "ARK548L2SA", ARKODE_ARK548L2SA_ERK_8_4_5, ARKODE_ARK548L2SA_DIRK_8_4_5, 5},
  };
  return methods;
}

const ArkodeMethod& arkode_method(const std::string& name, const std::string& file) {
  std::vector<std::string> names;
  for (const auto& m : arkode_methods()) {
    if (m.name == name || "ARKODE_" + m.name == name) return m;
    names.push_back(m.name);
  }
  throw InputError(file, "integrator.method", unknown_choice("ARKODE method", name, names));
}

void arkode_check(int flag, const char* what) {
  if (flag < 0)
    throw RunError(fmt::format("ARKODE: {} failed: {}", what, ARKStepGetReturnFlagName(flag)));
}

}  // namespace fissure
