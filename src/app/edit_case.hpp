#pragma once
// `sartor edit` (docs/sensitivity.md#sartor-edit): after a static drape,
// a sequence of pattern edits (outline corners moved, read from an edit
// file), each predicted by the design sensitivity (linear) and by GMLS over
// the designs solved so far, then re-solved warm from the prediction and
// certified; the edited pattern, the predictions and the re-solved drape
// written per edit, with the prediction errors and CPU times.

#include "app/cli.hpp"
#include "app/cloth_case.hpp"
#include "app/commands.hpp"
#include "fem/cloth_output.hpp"
#include "garment/pattern.hpp"
#include "garment/pattern_edit.hpp"
#include "mesh/seams.hpp"
#include "mesh/triangle_mesh.hpp"

#include <nlohmann/json.hpp>

#include <Eigen/Core>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace sartor {

// One move of an edit file: the corners of an outline line (both, or its
// start or its end) move by `by` (pattern coordinates, m); or, with
// `control` 1 or 2, that inner control point of a Bezier line (a curve edit).
struct CornerMove {
  std::string line;
  using Which = garment::LineCorners;
  Which which = Which::both;
  Eigen::Vector2d by = Eigen::Vector2d::Zero();
  int control = 0;
};

// A drag of the drape (Sensitive Couture §4.1, direct 3D editing): the cloth
// vertex nearest `point` in the drape the step starts from is asked to move
// by `by` (m).
struct DragRequest {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d by = Eigen::Vector3d::Zero();
};

// A design parameter of a drag step: its moves per unit of it.
struct EditParameter {
  std::string name;
  std::vector<CornerMove> moves;
};

// A named parameter changed by a step (a slider): `by` units of it (m).
struct ParameterChange {
  EditParameter parameter;
  double by = 0.0;
};

// An edit: its moves and its parameter changes, added; or, with drags, the
// design parameters (the moves of a step with one) whose change dg makes the
// linear response S dg (S: the dragged vertices' sensitivities to the
// parameters, 3 rows per drag) the least-squares fit to the drags, with the
// least |dg| where several fit as well.
struct EditStep {
  std::string name;
  std::vector<CornerMove> moves;
  std::vector<ParameterChange> changes;
  std::vector<DragRequest> drags;
  std::vector<EditParameter> parameters;
};

// The parameters an edit may name: the pattern's sloper parameters (by id)
// and, per dart, DART.slide (the dart rides the outline: its three corners
// move along the line from its first to its second base corner), DART.open
// (its base corners move apart along that line, half a unit each) and
// DART.depth (its apex moves away from its bases' midpoint); per unit, m.
std::map<std::string, EditParameter> named_edit_parameters(const garment::Pattern& pattern);

// Reads an edit file (YAML; docs/sensitivity.md#the-edit-file) against the
// pattern its lines must belong to. Throws InputError "FILE:LINE: KEY: what
// is wrong".
std::vector<EditStep> read_edit_file(const std::string& path, const garment::Pattern& pattern);

// --edit-interior: the coordinates a panel's interior follows its outline
// by. Throws InputError naming the option for an unknown kind.
garment::InteriorCoordinates interior_coordinates_option(const Options& options);

// Checks the kinds --edit-start, --edit-anchors and --edit-friction name,
// before anything is solved. Throws InputError naming the option.
void check_edit_kinds(const Options& options);

// The options of `sartor edit` beyond drape's.
const std::vector<OptionSpec>& edit_option_specs();

// What the garment is, for the edit: the pattern, and per triangle of the
// cloth mesh its panel (an index into pattern.panels); the seams sewn.
struct EditGarment {
  garment::Pattern pattern;
  std::vector<int> panel_of_triangle;
  std::vector<Seam> seams;
  ClothOutputLabels labels; // for the drapes written
};

// The edits' results, filled in by the drape's after_statics.
struct EditRun {
  bool ran = false;
  nlohmann::json summary = nlohmann::json::object();
  std::string message; // the closing lines
  bool all_certified = false;
  std::vector<std::string> not_converged; // the folders of the edits no re-solve converged
};

// The file in a drape's output directory holding its final state (a static
// checkpoint: positions, friction anchors, the contact penalty's scale and
// the solve's report), which `sartor edit DRAPE_DIR` resumes from.
inline constexpr const char* drape_state_file = "drape_state.h5";

// Where the drape the edits start from was made, and what it cost: the
// edits' speed-ups are against its CPU time from scratch.
struct EditDrapeSource {
  // `sartor edit DRAPE_DIR`: the directory of the drape resumed, and the CPU
  // time (s) its summary.json records for the drape from scratch; "" when
  // this process draped it.
  std::string directory;
  double recorded_cpu = 0.0;
  double started_cpu = 0.0; // the process CPU time (s) when this process's drape began
};

// Sets cloth->after_statics so that, once the drape converged, the edits of
// `steps` are predicted, re-solved and written to DIRECTORY/edit_NN (rank 0).
void attach_edit(const Options& options, const std::string& directory, EditGarment garment,
                 std::vector<EditStep> steps, const EditDrapeSource& drape, CaseCloth* cloth,
                 const std::shared_ptr<EditRun>& run);

// What `sartor edit` asks of the drape: the edits, where their results go,
// and the drape resumed (a DRAPE_DIR's; directory "" drapes afresh).
struct EditRequest {
  std::vector<EditStep> steps;
  std::shared_ptr<EditRun> run = std::make_shared<EditRun>();
  EditDrapeSource drape;
};

// `sartor drape` (edit null) and `sartor edit`: constructs and drapes the
// pattern of the invocation's first argument; with `edit`, the edits follow
// the converged drape (app/drape_command.cpp).
int drape_pattern(const Invocation& invocation, const EditRequest* edit);

} // namespace sartor
