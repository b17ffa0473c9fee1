#include "app/edit_case.hpp"

#include "app/commands.hpp"
#include "app/edit_design.hpp"
#include "app/seam_case.hpp"
#include "common/csv.hpp"
#include "common/error.hpp"
#include "common/output.hpp"
#include "common/yaml_input.hpp"
#include "fem/petsc_call.hpp"
#include "solvers/sensitivity.hpp"
#include "solvers/statics.hpp"

#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>

namespace sartor {

namespace {

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

CornerMove read_move(const std::string& path, const YAML::Node& node, const std::string& key,
                     const std::set<std::string>& outline_lines) {
  if (!node.IsMap()) edit_error(path, node, key, "a move is a mapping {line, by[, end]}");
  reject_unknown_keys(path, node, key, {"line", "by", "end"});
  CornerMove move;
  if (!node["line"] || !node["line"].IsScalar())
    edit_error(path, node, key + ".line", "missing: the id of an outline line of the pattern");
  move.line = node["line"].Scalar();
  if (!outline_lines.count(move.line))
    edit_error(path, node["line"], key + ".line",
               "'" + move.line + "' is not an outline line of the pattern");
  const YAML::Node by = node["by"];
  if (!by) edit_error(path, node, key + ".by", "missing: the move [dx, dy] in m");
  if (!by.IsSequence() || by.size() != 2)
    edit_error(path, by, key + ".by", "must be two numbers [dx, dy] in m");
  for (std::size_t i = 0; i < 2; ++i) {
    double value = NAN;
    try {
      value = by[i].as<double>();
    } catch (const YAML::Exception&) {
      edit_error(path, by[i], key + ".by", "'" + by[i].Scalar() + "' is not a number");
    }
    if (!std::isfinite(value) || std::abs(value) > 0.5)
      edit_error(path, by[i], key + ".by",
                 "a move of " + by[i].Scalar() + " m: moves are finite and at most 0.5 m");
    move.by[Eigen::Index(i)] = value;
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
  for (std::size_t i = 0; i < 3; ++i) {
    double value = NAN;
    try {
      value = node[i].as<double>();
    } catch (const YAML::Exception&) {
      edit_error(path, node[i], key, "'" + node[i].Scalar() + "' is not a number");
    }
    if (!std::isfinite(value) || std::abs(value) > limit)
      edit_error(path, node[i], key,
                 node[i].Scalar() + " m: must be finite and at most " + format_number(limit) +
                     " m");
    point[Eigen::Index(i)] = value;
  }
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

// The outline corners a move moves, as (panel, corner) with corner i the
// start of line i.
std::vector<std::pair<std::size_t, std::size_t>> moved_corners(const garment::Pattern& pattern,
                                                               const CornerMove& move) {
  std::vector<std::pair<std::size_t, std::size_t>> corners;
  for (std::size_t panel = 0; panel < pattern.panels.size(); ++panel) {
    const auto& outline = pattern.panels[panel].outline;
    for (std::size_t i = 0; i < outline.size(); ++i) {
      if (outline[i].id != move.line) continue;
      if (move.which != CornerMove::Which::end) corners.emplace_back(panel, i);
      if (move.which != CornerMove::Which::start)
        corners.emplace_back(panel, (i + 1) % outline.size());
    }
  }
  return corners;
}

// A non-empty list of moves; a corner two moves name (the shared end of two
// lines moved together) moves once, and two different moves of it are an
// error.
std::vector<CornerMove> read_moves(const std::string& path, const YAML::Node& moves,
                                   const std::string& key, const garment::Pattern& pattern,
                                   const std::set<std::string>& outline_lines) {
  if (!moves.IsSequence() || moves.size() == 0)
    edit_error(path, moves, key, "must be a non-empty list of moves");
  std::vector<CornerMove> result;
  std::map<std::pair<std::size_t, std::size_t>, CornerMove> corners;
  for (std::size_t m = 0; m < moves.size(); ++m) {
    const std::string move_key = key + "[" + std::to_string(m) + "]";
    result.push_back(read_move(path, moves[m], move_key, outline_lines));
    for (const auto& corner : moved_corners(pattern, result.back())) {
      const auto [entry, fresh] = corners.emplace(corner, result.back());
      if (!fresh && entry->second.by != result.back().by)
        edit_error(path, moves[m], move_key,
                   "the moves of lines '" + entry->second.line + "' and '" + result.back().line +
                       "' move their shared corner differently");
    }
  }
  return result;
}

std::vector<EditParameter> read_parameters(const std::string& path, const YAML::Node& node,
                                           const std::string& key, const garment::Pattern& pattern,
                                           const std::set<std::string>& outline_lines) {
  if (!node.IsSequence() || node.size() == 0)
    edit_error(path, node, key, "must be a non-empty list of parameters {name, moves}");
  std::vector<EditParameter> parameters;
  for (std::size_t j = 0; j < node.size(); ++j) {
    const std::string parameter_key = key + "[" + std::to_string(j) + "]";
    const YAML::Node parameter = node[j];
    if (!parameter.IsMap())
      edit_error(path, parameter, parameter_key, "a parameter is {name, moves}");
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

} // namespace

std::vector<EditStep> read_edit_file(const std::string& path, const garment::Pattern& pattern) {
  const YAML::Node root = load_yaml_input(path, "edit file");
  if (!root.IsMap()) throw InputError(path, 1, "an edit file is a mapping with the key 'steps'");
  reject_unknown_keys(path, root, "(top level)", {"steps"});
  const YAML::Node steps = root["steps"];
  if (!steps) throw InputError(path, 1, "steps: missing: the list of edits, applied in turn");
  if (!steps.IsSequence() || steps.size() == 0)
    edit_error(path, steps, "steps", "must be a non-empty list of edits");
  std::set<std::string> outline_lines;
  for (const auto& panel : pattern.panels)
    for (const auto& line : panel.outline)
      outline_lines.insert(line.id);
  std::vector<EditStep> result;
  for (std::size_t s = 0; s < steps.size(); ++s) {
    const std::string key = "steps[" + std::to_string(s) + "]";
    const YAML::Node step = steps[s];
    if (!step.IsMap())
      edit_error(path, step, key,
                 "an edit is a mapping {name, moves} or {name, drag, moves|parameters}");
    reject_unknown_keys(path, step, key, {"name", "moves", "drag", "parameters"});
    EditStep edit;
    edit.name = step["name"] && step["name"].IsScalar() ? step["name"].Scalar()
                                                        : "edit " + std::to_string(s + 1);
    if (step["drag"]) edit.drags = read_drags(path, step["drag"], key + ".drag");
    if (step["parameters"]) {
      if (edit.drags.empty())
        edit_error(path, step["parameters"], key + ".parameters",
                   "parameters are for a drag: give the step a drag, or moves");
      if (step["moves"])
        edit_error(path, step["moves"], key + ".moves",
                   "a drag step has moves (one parameter) or parameters, not both");
      edit.parameters =
          read_parameters(path, step["parameters"], key + ".parameters", pattern, outline_lines);
    } else {
      if (!step["moves"]) edit_error(path, step, key + ".moves", "missing: the list of moves");
      edit.moves = read_moves(path, step["moves"], key + ".moves", pattern, outline_lines);
      if (!edit.drags.empty()) edit.parameters = {{edit.name, edit.moves}};
    }
    result.push_back(edit);
  }
  return result;
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
      {"sensitivity-tangent", "KIND", "exact",
       "the sensitivity's tangent: exact (the derivative) or projected (the minimiser's, "
       "PSD-projected element Hessians: damps the wrinkles' negative curvature)"},
      {"gmls-degree", "N", "2", "degree of GMLS's polynomial basis: 1 (Sensitive Couture's) or 2"},
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
