#pragma once
// TAGCON construction of a garment on the built-in mannequin, as `sartor
// construct` runs it and `sartor drape` starts with: read the pattern, place
// its packs and find its seams (src/garment/tagcon), mesh the panels
// (src/garment/garment_mesh), and report and write the result.

#include "app/cli.hpp"
#include "app/commands.hpp"
#include "contact/body_spec.hpp"
#include "garment/garment_mesh.hpp"
#include "garment/pattern.hpp"
#include "garment/tagcon.hpp"
#include "mesh/panel_mesher.hpp"

#include <nlohmann/json_fwd.hpp>

#include <memory>
#include <string>
#include <vector>

namespace sartor {

struct ConstructedGarment {
  std::string path;       // the pattern file
  std::string seams_file; // user seams and tags (garment/seam_overrides.hpp); empty: none
  garment::Pattern pattern;
  garment::TagconOptions tagcon;
  PanelMeshOptions mesh_options;
  garment::Construction construction;
  garment::GarmentMesh garment;
  std::shared_ptr<const contact::GarmentBody> body; // what the garment is placed on
  double body_seconds = 0.0;                        // the body and its distance queries, s
  double mesh_seconds = 0.0;                        // meshing the panels, s
};

// --edge-length and --min-angle: how finely the panels are meshed;
// --no-prefold: the creased panels start flat (docs/pleats.md).
const std::vector<OptionSpec>& panel_mesh_option_specs();
// Throws InputError for a value out of range.
PanelMeshOptions panel_mesh_options(const Options& options);

// Reads PATTERN.json and constructs it around the built-in mannequin,
// pre-folding its creased fold lines when `prefold`; a `seams_file` (not
// empty) retags panels before TAGCON and overrides or completes its seams
// after. Throws InputError for a bad pattern or seams file, or a pattern
// TAGCON cannot construct.
// `body_spec`: "default" or a body with a skeleton (contact::garment_body),
// e.g. "mannequin measurements=me.json"; `where` names it in errors.
ConstructedGarment construct_garment(const std::string& path, const PanelMeshOptions& mesh_options,
                                     const std::string& seams_file = "", bool prefold = true,
                                     const std::string& body_spec = "default",
                                     const std::string& where = "option --body");

// --seams-file of construct and drape.
OptionSpec seams_file_option_spec();

// Prints the one-line summary and the seam table (PetscPrintf, rank 0).
void print_construction(const ConstructedGarment& garment);

// construct.json: the run's metadata (`command`, the pattern file, the body,
// units) and the description of the construction (cylinders, packs, panels,
// seams, lines, T-seams, mesh, timings).
nlohmann::json construction_summary(const Invocation& invocation, const std::string& command,
                                    const std::string& pattern_path,
                                    const ConstructedGarment& garment);

// Rank 0: garment.obj, seams.json, construct.json (= `summary`),
// pattern_seams.svg and placement.svg in `directory` (created).
void write_construction(const std::string& directory, const ConstructedGarment& garment,
                        const nlohmann::json& summary);

} // namespace sartor
