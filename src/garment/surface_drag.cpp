// Surface dragging and pushpins (garment/surface_drag.hpp).

#include "garment/surface_drag.hpp"

#include "common/error.hpp"
#include "common/yaml_input.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <utility>

namespace sartor::garment {

namespace {

std::vector<double> mesh_distance(const RestEdges& edges, int source) {
  return dependency_graph(edges, source).distance;
}

// The local frame of a vertex with unit body normal `z` for an edge along `u`.
std::array<Eigen::Vector3d, 3> local_frame(const Eigen::Vector3d& z, const Eigen::Vector3d& u) {
  Eigen::Vector3d x = u - u.dot(z) * z;
  if (x.norm() < 1e-9) {
    const Eigen::Vector3d helper =
        std::abs(z.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    x = z.cross(helper);
  }
  x.normalize();
  return {x, z.cross(x), z};
}

} // namespace

DependencyGraph dependency_graph(const RestEdges& edges, int root) {
  const std::size_t n = edges.neighbours.size();
  DependencyGraph graph;
  graph.root = root;
  graph.parents.resize(n);
  graph.distance.assign(n, std::numeric_limits<double>::infinity());
  std::vector<bool> in_graph(n, false);
  std::set<std::pair<double, int>> queue{{0.0, root}};
  graph.distance[std::size_t(root)] = 0.0;
  while (!queue.empty()) {
    const auto [d, v] = *queue.begin();
    queue.erase(queue.begin());
    in_graph[std::size_t(v)] = true;
    graph.order.push_back(v);
    for (const auto& [neighbour, length] : edges.neighbours[std::size_t(v)]) {
      if (in_graph[std::size_t(neighbour)]) {
        graph.parents[std::size_t(v)].push_back(neighbour);
      } else if (d + length < graph.distance[std::size_t(neighbour)]) {
        queue.erase({graph.distance[std::size_t(neighbour)], neighbour});
        graph.distance[std::size_t(neighbour)] = d + length;
        queue.insert({d + length, neighbour});
      }
    }
  }
  return graph;
}

double attenuation_ratio(double a, double b, double c) {
  return std::clamp((c - a + b) / (2.0 * c), 0.0, 1.0);
}

std::vector<double> attenuation(const RestEdges& edges, int grabbed, const std::vector<int>& pins) {
  const std::vector<double> to_grabbed = mesh_distance(edges, grabbed);
  std::vector<double> ratio(to_grabbed.size(), 1.0);
  for (int pin : pins) {
    const std::vector<double> to_pin = mesh_distance(edges, pin);
    const double between = to_grabbed[std::size_t(pin)];
    if (!std::isfinite(between)) continue; // another piece of cloth: no effect
    for (std::size_t v = 0; v < ratio.size(); ++v)
      if (std::isfinite(to_grabbed[v]))
        ratio[v] = std::min(ratio[v], attenuation_ratio(to_grabbed[v], to_pin[v], between));
  }
  return ratio;
}

SurfaceDrag::SurfaceDrag(ClothOnBody& cloth, int grabbed, std::vector<int> pins,
                         const DragOptions& options, const RestEdges* graph_edges)
    : cloth_(cloth), grabbed_(grabbed), pins_(std::move(pins)), options_(options) {
  const RestEdges& edges = graph_edges ? *graph_edges : cloth.edges();
  const int n = int(edges.neighbours.size());
  if (grabbed < 0 || grabbed >= n)
    throw InputError("drag: vertex " + std::to_string(grabbed) + " is not in the garment (0.." +
                     std::to_string(n - 1) + ")");
  for (int pin : pins_) {
    if (pin < 0 || pin >= n)
      throw InputError("drag: pin " + std::to_string(pin) + " is not in the garment");
    if (pin == grabbed)
      throw InputError("drag: vertex " + std::to_string(pin) + " is both grabbed and pinned");
  }
  graph_ = dependency_graph(edges, grabbed);
  ratios_ = attenuation(edges, grabbed, pins_);
  motion_.assign(std::size_t(n), Eigen::Vector3d::Zero());
  cloth_.fixed[std::size_t(grabbed)] = true;
  for (int pin : pins_)
    cloth_.fixed[std::size_t(pin)] = true;
}

void SurfaceDrag::release() {
  cloth_.fixed[std::size_t(grabbed_)] = false;
  for (int pin : pins_)
    cloth_.fixed[std::size_t(pin)] = false;
}

void SurfaceDrag::propagate(const Eigen::Vector3d& root_motion) {
  const auto& x = cloth_.positions();
  std::vector<Eigen::Vector3d> normal(x.size());
  for (int v : graph_.order)
    normal[std::size_t(v)] = nearest_body_point(cloth_.body(), x[std::size_t(v)]).normal;
  std::fill(motion_.begin(), motion_.end(), Eigen::Vector3d::Zero());
  motion_[std::size_t(grabbed_)] = root_motion;
  for (int v : graph_.order) {
    if (v == grabbed_) continue;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int parent : graph_.parents[std::size_t(v)]) {
      const Eigen::Vector3d edge = x[std::size_t(v)] - x[std::size_t(parent)];
      const Eigen::Vector3d u = edge.norm() > 0.0 ? edge.normalized() : Eigen::Vector3d::UnitX();
      const auto from = local_frame(normal[std::size_t(parent)], u);
      const auto to = local_frame(normal[std::size_t(v)], u);
      const Eigen::Vector3d& m = motion_[std::size_t(parent)];
      sum += m.dot(from[0]) * to[0] + m.dot(from[1]) * to[1] + m.dot(from[2]) * to[2];
    }
    motion_[std::size_t(v)] = sum / double(graph_.parents[std::size_t(v)].size());
  }
}

void SurfaceDrag::step(const Eigen::Vector3d& displacement) {
  auto& x = cloth_.positions();
  const contact::Shape& body = cloth_.body();
  const double offset = cloth_.parameters().offset;
  const BodyPoint at_root = nearest_body_point(body, x[std::size_t(grabbed_)]);
  const std::vector<Eigen::Vector3d> before = x;
  propagate(displacement - displacement.dot(at_root.normal) * at_root.normal);
  for (int v : graph_.order) {
    const bool pinned = std::count(pins_.begin(), pins_.end(), v) > 0;
    if (pinned) continue;
    Eigen::Vector3d p = x[std::size_t(v)] + ratios_[std::size_t(v)] * motion_[std::size_t(v)];
    const BodyPoint near = nearest_body_point(body, p);
    if (near.distance < options_.pull_band && near.distance > offset)
      p = near.closest + (offset + 0.5 * (near.distance - offset)) * near.normal;
    x[std::size_t(v)] = keep_above(body, p, offset);
  }
  cloth_.hold_back_at_bones(before);
  cloth_.relax(options_.relax_steps);
}

namespace {

// A vertex given as an index or as a point (the nearest vertex).
int read_vertex(const YAML::Node& node, const std::vector<Eigen::Vector3d>& positions,
                const std::string& where) {
  if (node.IsScalar()) {
    int index = -1;
    try {
      index = node.as<int>();
    } catch (const YAML::Exception&) {
      throw InputError(where + ": a vertex index or a point [x, y, z] is needed");
    }
    if (index < 0 || std::size_t(index) >= positions.size())
      throw InputError(where + ": vertex " + std::to_string(index) + " is not in the garment (0.." +
                       std::to_string(positions.size() - 1) + ")");
    return index;
  }
  if (!node.IsSequence() || node.size() != 3)
    throw InputError(where + ": a vertex index or a point [x, y, z] is needed");
  Eigen::Vector3d point;
  for (std::size_t k = 0; k < 3; ++k)
    point[Eigen::Index(k)] = node[k].as<double>();
  std::size_t nearest = 0;
  for (std::size_t v = 1; v < positions.size(); ++v)
    if ((positions[v] - point).norm() < (positions[nearest] - point).norm()) nearest = v;
  return int(nearest);
}

Eigen::Vector3d read_vector(const YAML::Node& node, const std::string& where) {
  if (!node.IsSequence() || node.size() != 3)
    throw InputError(where + ": a displacement [dx, dy, dz] in m is needed");
  Eigen::Vector3d vector;
  for (std::size_t k = 0; k < 3; ++k) {
    vector[Eigen::Index(k)] = node[k].as<double>();
    if (!std::isfinite(vector[Eigen::Index(k)])) throw InputError(where + ": not a finite number");
  }
  return vector;
}

void check_keys(const YAML::Node& map, const std::vector<std::string>& known,
                const std::string& where) {
  for (const auto& item : map) {
    const std::string key = item.first.as<std::string>();
    if (std::find(known.begin(), known.end(), key) == known.end())
      throw InputError(where + ": unknown key '" + key + "'");
  }
}

} // namespace

DragScript read_drag_script(const std::string& path,
                            const std::vector<Eigen::Vector3d>& positions) {
  const YAML::Node document = load_yaml_input(path, "drag script");
  if (!document.IsMap()) throw InputError(path + ": a mapping is needed");
  check_keys(document, {"body", "relax_steps", "pull_band", "drags"}, path);
  DragScript script;
  try {
    if (!document["body"]) throw InputError(path + ": body: a body specification is needed");
    script.body = document["body"].as<std::string>();
    if (document["relax_steps"]) script.options.relax_steps = document["relax_steps"].as<int>();
    if (script.options.relax_steps < 0) throw InputError(path + ": relax_steps: must be >= 0");
    if (document["pull_band"]) script.options.pull_band = document["pull_band"].as<double>();
    if (!(script.options.pull_band >= 0.0)) throw InputError(path + ": pull_band: must be >= 0");
    const YAML::Node drags = document["drags"];
    if (!drags || !drags.IsSequence() || drags.size() == 0)
      throw InputError(path + ": drags: a list of at least one drag is needed");
    for (std::size_t i = 0; i < drags.size(); ++i) {
      const std::string where = path + ": drags[" + std::to_string(i) + "]";
      check_keys(drags[i], {"vertex", "steps", "repeat", "pins"}, where);
      if (!drags[i]["vertex"] || !drags[i]["steps"] || !drags[i]["steps"].IsSequence())
        throw InputError(where + ": \"vertex\" and \"steps\" (a list of displacements) are needed");
      ScriptedDrag drag;
      drag.vertex = read_vertex(drags[i]["vertex"], positions, where + ".vertex");
      const int repeat = drags[i]["repeat"] ? drags[i]["repeat"].as<int>() : 1;
      if (repeat < 1) throw InputError(where + ".repeat: must be >= 1");
      for (int r = 0; r < repeat; ++r)
        for (std::size_t s = 0; s < drags[i]["steps"].size(); ++s)
          drag.steps.push_back(
              read_vector(drags[i]["steps"][s], where + ".steps[" + std::to_string(s) + "]"));
      if (drags[i]["pins"]) {
        for (std::size_t p = 0; p < drags[i]["pins"].size(); ++p)
          drag.pins.push_back(read_vertex(drags[i]["pins"][p], positions,
                                          where + ".pins[" + std::to_string(p) + "]"));
      }
      script.drags.push_back(drag);
    }
  } catch (const YAML::Exception& error) {
    throw InputError(path + ":" + std::to_string(error.mark.line + 1) + ": " + error.msg);
  }
  return script;
}

} // namespace sartor::garment
