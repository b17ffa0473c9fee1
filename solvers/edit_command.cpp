// sartor edit: a garment draped, then edited (its outline corners moved),
// each edit predicted by the design sensitivity and GMLS and re-solved warm
// (solvers/edit_case.hpp; docs/sensitivity.md#sartor-edit).

#include "common/error.hpp"
#include "fem/petsc_call.hpp"
#include "garment/pattern.hpp"
#include "solvers/commands.hpp"
#include "solvers/edit_case.hpp"

#include <petscsys.h>

namespace sartor {

const CommandSpec& edit_command() {
  static const CommandSpec spec{
      "edit",
      "drape a garment, then edit its pattern and follow the drape by sensitivity",
      "sartor edit PATTERN.json EDITS.yaml [--edit-start auto|gmls|linear|unchanged] "
      "[--edit-anchors fresh|kept] [--gmls-degree 1|2] [--no-edit-retry] [--no-edit-outputs] "
      "[any option of sartor drape]",
      "Drapes PATTERN.json as `sartor drape` does (every drape option applies; the\n"
      "static drape only), then applies the edits of EDITS.yaml in turn (each\n"
      "moves outline corners of the pattern: a whole line, or one end of it; the\n"
      "edits add up; format in docs/sensitivity.md#the-edit-file). For each edit:\n"
      "the design sensitivity at the last drape (one factorisation of the exact\n"
      "tangent) gives the linear prediction x + S dp; GMLS over every design\n"
      "solved so far (values and sensitivities) gives another; the re-solve of\n"
      "the drape's last stage starts from one of them (--edit-start) and its\n"
      "certificate is reported as it is (friction and contact checks included:\n"
      "a re-solve that converged is not called certified unless the certificate\n"
      "says so). A re-solve that fails is tried again from the other starts\n"
      "(not with --no-edit-retry); the edit goes on from the first that is\n"
      "certified, else the first that converged, else the first. Prints one\n"
      "line per edit: the lowest point's change, each\n"
      "prediction's largest vertex error against the re-solved drape, the\n"
      "re-solve and the CPU times against the drape from scratch.\n\n"
      "Output in DIR: what `sartor drape` writes (the drape before the edits),\n"
      "summary.json with \"edit\" (per edit: errors of the unchanged, linear and\n"
      "GMLS predictions, lowest points, re-solve, its attempts, certificate, CPU seconds and\n"
      "speed-ups against the drape from scratch), and per edit DIR/edit_NN/:\n"
      "pattern.svg (outlines before and after), linear/, gmls/ and resolved/\n"
      "(result.h5, result.xmf, final.obj each; not with --no-edit-outputs).\n\n"
      "examples:\n"
      "  sartor edit cases/patterns/skirt.json cases/edit/skirt_hem.yaml "
      "-options_file_yaml cases/garments/skirt_coarse.yaml --output out/edit/skirt\n"
      "  sartor edit cases/patterns/skirt.json cases/edit/skirt_hem_growing.yaml --edit-start "
      "linear",
      [] {
        std::vector<OptionSpec> options = drape_command().options;
        for (OptionSpec& option : options) {
          if (option.name == "output") option.fallback = "out/edit";
          if (option.name == "bending-model") {
            option.fallback = "discrete_shell";
            option.help = "patch, discrete_shell or quadratic (hinges); edit keeps the hinges "
                          "(docs/sensitivity.md#bending-models)";
          }
        }
        for (const OptionSpec& option : edit_option_specs())
          options.push_back(option);
        return options;
      }(),
      2};
  return spec;
}

int run_edit(const Invocation& invocation) {
  const auto& positionals = invocation.command_line.positionals;
  // The edits are checked against the pattern before anything is solved.
  EditRequest request;
  request.steps = read_edit_file(positionals.at(1), garment::read_pattern(positionals.at(0)));
  // The hinges: with the bending patches the sample skirt's hem edit is
  // predicted worse (docs/sensitivity.md#bending-models).
  Invocation edit = invocation;
  edit.options.set_default("bending-model", "discrete_shell");
  const int status = drape_pattern(edit, &request);
  if (!request.run->ran) throw SolveFailure("the drape did not converge, so no edit was made");
  if (!request.run->not_converged.empty()) {
    std::string folders;
    for (const std::string& folder : request.run->not_converged)
      folders += (folders.empty() ? "" : ", ") + folder;
    throw SolveFailure("the re-solve of " + folders +
                       " did not converge from any start tried (summary.json: "
                       "edit.steps[].attempts); the edit folders hold the states reached");
  }
  if (!request.run->all_certified) {
    SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD,
                                "sartor edit: not every re-solved drape is certified "
                                "(summary.json: edit.steps[].resolve.certificate)\n"));
  }
  return status;
}

} // namespace sartor
