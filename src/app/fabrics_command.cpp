// sartor fabrics: the built-in fabric parameter sets.

#include "app/commands.hpp"
#include "fem/petsc_call.hpp"
#include "material/fabric.hpp"

#include <nlohmann/json.hpp>
#include <petscsys.h>

namespace sartor {

const CommandSpec& fabrics_command() {
  static const CommandSpec spec{
      "fabrics",
      "list the built-in fabric parameter sets (thesis Table 5.1)",
      "sartor fabrics [--json]",
      "Lists the ten creep parameter sets of thesis Table 5.1 by the names that\n"
      "--fabric accepts (e.g. cotton_twill:warp). Table 5.1 gives no immediate-elastic\n"
      "stiffness: presets assume a linear elastic modulus of 2E (override with\n"
      "--elastic-modulus or a fabric file).",
      {{"json", "", "", "print JSON instead of a table"}},
      0};
  return spec;
}

int run_fabrics(const Invocation& invocation) {
  nlohmann::json list = nlohmann::json::array();
  if (!invocation.options.flag("json")) {
    SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD, "%-20s %10s %7s %12s %14s %16s\n", "name",
                                "E (N/m)", "alpha", "lambda_load", "lambda_unload",
                                "elastic (N/m)"));
  }
  for (const auto& preset : fabric_presets()) {
    const Fabric fabric = preset_fabric(preset.name);
    for (Direction direction : {Direction::warp, Direction::weft}) {
      const DirectionalMaterial& m = fabric.in(direction);
      const std::string name = fabric.name + ":" + name_of(direction);
      list.push_back({{"name", name},
                      {"E_N_per_m", m.creep.creep_modulus},
                      {"alpha", m.creep.alpha},
                      {"lambda_load_per_s", m.creep.lambda_load},
                      {"lambda_unload_per_s", m.creep.lambda_unload},
                      {"elastic_modulus_N_per_m", m.elastic.initial_modulus()}});
      if (!invocation.options.flag("json")) {
        SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD, "%-20s %10.0f %7.3f %12.4g %14.4g %16.0f\n",
                                    name.c_str(), m.creep.creep_modulus, m.creep.alpha,
                                    m.creep.lambda_load, m.creep.lambda_unload,
                                    m.elastic.initial_modulus()));
      }
    }
  }
  if (invocation.options.flag("json")) {
    SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s\n", list.dump(2).c_str()));
  } else {
    SartorPetscCall(PetscPrintf(
        PETSC_COMM_WORLD, "\ncreep: thesis Table 5.1; elastic: assumed 2E (not in the thesis)\n"));
  }
  return 0;
}

} // namespace sartor
