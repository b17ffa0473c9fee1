// sartor construct: TAGCON garment construction (thesis ch. 3) from a tagged
// and packed pattern: positioned panels, seams, pictures.

#include "app/commands.hpp"
#include "app/garment_construction.hpp"
#include "common/error.hpp"
#include "fem/petsc_call.hpp"

#include <nlohmann/json.hpp>
#include <petscsys.h>

namespace sartor {

const CommandSpec& construct_command() {
  static const CommandSpec spec{
      "construct",
      "TAGCON: place a tagged, packed pattern around the body and find its seams",
      "sartor construct PATTERN.json [--body SPEC] [--output DIR] [--edge-length M] "
      "[--min-angle DEG] [--seams-file FILE]",
      "Constructs a garment from a pattern (docs/pattern-format.md) as the thesis'\n"
      "TAGCON does (ch. 3; docs/tagcon.md): cylinders fitted to the body's skeleton\n"
      "(torso, arms, legs, neck, head); each pack's bounding box wrapped onto its\n"
      "half cylinder (front or back), layers outside; then the seams: inter-layer\n"
      "(T- and Y-seams), intra-pack (closest line in the field of view), inter-\n"
      "cylinder (ring match with clicks) and inter-half-cylinder (greedy on the\n"
      "objective M(i, j) = M_ld M_lo M_ll M_lc M_sa, eqs. 3.1-3.6); seams whose sweep\n"
      "penetrates the body are deleted. Each seam carries its certainty M.\n"
      "A garment TAGCON cannot construct (a panel spanning two cylinders, thesis\n"
      "Fig. 3.9; a pack none of whose lines can be seamed) is an error that names\n"
      "the lines and the reason. A --seams-file retags panels and overrides or\n"
      "completes the seams (docs/pattern-format.md#user-seams-and-tags); a\n"
      "pattern's darts are always sewn leg to leg.\n\n"
      "Output in DIR: garment.obj (all panels meshed and placed; vt = material uv\n"
      "in m; g/usemtl per panel), seams.json (seam file for `sartor run\n"
      "--seams-file`, vertex numbers of garment.obj), construct.json (cylinders,\n"
      "pack placements, every line in 3D with its seam or the reason it has none,\n"
      "seams with kind, certainty and the five factors, timings), pattern_seams.svg\n"
      "(the pattern with its seams, blue = certain to red = uncertain),\n"
      "placement.svg (front and side views of the placed panels on the body).\n\n"
      "examples:\n"
      "  sartor construct cases/patterns/tshirt.json --output out/tshirt\n"
      "  sartor run --mesh obj --mesh-file out/tshirt/garment.obj \\\n"
      "      --seams-file out/tshirt/seams.json --body mannequin ...",
      [] {
        std::vector<OptionSpec> options{
            {"body", "SPEC", "default",
             "the body: default (the built-in mannequin), \"mannequin measurements=FILE.json "
             "pose=JOINT:DEG,...\" (sized, posed) or \"mesh file=BODY.obj "
             "skeleton=SKELETON.json\" (docs/bodies.md)"},
            {"output", "DIR", "out/construct",
             "output folder (created; files in it are replaced)"}};
        options.insert(options.end(), panel_mesh_option_specs().begin(),
                       panel_mesh_option_specs().end());
        options.push_back(seams_file_option_spec());
        return options;
      }(),
      1};
  return spec;
}

int run_construct(const Invocation& invocation) {
  const Options& options = invocation.options;
  const std::string path = invocation.command_line.positionals.at(0);
  const std::string directory = options.text("output");
  const ConstructedGarment constructed =
      construct_garment(path, panel_mesh_options(options),
                        options.is_set("seams-file") ? options.text("seams-file") : "",
                        !options.flag("no-prefold"), options.text("body"));
  print_construction(constructed);
  write_construction(directory, constructed,
                     construction_summary(invocation, "construct", path, constructed));
  SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD, "wrote %s\n", directory.c_str()));
  return 0;
}

} // namespace sartor
