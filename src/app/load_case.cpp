#include "app/load_case.hpp"

#include "app/commands.hpp"
#include "common/csv.hpp"
#include "common/error.hpp"
#include "common/output.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

namespace sartor {

namespace {

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::stringstream stream(text);
  std::string part;
  while (std::getline(stream, part, separator))
    parts.push_back(part);
  return parts;
}

std::vector<CaseBox> read_pin_boxes(const Options& options) {
  std::vector<CaseBox> boxes;
  if (!options.is_set("pin-box")) return boxes;
  const auto numbers = option_numbers(options, "pin-box", 0);
  if (numbers.empty() || numbers.size() % 6 != 0) {
    throw InputError("option --pin-box: expected 6 numbers per box (x0,x1,y0,y1,z0,z1), got " +
                     std::to_string(numbers.size()));
  }
  for (std::size_t b = 0; b < numbers.size(); b += 6) {
    CaseBox box;
    std::copy(numbers.begin() + long(b), numbers.begin() + long(b + 6), box.bounds.begin());
    boxes.push_back(box);
  }
  return boxes;
}

// One item of --pin-motion-boxes: a box of --pin-box, numbered from 1.
std::size_t pin_box_number(const std::string& item, std::size_t box_count) {
  std::size_t used = 0;
  long box = 0;
  try {
    box = std::stol(item, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || item.find_first_not_of(" \t", used) != std::string::npos || box < 1 ||
      std::size_t(box) > box_count) {
    throw InputError("option --pin-motion-boxes: '" + item + "' is not a box of --pin-box (1.." +
                     std::to_string(box_count) + ")");
  }
  return std::size_t(box);
}

std::optional<PinMotionCase> read_pin_motion(const Options& options, std::size_t box_count) {
  if (!options.is_set("pin-motion")) {
    if (options.is_set("pin-motion-boxes")) {
      throw InputError("option --pin-motion-boxes: there is no --pin-motion to apply");
    }
    return std::nullopt;
  }
  PinMotionCase motion;
  const auto histories = split(options.text("pin-motion"), '|');
  motion.axis = option_vector3(options, "pin-rotation-axis");
  if (motion.axis.norm() == 0.0) throw InputError("option --pin-rotation-axis: the axis is zero");
  motion.axis.normalize();
  for (std::size_t g = 0; g < histories.size(); ++g) {
    motion.histories.push_back(PinHistory::parse(
        histories[g],
        "option --pin-motion" +
            (histories.size() > 1 ? " (group " + std::to_string(g + 1) + ")" : std::string())));
  }
  motion.center = option_vector3(options, "pin-rotation-center");
  const std::size_t groups = motion.histories.size();
  if (!options.is_set("pin-motion-boxes")) {
    if (groups > 1) {
      throw InputError("option --pin-motion: " + std::to_string(groups) +
                       " groups need --pin-motion-boxes to say which pins each moves");
    }
    return motion;
  }
  const auto selections = split(options.text("pin-motion-boxes"), '|');
  if (selections.size() != groups) {
    throw InputError("option --pin-motion-boxes: " + std::to_string(selections.size()) +
                     " group(s) of boxes for " + std::to_string(groups) + " --pin-motion group(s)");
  }
  for (const std::string& selection : selections) {
    motion.boxes.emplace_back();
    for (const std::string& item : split(selection, ','))
      motion.boxes.back().push_back(pin_box_number(item, box_count));
  }
  return motion;
}

// --pin-release "BOX:TIME,...": per --pin-box box, the time it lets go.
std::vector<double> read_pin_release(const Options& options, std::size_t box_count) {
  if (!options.is_set("pin-release")) return {};
  std::vector<double> box_release(box_count, INFINITY);
  for (const std::string& item : split(options.text("pin-release"), ',')) {
    const auto colon = item.find(':');
    std::size_t box_used = 0, time_used = 0;
    long box = 0;
    double time = NAN;
    try {
      if (colon != std::string::npos) {
        box = std::stol(item.substr(0, colon), &box_used);
        time = std::stod(item.substr(colon + 1), &time_used);
      }
    } catch (const std::exception&) {
      box_used = 0;
    }
    const bool whole = colon != std::string::npos && box_used > 0 &&
                       item.find_first_not_of(" \t", box_used) >= colon && time_used > 0 &&
                       item.find_first_not_of(" \t", colon + 1 + time_used) == std::string::npos;
    if (!whole || !std::isfinite(time) || time < 0.0) {
      throw InputError("option --pin-release: '" + item +
                       "' is not BOX:TIME (a --pin-box number and a time >= 0 in s)");
    }
    if (box < 1 || std::size_t(box) > box_count) {
      throw InputError("option --pin-release: box " + std::to_string(box) +
                       " is not a box of --pin-box (1.." + std::to_string(box_count) + ")");
    }
    box_release[std::size_t(box - 1)] = time;
  }
  return box_release;
}

std::optional<EdgeForceCase> read_edge_force(const Options& options) {
  if (options.is_set("edge-force") != options.is_set("edge-force-box")) {
    throw InputError("options --edge-force and --edge-force-box go together");
  }
  if (!options.is_set("edge-force")) return std::nullopt;
  EdgeForceCase edge;
  edge.force = option_vector3(options, "edge-force");
  const auto box = option_numbers(options, "edge-force-box", 6);
  std::copy(box.begin(), box.end(), edge.box.bounds.begin());
  return edge;
}

// Material lengths of the mesh's edges, from the corners' uv in a triangle
// holding each.
std::map<std::pair<int, int>, double> material_edge_lengths(const TriangleMesh& mesh) {
  std::map<std::pair<int, int>, double> length;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    for (std::size_t c = 0; c < 3; ++c) {
      const int a = mesh.triangles[t][c], b = mesh.triangles[t][(c + 1) % 3];
      length[{std::min(a, b), std::max(a, b)}] =
          (mesh.material_uv[t][(c + 1) % 3] - mesh.material_uv[t][c]).norm();
    }
  }
  return length;
}

// The edge load's consistent nodal forces on the boundary edges whose both
// ends lie in its box.
void add_edge_force(const EdgeForceCase& edge, const TriangleMesh& mesh, ClothLoads* loads) {
  const auto inside = [&](int v) { return edge.box.contains(mesh.positions[std::size_t(v)]); };
  const auto material_length = material_edge_lengths(mesh);
  std::vector<std::pair<std::array<int, 2>, double>> loaded;
  double total = 0.0;
  for (const auto& boundary_edge : boundary_edges(mesh)) {
    if (!inside(boundary_edge[0]) || !inside(boundary_edge[1])) continue;
    const double length = material_length.at({boundary_edge[0], boundary_edge[1]});
    loaded.push_back({boundary_edge, length});
    total += length;
  }
  if (loaded.empty()) {
    throw InputError("option --edge-force-box: no boundary edge has both ends in the box");
  }
  std::map<int, Eigen::Vector3d> nodal;
  for (const auto& [vertices, length] : loaded) {
    for (int v : vertices) {
      auto [entry, added] = nodal.try_emplace(v, Eigen::Vector3d::Zero());
      entry->second += 0.5 * length / total * edge.force;
    }
  }
  for (const auto& [vertex, f] : nodal)
    loads->point_forces.push_back({vertex, f});
}

} // namespace
// Loads, pins and the probe.
const std::vector<OptionSpec>& load_option_specs() {
  static const std::vector<OptionSpec> specs = with_module_prefix(
      {
          {"gravity", "X,Y,Z", "0,0,-9.80665", "gravitational acceleration, m/s^2"},
          {"pressure", "PA", "0", "follower pressure on the triangles' normal side, Pa"},
          {"point-force", "V,FX,FY,FZ", "", "a force (N) on vertex V"},
          {"edge-force", "FX,FY,FZ", "",
           "a total force (N) spread over the boundary edges inside --edge-force-box as a uniform "
           "line load (per unit material length)"},
          {"edge-force-box", "X0,X1,Y0,Y1,Z0,Z1", "", "the box of the --edge-force edges, m"},
          {"pin-box", "X0,X1,Y0,Y1,Z0,Z1", "",
           "pin the vertices inside these boxes (6 numbers each)"},
          {"pin-boundary", "", "", "pin every boundary vertex"},
          {"pin-vertices", "I,J,...", "", "pin these vertices"},
          {"pin-move", "X,Y,Z", "0,0,0", "move the pins by this much as the load ramps, m"},
          {"pin-motion", "HISTORY", "",
           "pins follow 'T:DX,DY,DZ[,DEG]; ...' (m, degrees; T: load factor, or time in s with "
           "--analysis dynamic); groups separated by '|'"},
          {"pin-motion-boxes", "I,..|J,..", "",
           "the --pin-box boxes (numbered from 1) each --pin-motion group moves [all pins]"},
          {"pin-release", "BOX:T,...", "",
           "dynamic, creep: the pins of --pin-box BOX (numbered from 1) let go at time T, s"},
          {"pin-rotation-axis", "X,Y,Z", "0,0,1", "axis of the --pin-motion angles"},
          {"pin-rotation-center", "X,Y,Z", "0,0,0", "a point of that axis, m"},
          {"probe", "X,Y,Z", "", "report the displacement of the vertex nearest this point"},
      },
      {"load", "pin"});
  return specs;
}

Eigen::Vector3d option_vector3(const Options& options, const std::string& name) {
  const auto v = option_numbers(options, name, 3);
  return {v[0], v[1], v[2]};
}

bool CaseBox::contains(const Eigen::Vector3d& p) const {
  bool inside = true;
  for (std::size_t d = 0; d < 3; ++d)
    inside = inside && p[long(d)] >= bounds[2 * d] && p[long(d)] <= bounds[2 * d + 1];
  return inside;
}

LoadCase read_load_case(const Options& options) {
  LoadCase loads;
  loads.gravity = option_vector3(options, "gravity");
  loads.pressure = options.real("pressure");
  if (options.is_set("point-force")) {
    const auto f = option_numbers(options, "point-force", 4);
    loads.point_force = PointForceCase{f[0], Eigen::Vector3d(f[1], f[2], f[3])};
  }
  loads.edge_force = read_edge_force(options);
  loads.pin_boxes = read_pin_boxes(options);
  loads.pin_boundary = options.flag("pin-boundary");
  if (options.is_set("pin-vertices"))
    loads.pin_vertices = option_numbers(options, "pin-vertices", 0);
  loads.pin_move = option_vector3(options, "pin-move");
  loads.pin_motion = read_pin_motion(options, loads.pin_boxes.size());
  loads.pin_release = read_pin_release(options, loads.pin_boxes.size());
  if (options.is_set("probe")) loads.probe = option_vector3(options, "probe");
  return loads;
}

std::vector<int> pinned_vertices(const LoadCase& loads, const TriangleMesh& mesh) {
  std::vector<bool> pin(mesh.vertex_count(), false);
  for (const CaseBox& box : loads.pin_boxes) {
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
      if (box.contains(mesh.positions[v])) pin[v] = true;
  }
  if (loads.pin_boundary) {
    for (int v : boundary_vertices(mesh))
      pin[std::size_t(v)] = true;
  }
  for (double value : loads.pin_vertices) {
    const auto v = long(value);
    if (double(v) != value || v < 0 || std::size_t(v) >= mesh.vertex_count()) {
      throw InputError("option --pin-vertices: " + format_number(value) +
                       " is not a vertex of the mesh (0.." +
                       std::to_string(mesh.vertex_count() - 1) + ")");
    }
    pin[std::size_t(v)] = true;
  }
  std::vector<int> pinned;
  for (std::size_t v = 0; v < pin.size(); ++v) {
    if (pin[v]) pinned.push_back(int(v));
  }
  return pinned;
}

std::vector<PinGroupMotion> pin_groups(const LoadCase& loads, const TriangleMesh& mesh,
                                       const std::vector<int>& pinned) {
  std::vector<PinGroupMotion> groups;
  if (!loads.pin_motion) return groups;
  const PinMotionCase& motion = *loads.pin_motion;
  if (pinned.empty()) throw InputError("option --pin-motion: no vertex is pinned");
  for (const PinHistory& history : motion.histories)
    groups.push_back(PinGroupMotion{{}, history, motion.axis, motion.center});
  if (motion.boxes.empty()) {
    for (std::size_t i = 0; i < pinned.size(); ++i)
      groups[0].pins.push_back(i);
    return groups;
  }
  std::vector<std::size_t> group_of(pinned.size(), 0);
  for (std::size_t g = 0; g < groups.size(); ++g) {
    for (std::size_t box : motion.boxes[g]) {
      for (std::size_t i = 0; i < pinned.size(); ++i) {
        const Eigen::Vector3d& p = mesh.positions[std::size_t(pinned[i])];
        if (!loads.pin_boxes[box - 1].contains(p) || group_of[i] == g + 1) continue;
        if (group_of[i] != 0) {
          throw InputError("option --pin-motion-boxes: pinned vertex " + std::to_string(pinned[i]) +
                           " is in groups " + std::to_string(group_of[i]) + " and " +
                           std::to_string(g + 1));
        }
        group_of[i] = g + 1;
        groups[g].pins.push_back(i);
      }
    }
  }
  return groups;
}

std::vector<double> pin_release_times(const LoadCase& loads, const TriangleMesh& mesh,
                                      const std::vector<int>& pinned) {
  std::vector<double> release(pinned.size(), INFINITY);
  if (loads.pin_release.empty()) return release;
  std::vector<bool> listed(mesh.vertex_count(), false);
  if (loads.pin_boundary) {
    for (int v : boundary_vertices(mesh))
      listed[std::size_t(v)] = true;
  }
  for (double value : loads.pin_vertices)
    listed[std::size_t(value)] = true; // checked by pinned_vertices
  for (std::size_t i = 0; i < pinned.size(); ++i) {
    if (listed[std::size_t(pinned[i])]) continue;
    const Eigen::Vector3d& p = mesh.positions[std::size_t(pinned[i])];
    double latest = -INFINITY;
    for (std::size_t b = 0; b < loads.pin_boxes.size(); ++b)
      if (loads.pin_boxes[b].contains(p)) latest = std::max(latest, loads.pin_release[b]);
    release[i] = latest;
  }
  return release;
}

void set_case_loads(const LoadCase& case_loads, const TriangleMesh& mesh, ClothLoads* loads) {
  loads->gravity = case_loads.gravity;
  loads->pressure = case_loads.pressure;
  if (case_loads.point_force) {
    const PointForceCase& point = *case_loads.point_force;
    const auto v = long(point.vertex);
    if (double(v) != point.vertex || v < 0 || std::size_t(v) >= mesh.vertex_count()) {
      throw InputError("option --point-force: vertex " + format_number(point.vertex) +
                       " is not in the mesh");
    }
    loads->point_forces.push_back({int(v), point.force});
  }
  if (case_loads.edge_force) add_edge_force(*case_loads.edge_force, mesh, loads);
}

} // namespace sartor
