#include "app/edit_case.hpp"

#include "app/commands.hpp"
#include "app/edit_design.hpp"
#include "app/seam_case.hpp"
#include "common/csv.hpp"
#include "common/error.hpp"
#include "common/output.hpp"
#include "common/yaml_input.hpp"
#include "fem/petsc_call.hpp"
#include "garment/pattern_edit.hpp"
#include "solvers/sensitivity.hpp"
#include "solvers/statics.hpp"

#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <tuple>

namespace sartor {

namespace {

// The pattern's outline lines: id, and the kind of its curve.
using LineKinds = std::map<std::string, garment::Curve::Kind>;

[[noreturn]] void edit_error(const std::string& path, const YAML::Node& node,
                             const std::string& key, const std::string& what) {
  throw InputError(path, node.Mark().line + 1, key + ": " + what);
}

void reject_unknown_keys(const std::string& path, const YAML::Node& node, const std::string& key,
                         const std::set<std::string>& known) {
  for (const auto& entry : node) {
    const std::string name = entry.first.Scalar();
    if (!known.count(name)) {
      std::string list;
      for (const std::string& k : known)
        list += (list.empty() ? "" : ", ") + k;
      edit_error(path, entry.first, key + "." + name, "unknown key (known: " + list + ")");
    }
  }
}

// A finite number (`item`, under `key`) at most `limit` in size; `unit`
// (" m" or "") follows the numbers in the message.
double read_bounded(const std::string& path, const YAML::Node& item, const std::string& key,
                    double limit, const std::string& unit) {
  double value = NAN;
  try {
    value = item.as<double>();
  } catch (const YAML::Exception&) {
    edit_error(path, item, key, "'" + item.Scalar() + "' is not a number");
  }
  if (!std::isfinite(value) || std::abs(value) > limit)
    edit_error(path, item, key,
               item.Scalar() + unit + ": must be finite and at most " + format_number(limit) +
                   unit);
  return value;
}

// Two finite numbers [a, b] (`node`, under `key`), each at most `limit`.
Eigen::Vector2d read_pair(const std::string& path, const YAML::Node& node, const std::string& key,
                          const std::string& what, double limit) {
  if (!node.IsSequence() || node.size() != 2)
    edit_error(path, node, key, "must be two numbers [" + what + "]");
  return {read_bounded(path, node[0], key, limit, ""), read_bounded(path, node[1], key, limit, "")};
}

// Sensitive Couture's Psi tensor of a move: the corners move by Psi times
// the step's pointer movement. `psi: [[a, b], [c, d]]` gives it whole,
// `along: [ex, ey]` is e e^T (e normalised): the corners shadow the
// pointer along e only.
Eigen::Matrix2d read_psi(const std::string& path, const YAML::Node& node, const std::string& key) {
  if (node["along"]) {
    const Eigen::Vector2d e = read_pair(path, node["along"], key + ".along", "ex, ey", 1e3);
    if (e.norm() == 0.0) edit_error(path, node["along"], key + ".along", "the direction is zero");
    return e.normalized() * e.normalized().transpose();
  }
  const YAML::Node psi = node["psi"];
  if (!psi.IsSequence() || psi.size() != 2)
    edit_error(path, psi, key + ".psi", "must be two rows [[a, b], [c, d]]");
  Eigen::Matrix2d tensor;
  for (std::size_t r = 0; r < 2; ++r)
    tensor.row(Eigen::Index(r)) =
        read_pair(path, psi[r], key + ".psi", "a, b (a row of the tensor)", 1e3).transpose();
  return tensor;
}

// A curve edit's `control`: 1 or 2, the inner control point of a Bezier
// line that moves (its corners are `end`'s).
int read_control(const std::string& path, const YAML::Node& node, const std::string& key,
                 garment::Curve::Kind kind) {
  if (node["end"])
    edit_error(path, node["end"], key + ".end",
               "a move is of corners (end) or of a control point (control), not both");
  if (kind != garment::Curve::Kind::bezier)
    edit_error(path, node["control"], key + ".control",
               "line '" + node["line"].Scalar() + "' is " + garment::name_of(kind) +
                   ": only a Bezier line has control points to move");
  const std::string control = node["control"].IsScalar() ? node["control"].Scalar() : "";
  if (control != "1" && control != "2")
    edit_error(path, node["control"], key + ".control",
               "must be 1 or 2 (the Bezier's inner control points; its ends are corners)");
  return control == "1" ? 1 : 2;
}

// A move {line, by[, end]}; or, where the step has a pointer movement,
// {line, psi | along[, end]}, its `by` the tensor times the pointer's.
CornerMove read_move(const std::string& path, const YAML::Node& node, const std::string& key,
                     const LineKinds& outline_lines,
                     const std::optional<Eigen::Vector2d>& pointer) {
  if (!node.IsMap()) edit_error(path, node, key, "a move is a mapping {line, by[, end]}");
  reject_unknown_keys(path, node, key, {"line", "by", "end", "control", "psi", "along"});
  CornerMove move;
  if (!node["line"] || !node["line"].IsScalar())
    edit_error(path, node, key + ".line", "missing: the id of an outline line of the pattern");
  move.line = node["line"].Scalar();
  if (!outline_lines.count(move.line))
    edit_error(path, node["line"], key + ".line",
               "'" + move.line + "' is not an outline line of the pattern");
  const int given = int(bool(node["by"])) + int(bool(node["psi"])) + int(bool(node["along"]));
  if (given != 1)
    edit_error(path, node, key,
               "give one of by (the move [dx, dy] in m), psi or along (with the step's pointer)");
  if (node["by"]) {
    move.by = read_pair(path, node["by"], key + ".by", "dx, dy in m", 0.5);
  } else {
    if (!pointer)
      edit_error(path, node, key,
                 "psi and along map the step's pointer movement: give the step a pointer [dx, dy]");
    move.by = read_psi(path, node, key) * *pointer;
    if (move.by.lpNorm<Eigen::Infinity>() > 0.5)
      edit_error(path, node, key,
                 "the pointer moves the corners by " + format_number(move.by.norm()) +
                     " m: moves are at most 0.5 m");
  }
  if (node["control"]) {
    move.control = read_control(path, node, key, outline_lines.at(move.line));
    return move;
  }
  if (node["end"]) {
    const std::string end = node["end"].IsScalar() ? node["end"].Scalar() : "";
    if (end == "start")
      move.which = CornerMove::Which::start;
    else if (end == "end")
      move.which = CornerMove::Which::end;
    else
      edit_error(path, node["end"], key + ".end",
                 "must be 'start' or 'end' (the corner of the line that moves; without "
                 "it, both move)");
  }
  return move;
}

// Three finite numbers [x, y, z] under `name` of `parent`, each at most
// `limit` in size.
Eigen::Vector3d read_point(const std::string& path, const YAML::Node& parent,
                           const std::string& name, const std::string& key, const std::string& what,
                           double limit) {
  const YAML::Node node = parent[name];
  if (!node) edit_error(path, parent, key, "missing: " + what);
  if (!node.IsSequence() || node.size() != 3)
    edit_error(path, node, key, "must be three numbers [x, y, z] in m (" + what + ")");
  Eigen::Vector3d point;
  for (std::size_t i = 0; i < 3; ++i)
    point[Eigen::Index(i)] = read_bounded(path, node[i], key, limit, " m");
  return point;
}

DragRequest read_drag(const std::string& path, const YAML::Node& node, const std::string& key) {
  if (!node.IsMap()) edit_error(path, node, key, "a drag is a mapping {point, by}");
  reject_unknown_keys(path, node, key, {"point", "by"});
  DragRequest drag;
  drag.point = read_point(path, node, "point", key + ".point",
                          "the point of the drape to drag, [x, y, z] in m", 100.0);
  drag.by =
      read_point(path, node, "by", key + ".by", "where it should move, [dx, dy, dz] in m", 0.5);
  if (drag.by.norm() == 0.0) edit_error(path, node["by"], key + ".by", "the drag is zero");
  return drag;
}

// A drag, or a non-empty list of drags.
std::vector<DragRequest> read_drags(const std::string& path, const YAML::Node& node,
                                    const std::string& key) {
  if (!node.IsSequence()) return {read_drag(path, node, key)};
  if (node.size() == 0) edit_error(path, node, key, "must be a drag or a non-empty list of drags");
  std::vector<DragRequest> drags;
  for (std::size_t d = 0; d < node.size(); ++d)
    drags.push_back(read_drag(path, node[d], key + "[" + std::to_string(d) + "]"));
  return drags;
}

// A non-empty list of moves; a corner two moves name (the shared end of two
// lines moved together) moves once, and two different moves of it (or of a
// control point) are an error.
std::vector<CornerMove> read_moves(const std::string& path, const YAML::Node& moves,
                                   const std::string& key, const garment::Pattern& pattern,
                                   const LineKinds& outline_lines,
                                   const std::optional<Eigen::Vector2d>& pointer = std::nullopt) {
  if (!moves.IsSequence() || moves.size() == 0)
    edit_error(path, moves, key, "must be a non-empty list of moves");
  std::vector<CornerMove> result;
  std::map<garment::OutlinePoint, CornerMove> points;
  for (std::size_t m = 0; m < moves.size(); ++m) {
    const std::string move_key = key + "[" + std::to_string(m) + "]";
    const CornerMove& move =
        result.emplace_back(read_move(path, moves[m], move_key, outline_lines, pointer));
    for (const auto& point :
         garment::moved_outline_points(pattern, move.line, move.which, move.control)) {
      const auto [entry, fresh] = points.emplace(point, move);
      if (fresh || entry->second.by == move.by) continue;
      if (point.control > 0)
        edit_error(path, moves[m], move_key,
                   "moves control point " + std::to_string(point.control) + " of line '" +
                       move.line + "' a second time, differently");
      edit_error(path, moves[m], move_key,
                 "the moves of lines '" + entry->second.line + "' and '" + move.line +
                     "' move their shared corner differently");
    }
  }
  return result;
}

// The named parameter `name` (named_edit_parameters), or an error listing
// the names there are.
const EditParameter& named_parameter(const std::string& path, const YAML::Node& node,
                                     const std::string& key, const std::string& name,
                                     const std::map<std::string, EditParameter>& named) {
  const auto found = named.find(name);
  if (found != named.end()) return found->second;
  std::string list;
  for (const auto& [known, parameter] : named)
    list += (list.empty() ? "" : ", ") + known;
  edit_error(path, node, key,
             "'" + name + "' is not a parameter of the pattern (" +
                 (list.empty() ? "it has none: no sloper parameters, no darts" : "known: " + list) +
                 ")");
}

// The design parameters of a drag step: each a named parameter, or
// {name, moves} with its moves per unit.
std::vector<EditParameter> read_parameters(const std::string& path, const YAML::Node& node,
                                           const std::string& key, const garment::Pattern& pattern,
                                           const LineKinds& outline_lines,
                                           const std::map<std::string, EditParameter>& named) {
  if (!node.IsSequence() || node.size() == 0)
    edit_error(path, node, key,
               "must be a non-empty list of parameters (a parameter's name, or {name, moves})");
  std::vector<EditParameter> parameters;
  for (std::size_t j = 0; j < node.size(); ++j) {
    const std::string parameter_key = key + "[" + std::to_string(j) + "]";
    const YAML::Node parameter = node[j];
    if (parameter.IsScalar()) {
      parameters.push_back(
          named_parameter(path, parameter, parameter_key, parameter.Scalar(), named));
      continue;
    }
    if (!parameter.IsMap())
      edit_error(path, parameter, parameter_key, "a parameter is a name or {name, moves}");
    reject_unknown_keys(path, parameter, parameter_key, {"name", "moves"});
    if (!parameter["moves"])
      edit_error(path, parameter, parameter_key + ".moves", "missing: its moves per unit");
    parameters.push_back(
        {parameter["name"] && parameter["name"].IsScalar() ? parameter["name"].Scalar()
                                                           : "parameter " + std::to_string(j + 1),
         read_moves(path, parameter["moves"], parameter_key + ".moves", pattern, outline_lines)});
  }
  return parameters;
}

// A step's `change`: {NAME: by, ...}, named parameters changed by `by` (m);
// the corners they move are checked against the 0.5 m limit of a move.
std::vector<ParameterChange> read_changes(const std::string& path, const YAML::Node& node,
                                          const std::string& key,
                                          const std::map<std::string, EditParameter>& named) {
  if (!node.IsMap() || node.size() == 0)
    edit_error(path, node, key, "must be a mapping {parameter: change in m, ...}");
  std::vector<ParameterChange> changes;
  for (const auto& entry : node) {
    const std::string name = entry.first.Scalar();
    const std::string entry_key = key + "." + name;
    ParameterChange change{named_parameter(path, entry.first, entry_key, name, named), NAN};
    try {
      change.by = entry.second.as<double>();
    } catch (const YAML::Exception&) {
      edit_error(path, entry.second, entry_key, "'" + entry.second.Scalar() + "' is not a number");
    }
    double largest = 0.0;
    for (const CornerMove& move : change.parameter.moves)
      largest = std::max(largest, std::abs(change.by) * move.by.norm());
    if (!std::isfinite(change.by) || largest > 0.5)
      edit_error(path, entry.second, entry_key,
                 "a change of " + entry.second.Scalar() + " m moves corners by " +
                     format_number(largest) + " m: moves are finite and at most 0.5 m");
    changes.push_back(change);
  }
  return changes;
}

// The line of `panel` with this id.
const garment::OutlineLine& outline_line(const garment::Panel& panel, const std::string& id) {
  for (const garment::OutlineLine& line : panel.outline)
    if (line.id == id) return line;
  throw std::logic_error("named_edit_parameters: dart leg '" + id + "' is not on its panel");
}

// DART.slide, DART.open and DART.depth of one dart (named_edit_parameters).
void add_dart_parameters(const garment::Panel& panel, const garment::Dart& dart,
                         std::map<std::string, EditParameter>* named) {
  using Which = CornerMove::Which;
  const Eigen::Vector2d first_base = outline_line(panel, dart.first_leg).curve.start();
  const Eigen::Vector2d apex = outline_line(panel, dart.first_leg).curve.end();
  const Eigen::Vector2d second_base = outline_line(panel, dart.second_leg).curve.end();
  const Eigen::Vector2d along = (second_base - first_base).normalized();
  const Eigen::Vector2d axis = (apex - 0.5 * (first_base + second_base)).normalized();
  const auto add = [&](const std::string& what, std::vector<CornerMove> moves) {
    (*named)[dart.id + "." + what] = {dart.id + "." + what, std::move(moves)};
  };
  add("slide", {{dart.first_leg, Which::both, along}, {dart.second_leg, Which::end, along}});
  add("open",
      {{dart.first_leg, Which::start, -0.5 * along}, {dart.second_leg, Which::end, 0.5 * along}});
  add("depth", {{dart.first_leg, Which::end, axis}});
}

// Whether any move of the list `moves` maps the pointer (psi or along).
bool maps_pointer(const YAML::Node& moves) {
  if (!moves.IsSequence()) return false;
  for (const auto& move : moves)
    if (move.IsMap() && (move["psi"] || move["along"])) return true;
  return false;
}

// A drag step: its drags and design parameters (`parameters`, or its
// `moves` as one).
void read_drag_step(const std::string& path, const YAML::Node& step, const std::string& key,
                    const garment::Pattern& pattern, const LineKinds& outline_lines,
                    const std::map<std::string, EditParameter>& named, EditStep* edit) {
  edit->drags = read_drags(path, step["drag"], key + ".drag");
  if (step["change"])
    edit_error(path, step["change"], key + ".change",
               "a drag step finds its parameters' change: give it parameters (or moves), "
               "not a change");
  if (step["parameters"] && step["moves"])
    edit_error(path, step["moves"], key + ".moves",
               "a drag step has moves (one parameter) or parameters, not both");
  if (step["parameters"]) {
    edit->parameters = read_parameters(path, step["parameters"], key + ".parameters", pattern,
                                       outline_lines, named);
    return;
  }
  if (!step["moves"])
    edit_error(path, step, key + ".moves",
               "missing: the drag's parameters (or moves: the direction of one)");
  edit->moves = read_moves(path, step["moves"], key + ".moves", pattern, outline_lines);
  edit->parameters = {{edit->name, edit->moves}};
}

EditStep read_step(const std::string& path, const YAML::Node& step, const std::string& key,
                   std::size_t index, const garment::Pattern& pattern,
                   const LineKinds& outline_lines,
                   const std::map<std::string, EditParameter>& named) {
  if (!step.IsMap())
    edit_error(path, step, key,
               "an edit is a mapping {name, moves, change} or {name, drag, moves|parameters}");
  reject_unknown_keys(path, step, key,
                      {"name", "moves", "change", "pointer", "drag", "parameters"});
  EditStep edit;
  edit.name = step["name"] && step["name"].IsScalar() ? step["name"].Scalar()
                                                      : "edit " + std::to_string(index + 1);
  std::optional<Eigen::Vector2d> pointer;
  if (step["pointer"]) {
    if (!maps_pointer(step["moves"]))
      edit_error(path, step["pointer"], key + ".pointer",
                 "no move maps the pointer: give moves with psi or along");
    pointer = read_pair(path, step["pointer"], key + ".pointer", "dx, dy in m", 0.5);
  }
  if (step["drag"]) {
    read_drag_step(path, step, key, pattern, outline_lines, named, &edit);
    return edit;
  }
  if (step["parameters"])
    edit_error(path, step["parameters"], key + ".parameters",
               "parameters are for a drag: give the step a drag, or moves or a change");
  if (!step["moves"] && !step["change"])
    edit_error(path, step, key + ".moves",
               "missing: the list of moves, or a change of the pattern's parameters");
  if (step["moves"])
    edit.moves = read_moves(path, step["moves"], key + ".moves", pattern, outline_lines, pointer);
  if (step["change"]) edit.changes = read_changes(path, step["change"], key + ".change", named);
  return edit;
}

} // namespace

std::map<std::string, EditParameter> named_edit_parameters(const garment::Pattern& pattern) {
  std::map<std::string, EditParameter> named;
  for (const garment::SloperParameter& parameter : pattern.parameters) {
    EditParameter& edit = named[parameter.id];
    edit.name = parameter.id;
    for (const garment::ParameterMove& move : parameter.moves) {
      const CornerMove::Which which =
          move.corner == garment::ParameterMove::Corner::start ? CornerMove::Which::start
          : move.corner == garment::ParameterMove::Corner::end ? CornerMove::Which::end
                                                               : CornerMove::Which::both;
      edit.moves.push_back({move.line, which, move.per_unit});
    }
  }
  for (const garment::Panel& panel : pattern.panels)
    for (const garment::Dart& dart : panel.darts)
      add_dart_parameters(panel, dart, &named);
  return named;
}

std::vector<EditStep> read_edit_file(const std::string& path, const garment::Pattern& pattern) {
  const YAML::Node root = load_yaml_input(path, "edit file");
  if (!root.IsMap()) throw InputError(path, 1, "an edit file is a mapping with the key 'steps'");
  reject_unknown_keys(path, root, "(top level)", {"steps"});
  const YAML::Node steps = root["steps"];
  if (!steps) throw InputError(path, 1, "steps: missing: the list of edits, applied in turn");
  if (!steps.IsSequence() || steps.size() == 0)
    edit_error(path, steps, "steps", "must be a non-empty list of edits");
  LineKinds outline_lines;
  for (const auto& panel : pattern.panels)
    for (const auto& line : panel.outline)
      outline_lines[line.id] = line.curve.kind;
  const std::map<std::string, EditParameter> named = named_edit_parameters(pattern);
  std::vector<EditStep> result;
  for (std::size_t s = 0; s < steps.size(); ++s)
    result.push_back(read_step(path, steps[s], "steps[" + std::to_string(s) + "]", s, pattern,
                               outline_lines, named));
  return result;
}

garment::InteriorCoordinates interior_coordinates_option(const Options& options) {
  const std::string kind = options.text("edit-interior");
  if (kind == "positive") return garment::InteriorCoordinates::positive_mean_value;
  if (kind == "mean-value") return garment::InteriorCoordinates::mean_value;
  throw InputError("option --edit-interior: unknown kind '" + kind + "' (positive or mean-value)");
}

void check_edit_kinds(const Options& options) {
  const auto check = [&](const std::string& option, const std::vector<std::string>& kinds) {
    const std::string kind = options.text(option);
    if (std::find(kinds.begin(), kinds.end(), kind) != kinds.end()) return;
    std::string listed;
    for (const std::string& k : kinds)
      listed += (listed.empty() ? "" : ", ") + k;
    throw InputError("option --" + option + ": unknown kind '" + kind + "' (" + listed + ")");
  };
  check("edit-start", {"auto", "gmls", "linear", "unchanged", "geometric"});
  check("edit-anchors", {"fresh", "kept"});
  check("edit-friction", {"staged", "held"});
}

const std::vector<OptionSpec>& edit_option_specs() {
  static const std::vector<OptionSpec> specs{
      {"edit-start", "KIND", "auto",
       "the start of each warm re-solve, pushed out of the body: auto (of the three below, the "
       "one of least potential energy), gmls (GMLS over the designs solved so far; the linear "
       "prediction while there is one), linear (x + S dp from the last design), unchanged "
       "(the last drape as it is) or geometric (the thesis' barycentric transfer of the last "
       "drape onto the edited pattern; not among auto's)"},
      {"edit-anchors", "KIND", "fresh",
       "the friction anchors of each re-solve: fresh (set where the start touches the body) "
       "or kept (the last drape's)"},
      {"edit-friction", "KIND", "staged",
       "how each re-solve meets the bodies' friction: staged (as the drape's sewing stages: "
       "the stage before the last again without friction, then the last with anchors set "
       "afresh where it left the cloth; when the drape was sewn in stages and the anchors are "
       "fresh) or held (friction from the re-solve's start, anchored where it starts)"},
      {"sensitivity-tangent", "KIND", "exact",
       "the sensitivity's tangent: exact (the derivative) or projected (the minimiser's, "
       "PSD-projected element Hessians: damps the wrinkles' negative curvature)"},
      {"gmls-degree", "N", "2", "degree of GMLS's polynomial basis: 1 (Sensitive Couture's) or 2"},
      {"edit-smoothing-quality", "Q", "0.3",
       "Delaunay smoothing (edge flips, the vertices kept) of an edited rest mesh whose worst "
       "triangle's quality (sqrt(3) times the incircle's diameter over the longest edge: 1 "
       "equilateral) fell below Q (0: never)"},
      {"edit-interior", "KIND", "positive",
       "how a panel's interior follows its outline's edits: positive (positive mean value "
       "coordinates, Lipman et al., never negative in a notched panel) or mean-value "
       "(Floater's, negative behind a notch)"},
      {"edit-max-newton", "N", "0",
       "the most Newton iterations of each solve (sewing stage or contact round) of a "
       "re-solve; a start that needs more fails, and the next is tried (0: the drape's "
       "-snes_max_it)"},
      {"no-edit-retry", "", "",
       "keep a re-solve that fails (not converged, or not certified) instead of re-solving "
       "again from the other starts (by increasing potential energy)"},
      {"no-edit-outputs", "", "",
       "write summary.json and the edited patterns only, not the predicted and re-solved "
       "drapes"},
  };
  return specs;
}

} // namespace sartor
