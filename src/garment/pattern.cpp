#include "garment/pattern.hpp"

#include "garment/pleats.hpp"

#include "common/csv.hpp"
#include "common/error.hpp"
#include "common/json_input.hpp"
#include "material/fabric.hpp"

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace sartor::garment {

using Eigen::Vector2d;
using nlohmann::json;

// ---------------------------------------------------------------- names ----

const char* name_of(Cylinder cylinder) {
  switch (cylinder) {
  case Cylinder::torso:
    return "torso";
  case Cylinder::arm_l:
    return "arm_l";
  case Cylinder::arm_r:
    return "arm_r";
  case Cylinder::leg_l:
    return "leg_l";
  case Cylinder::leg_r:
    return "leg_r";
  case Cylinder::neck:
    return "neck";
  case Cylinder::head:
    return "head";
  }
  return "?";
}

const char* name_of(Side side) {
  return side == Side::front ? "front" : "back";
}

const std::vector<Cylinder>& all_cylinders() {
  static const std::vector<Cylinder> all = {Cylinder::torso, Cylinder::arm_l, Cylinder::arm_r,
                                            Cylinder::leg_l, Cylinder::leg_r, Cylinder::neck,
                                            Cylinder::head};
  return all;
}

std::string to_string(const PanelTag& tag) {
  return std::string("(") + name_of(tag.cylinder) + ", " + name_of(tag.side) + ", " +
         std::to_string(tag.layer) + ")";
}

const char* name_of(Curve::Kind kind) {
  switch (kind) {
  case Curve::Kind::straight:
    return "straight";
  case Curve::Kind::bezier:
    return "bezier";
  case Curve::Kind::polyline:
    return "polyline";
  }
  return "?";
}

const char* name_of(InteriorLine::Kind kind) {
  return kind == InteriorLine::Kind::fold ? "fold" : "t_seam";
}

// ---------------------------------------------------------------- curves ----

namespace {

// de Casteljau: the cubic with control points c, at t.
Vector2d bezier_point(const std::vector<Vector2d>& c, double t) {
  const double s = 1 - t;
  return s * s * s * c[0] + 3 * s * s * t * c[1] + 3 * s * t * t * c[2] + t * t * t * c[3];
}

Vector2d bezier_derivative(const std::vector<Vector2d>& c, double t) {
  const double s = 1 - t;
  return 3 * s * s * (c[1] - c[0]) + 6 * s * t * (c[2] - c[1]) + 3 * t * t * (c[3] - c[2]);
}

double distance_to_segment(const Vector2d& p, const Vector2d& a, const Vector2d& b) {
  const Vector2d ab = b - a;
  const double squared = ab.squaredNorm();
  const double t = squared > 0 ? std::clamp((p - a).dot(ab) / squared, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

// The control points of a cubic bound its distance from the chord, so a
// piece whose control points are within `tolerance` of its chord is flat.
void flatten_bezier(const std::array<Vector2d, 4>& c, double t0, double t1, double tolerance,
                    int depth, std::vector<Vector2d>& points, std::vector<double>& parameters) {
  const bool flat = distance_to_segment(c[1], c[0], c[3]) <= tolerance &&
                    distance_to_segment(c[2], c[0], c[3]) <= tolerance;
  if (flat || depth >= 40) {
    points.push_back(c[3]);
    parameters.push_back(t1);
    return;
  }
  const Vector2d p01 = 0.5 * (c[0] + c[1]), p12 = 0.5 * (c[1] + c[2]), p23 = 0.5 * (c[2] + c[3]);
  const Vector2d p012 = 0.5 * (p01 + p12), p123 = 0.5 * (p12 + p23);
  const Vector2d mid = 0.5 * (p012 + p123);
  const double tm = 0.5 * (t0 + t1);
  flatten_bezier({c[0], p01, p012, mid}, t0, tm, tolerance, depth + 1, points, parameters);
  flatten_bezier({mid, p123, p23, c[3]}, tm, t1, tolerance, depth + 1, points, parameters);
}

// Arc length of a cubic over [a, b]: 5-point Gauss-Legendre on 8 sub-intervals
// (the speed is smooth, so this is accurate to rounding for pattern curves).
double bezier_length(const std::vector<Vector2d>& c, double a, double b) {
  static const std::array<double, 5> x = {0.0, -0.5384693101056831, 0.5384693101056831,
                                          -0.9061798459386640, 0.9061798459386640};
  static const std::array<double, 5> w = {0.5688888888888889, 0.4786286704993665,
                                          0.4786286704993665, 0.2369268850561891,
                                          0.2369268850561891};
  constexpr int intervals = 8;
  const double h = (b - a) / intervals;
  double sum = 0;
  for (int k = 0; k < intervals; ++k) {
    const double mid = a + (k + 0.5) * h;
    for (std::size_t q = 0; q < x.size(); ++q)
      sum += w[q] * 0.5 * h * bezier_derivative(c, mid + 0.5 * h * x[q]).norm();
  }
  return sum;
}

} // namespace

Vector2d Curve::at(double t) const {
  if (kind == Kind::bezier) return bezier_point(points, t);
  const double segments = double(points.size() - 1);
  const double position = std::clamp(t, 0.0, 1.0) * segments;
  const auto k = std::min(static_cast<std::size_t>(position), points.size() - 2);
  const double f = position - double(k);
  return (1 - f) * points[k] + f * points[k + 1];
}

std::vector<Vector2d> Curve::flatten(double tolerance, std::vector<double>* parameters) const {
  std::vector<Vector2d> out{points.front()};
  std::vector<double> ts{0.0};
  if (kind == Kind::bezier) {
    flatten_bezier({points[0], points[1], points[2], points[3]}, 0, 1, tolerance, 0, out, ts);
  } else {
    for (std::size_t k = 1; k < points.size(); ++k) {
      out.push_back(points[k]);
      ts.push_back(double(k) / double(points.size() - 1));
    }
  }
  if (parameters) *parameters = std::move(ts);
  return out;
}

double Curve::length() const {
  if (kind == Kind::bezier) return bezier_length(points, 0, 1);
  double sum = 0;
  for (std::size_t k = 1; k < points.size(); ++k)
    sum += (points[k] - points[k - 1]).norm();
  return sum;
}

std::vector<Vector2d> Curve::split_equal_arc_length(int pieces,
                                                    std::vector<double>* parameters) const {
  const double total = length();
  std::vector<Vector2d> out{start()};
  std::vector<double> at{0.0};
  if (kind == Kind::bezier) {
    // Newton on s(t) = target, safeguarded by bisection.
    double t = 0, s = 0;
    for (int i = 1; i < pieces; ++i) {
      const double target = total * i / pieces;
      double lo = t, hi = 1, guess = t + (target - s) / total;
      for (int iteration = 0; iteration < 60; ++iteration) {
        guess = std::clamp(guess, lo, hi);
        const double error = s + bezier_length(points, t, guess) - target;
        if (std::abs(error) <= 1e-12 * total) break;
        if (error > 0)
          hi = guess;
        else
          lo = guess;
        const double speed = bezier_derivative(points, guess).norm();
        double next = speed > 0 ? guess - error / speed : 0.5 * (lo + hi);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        guess = next;
      }
      s += bezier_length(points, t, guess);
      t = guess;
      out.push_back(bezier_point(points, t));
      at.push_back(t);
    }
  } else {
    std::size_t k = 0;
    double before = 0; // arc length up to points[k]
    const double segments = double(points.size() - 1);
    for (int i = 1; i < pieces; ++i) {
      const double target = total * i / pieces;
      while (k + 2 < points.size() && before + (points[k + 1] - points[k]).norm() < target) {
        before += (points[k + 1] - points[k]).norm();
        ++k;
      }
      const double piece = (points[k + 1] - points[k]).norm();
      const double f = piece > 0 ? std::clamp((target - before) / piece, 0.0, 1.0) : 0.0;
      out.push_back((1 - f) * points[k] + f * points[k + 1]);
      at.push_back((double(k) + f) / segments);
    }
  }
  out.push_back(end());
  at.push_back(1.0);
  if (parameters) *parameters = std::move(at);
  return out;
}

Curve Curve::reversed() const {
  Curve out = *this;
  std::reverse(out.points.begin(), out.points.end());
  return out;
}

// ------------------------------------------------------- panels, packs ----

std::vector<Vector2d> Panel::outline_polygon(double tolerance) const {
  std::vector<Vector2d> polygon;
  for (const auto& line : outline) {
    const auto points = line.curve.flatten(tolerance);
    polygon.insert(polygon.end(), points.begin(), points.end() - 1);
  }
  return polygon;
}

namespace {
double signed_area(const std::vector<Vector2d>& polygon) {
  double twice = 0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Vector2d& a = polygon[i];
    const Vector2d& b = polygon[(i + 1) % polygon.size()];
    twice += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * twice;
}
} // namespace

double Panel::area(double tolerance) const {
  return signed_area(outline_polygon(tolerance));
}

Vector2d Placement::apply(const Vector2d& p) const {
  const double c = std::cos(rotation), s = std::sin(rotation);
  return Vector2d(c * p.x() - s * p.y(), s * p.x() + c * p.y()) + translation;
}

Placement Placement::then(const Placement& outer) const {
  Placement combined;
  combined.rotation = rotation + outer.rotation;
  combined.translation = outer.apply(translation);
  return combined;
}

const Panel* Pattern::find_panel(const std::string& id) const {
  for (const auto& panel : panels)
    if (panel.id == id) return &panel;
  return nullptr;
}

int Pattern::pack_of(int panel) const {
  for (std::size_t p = 0; p < packs.size(); ++p)
    for (const auto& member : packs[p].members)
      if (member.panel == panel) return int(p);
  return -1;
}

double Pattern::flattening_tolerance() const {
  double size = 0;
  for (const auto& panel : panels)
    for (const auto& line : panel.outline)
      for (const auto& p : line.curve.points)
        size = std::max(size, p.cwiseAbs().maxCoeff());
  return std::max(tolerance, 1e-5 * size);
}

std::vector<Placement> sheet_layout(const Pattern& pattern, double gap) {
  std::vector<Placement> layout(pattern.panels.size());
  double next_left = 0;
  const double tolerance = pattern.flattening_tolerance();
  for (const auto& pack : pattern.packs) {
    Eigen::AlignedBox2d box;
    for (const auto& member : pack.members)
      for (const auto& p : pattern.panels[member.panel].outline_polygon(tolerance))
        box.extend(member.placement.apply(p));
    Placement shift;
    shift.translation = Vector2d(next_left - box.min().x(), -box.min().y());
    for (const auto& member : pack.members)
      layout[member.panel] = member.placement.then(shift);
    next_left += box.sizes().x() + gap;
  }
  return layout;
}

// ------------------------------------------------------------- reading ----

namespace {

// A JSON value and where it is, so that every message can say both.
std::string point_text(const Vector2d& p) {
  return "(" + format_number(p.x()) + ", " + format_number(p.y()) + ")";
}

struct Node {
  const json& value;
  std::string path;
  const std::string& source;

  [[noreturn]] void fail(const std::string& message) const {
    throw InputError(source + ": " + (path.empty() ? "" : path + ": ") + message);
  }
  Node child(const std::string& key) const {
    return {value.at(key), path.empty() ? key : path + "." + key, source};
  }
  Node element(std::size_t index) const {
    return {value.at(index), path + "[" + std::to_string(index) + "]", source};
  }
  bool has(const std::string& key) const { return value.contains(key); }
  Node require(const std::string& key) const {
    if (!has(key)) fail("missing field '" + key + "'");
    return child(key);
  }
  void only_keys(std::initializer_list<const char*> allowed) const {
    for (const auto& item : value.items()) {
      if (std::none_of(allowed.begin(), allowed.end(),
                       [&](const char* name) { return item.key() == name; })) {
        std::string list;
        for (const char* name : allowed)
          list += std::string(list.empty() ? "" : ", ") + name;
        fail("unknown key '" + item.key() + "' (expected one of: " + list + ")");
      }
    }
  }
  const json& object() const {
    if (!value.is_object()) fail("expected an object, got " + std::string(value.type_name()));
    return value;
  }
  std::size_t array_size() const {
    if (!value.is_array()) fail("expected an array, got " + std::string(value.type_name()));
    return value.size();
  }
  std::string text() const {
    if (!value.is_string()) fail("expected a string, got " + std::string(value.type_name()));
    return value.get<std::string>();
  }
  std::string id() const {
    std::string result = text();
    if (result.empty()) fail("an id must not be empty");
    return result;
  }
  double number() const {
    if (!value.is_number()) fail("expected a number, got " + std::string(value.type_name()));
    return value.get<double>();
  }
  int integer() const {
    if (!value.is_number_integer())
      fail("expected an integer, got " + (value.is_number() ? format_number(value.get<double>())
                                                            : std::string(value.type_name())));
    return value.get<int>();
  }
  bool boolean() const {
    if (!value.is_boolean()) fail("expected true or false, got " + std::string(value.type_name()));
    return value.get<bool>();
  }
  Vector2d point(double scale) const {
    if (array_size() != 2)
      fail("expected a point [x, y], got " + std::to_string(value.size()) + " numbers");
    const Vector2d point = scale * Vector2d(element(0).number(), element(1).number());
    // Beyond this no garment lies; the meshers and flattening would not end.
    constexpr double farthest = 1000.0; // m
    if (!(point.lpNorm<Eigen::Infinity>() <= farthest)) {
      fail("the point " + point_text(point) + " (m) is more than " + format_number(farthest) +
           " m from the origin; check \"units\"");
    }
    return point;
  }
};

Curve read_curve(const Node& node, double scale) {
  Curve curve;
  const std::string kind = node.require("type").text();
  std::size_t minimum = 2, maximum = 2;
  if (kind == "straight") {
    curve.kind = Curve::Kind::straight;
  } else if (kind == "bezier") {
    curve.kind = Curve::Kind::bezier;
    minimum = maximum = 4;
  } else if (kind == "polyline") {
    curve.kind = Curve::Kind::polyline;
    maximum = std::numeric_limits<std::size_t>::max();
  } else {
    node.child("type").fail("unknown curve type '" + kind +
                            "' (expected straight, bezier or polyline)");
  }
  const Node points = node.require("points");
  const std::size_t count = points.array_size();
  if (count < minimum || count > maximum) {
    points.fail("a " + kind + " curve takes " +
                (minimum == maximum ? std::to_string(minimum) : "at least 2") + " points, got " +
                std::to_string(count));
  }
  for (std::size_t i = 0; i < count; ++i)
    curve.points.push_back(points.element(i).point(scale));
  if (curve.length() <= 0) node.fail("the " + kind + " has zero length");
  return curve;
}

PanelTag read_tag(const Node& node) {
  node.object();
  node.only_keys({"cylinder", "side", "layer"});
  PanelTag tag;
  const Node cylinder = node.require("cylinder");
  const std::string alpha = cylinder.text();
  const auto& cylinders = all_cylinders();
  const auto found = std::find_if(cylinders.begin(), cylinders.end(),
                                  [&](Cylinder c) { return alpha == name_of(c); });
  if (found == cylinders.end()) {
    std::string list;
    for (Cylinder c : cylinders)
      list += std::string(list.empty() ? "" : ", ") + name_of(c);
    cylinder.fail("unknown cylinder '" + alpha + "' (expected one of: " + list + ")");
  }
  tag.cylinder = *found;
  const Node side = node.require("side");
  const std::string beta = side.text();
  if (beta == "front")
    tag.side = Side::front;
  else if (beta == "back")
    tag.side = Side::back;
  else
    side.fail("unknown side '" + beta + "' (expected front or back)");
  if (node.has("layer")) tag.layer = node.child("layer").integer();
  return tag;
}

GrainLine read_grain(const Node& node, double scale) {
  node.object();
  node.only_keys({"from", "to", "angle_deg"});
  GrainLine grain;
  const bool by_points = node.has("from") || node.has("to");
  if (by_points == node.has("angle_deg"))
    node.fail("give the grain line either as \"from\" and \"to\" points or as \"angle_deg\"");
  if (by_points) {
    grain.origin = node.require("from").point(scale);
    const Vector2d to = node.require("to").point(scale);
    if ((to - grain.origin).norm() <= 0) node.fail("the grain line has zero length");
    grain.warp = (to - grain.origin).normalized();
  } else {
    const double angle = node.child("angle_deg").number() * M_PI / 180;
    grain.warp = Vector2d(std::cos(angle), std::sin(angle));
  }
  return grain;
}

std::string check_fabric(const Node& node, const std::string& source) {
  const std::string name = node.text();
  for (const auto& preset : fabric_presets())
    if (name == preset.name) return name;
  const auto ends_with = [&](const std::string& suffix) {
    return name.size() > suffix.size() &&
           name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  if (ends_with(".yaml") || ends_with(".yml")) {
    const std::filesystem::path file =
        std::filesystem::path(source).parent_path() / std::filesystem::path(name);
    if (!std::filesystem::exists(file))
      node.fail("fabric file '" + file.string() + "' does not exist");
    return file.string();
  }
  std::string list;
  for (const auto& preset : fabric_presets())
    list += std::string(list.empty() ? "" : ", ") + preset.name;
  node.fail("unknown fabric '" + name + "' (expected a preset: " + list +
            "; or a fabric file NAME.yaml)");
}

// ----------------------------------------------------- geometry checks ----

double cross(const Vector2d& a, const Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Whether closed segments ab and cd share a point (touching counts), within
// `tolerance`; `where` receives one shared point.
bool segments_meet(const Vector2d& a, const Vector2d& b, const Vector2d& c, const Vector2d& d,
                   double tolerance, Vector2d& where) {
  const Vector2d r = b - a, s = d - c;
  const double denominator = cross(r, s);
  const double scale = r.norm() * s.norm();
  if (std::abs(denominator) > 1e-12 * scale) {
    const double t = cross(c - a, s) / denominator;
    const double u = cross(c - a, r) / denominator;
    const double t_slack = tolerance / r.norm(), u_slack = tolerance / s.norm();
    if (t >= -t_slack && t <= 1 + t_slack && u >= -u_slack && u <= 1 + u_slack) {
      where = a + std::clamp(t, 0.0, 1.0) * r;
      return true;
    }
    return false;
  }
  // Parallel: they meet where an endpoint of one lies on the other.
  for (const auto& [p, q0, q1] :
       {std::tuple{a, c, d}, std::tuple{b, c, d}, std::tuple{c, a, b}, std::tuple{d, a, b}}) {
    if (distance_to_segment(p, q0, q1) <= tolerance) {
      where = p;
      return true;
    }
  }
  return false;
}

bool boxes_near(const Eigen::AlignedBox2d& a, const Eigen::AlignedBox2d& b, double tolerance) {
  const Eigen::Vector2d slack = Eigen::Vector2d::Constant(tolerance);
  return a.intersects(Eigen::AlignedBox2d(b.min() - slack, b.max() + slack));
}

struct FlatSegment {
  Vector2d a, b;
  std::size_t line; // index of the line it flattens
  Eigen::AlignedBox2d box;
};

std::vector<FlatSegment> flat_segments(const std::vector<Curve>& curves, double tolerance) {
  std::vector<FlatSegment> segments;
  for (std::size_t l = 0; l < curves.size(); ++l) {
    const auto points = curves[l].flatten(tolerance);
    for (std::size_t k = 0; k + 1 < points.size(); ++k) {
      Eigen::AlignedBox2d box(points[k]);
      box.extend(points[k + 1]);
      segments.push_back({points[k], points[k + 1], l, box});
    }
  }
  return segments;
}

std::string line_name(const Panel& panel, std::size_t line) {
  return panel.outline[line].json_path + " ('" + panel.outline[line].id + "')";
}

void check_closed(const Node& node, Panel& panel, double tolerance) {
  for (std::size_t i = 0; i < panel.outline.size(); ++i) {
    auto& next = panel.outline[(i + 1) % panel.outline.size()];
    const Vector2d end = panel.outline[i].curve.end();
    const double gap = (next.curve.start() - end).norm();
    if (gap > tolerance) {
      node.element(i).fail("the outline is not closed: line '" + panel.outline[i].id +
                           "' ends at " + point_text(end) + " but the next line '" + next.id +
                           "' starts at " + point_text(next.curve.start()) + " (gap " +
                           format_number(gap) + " m, tolerance " + format_number(tolerance) +
                           " m)");
    }
    next.curve.points.front() = end; // close exactly
  }
}

void check_simple(const Node& node, const Panel& panel, double tolerance, double flattening) {
  std::vector<Curve> curves;
  for (const auto& line : panel.outline)
    curves.push_back(line.curve);
  const auto segments = flat_segments(curves, flattening);
  const std::size_t n = segments.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
      const FlatSegment& s = segments[i];
      const FlatSegment& t = segments[j];
      Vector2d where;
      if (adjacent) {
        // Consecutive segments share a corner; they must not fold back onto each other.
        const Vector2d corner = j == i + 1 ? s.b : s.a;
        const Vector2d u = (j == i + 1 ? s.a : s.b) - corner;
        const Vector2d v = (j == i + 1 ? t.b : t.a) - corner;
        if (std::abs(cross(u, v)) <= 1e-12 * u.norm() * v.norm() && u.dot(v) > 0) {
          node.fail("the outline folds back on itself at " + point_text(corner) + " (" +
                    line_name(panel, s.line) + " and " + line_name(panel, t.line) + ")");
        }
        continue;
      }
      if (!boxes_near(s.box, t.box, tolerance)) continue;
      if (segments_meet(s.a, s.b, t.a, t.b, tolerance, where)) {
        node.fail("the outline intersects itself near " + point_text(where) + ": " +
                  line_name(panel, s.line) +
                  (s.line == t.line ? " crosses itself" : " meets " + line_name(panel, t.line)));
      }
    }
  }
}

// Interior lines lie inside their panel and meet the outline only at corners
// between outline lines (so that no outline line gets a vertex that its
// equal-arc-length discretisation does not have).
void check_interior(const Node& node, const Panel& panel, double tolerance, double flattening) {
  std::vector<Curve> outline;
  std::vector<Vector2d> corners;
  for (const auto& line : panel.outline) {
    outline.push_back(line.curve);
    corners.push_back(line.curve.start());
  }
  const auto boundary = flat_segments(outline, flattening);
  const auto polygon = panel.outline_polygon(flattening);
  for (std::size_t l = 0; l < panel.interior.size(); ++l) {
    const InteriorLine& line = panel.interior[l];
    const Node where_defined = node.element(l);
    const auto points = line.curve.flatten(flattening);
    for (std::size_t k = 0; k + 1 < points.size(); ++k) {
      Eigen::AlignedBox2d box(points[k]);
      box.extend(points[k + 1]);
      for (const auto& segment : boundary) {
        if (!boxes_near(box, segment.box, tolerance)) continue;
        Vector2d where;
        if (!segments_meet(points[k], points[k + 1], segment.a, segment.b, tolerance, where))
          continue;
        const bool at_line_end =
            (k == 0 && (where - line.curve.start()).norm() <= tolerance) ||
            (k + 2 == points.size() && (where - line.curve.end()).norm() <= tolerance);
        const bool at_corner = std::any_of(corners.begin(), corners.end(), [&](const Vector2d& c) {
          return (c - where).norm() <= tolerance;
        });
        if (!(at_line_end && at_corner)) {
          where_defined.fail("interior line '" + line.id + "' meets the outline at " +
                             point_text(where) + ", which is not a corner between outline " +
                             "lines (an interior line may end on the outline only at such a " +
                             "corner; split the outline line there)");
        }
      }
      const Vector2d middle = 0.5 * (points[k] + points[k + 1]);
      if (!inside_polygon(polygon, middle)) {
        where_defined.fail("interior line '" + line.id + "' leaves the panel near " +
                           point_text(middle));
      }
    }
  }
}

// A fold line's crease (docs/pleats.md): the line must be straight, since
// pre-folding turns the warping region rigidly about its chord.
Crease read_crease(const Node& node, const Curve& curve, double flattening) {
  node.object();
  node.only_keys({"side", "angle_deg", "toward", "pressed"});
  Crease crease;
  crease.json_path = node.path;
  const std::string side = node.require("side").text();
  if (side != "left" && side != "right")
    node.child("side").fail("unknown side '" + side + "' (expected left or right)");
  crease.side = side == "left" ? Crease::Side::left : Crease::Side::right;
  const double degrees = node.require("angle_deg").number();
  if (!(degrees > 0 && degrees < 180))
    node.child("angle_deg")
        .fail("a crease angle must lie in (0, 180) degrees, got " + format_number(degrees));
  crease.angle = degrees * M_PI / 180;
  if (node.has("toward")) {
    const std::string toward = node.child("toward").text();
    if (toward != "outside" && toward != "inside")
      node.child("toward").fail("unknown direction '" + toward + "' (expected outside or inside)");
    crease.outside = toward == "outside";
  }
  if (node.has("pressed")) {
    crease.pressed = node.child("pressed").number();
    if (!(crease.pressed >= 1.0 && crease.pressed <= 1e4))
      node.child("pressed").fail(
          "a pressed crease is 1 to 10000 times as stiff as the fabric, got " +
          format_number(crease.pressed));
  }
  const Vector2d a = curve.start(), b = curve.end();
  for (const auto& p : curve.flatten(flattening)) {
    if (distance_to_segment(p, a, b) > std::max(flattening, 1e-3 * (b - a).norm()))
      node.fail("a creased fold line must be straight: it passes " +
                format_number(distance_to_segment(p, a, b)) + " m from its chord at " +
                point_text(p));
  }
  return crease;
}

Panel read_panel(const Node& node, double scale, double tolerance, double flattening,
                 std::set<std::string>& line_ids) {
  node.object();
  node.only_keys({"id", "fabric", "tag", "grain", "outline", "interior", "darts"});
  Panel panel;
  panel.json_path = node.path;
  panel.id = node.require("id").id();
  panel.fabric = check_fabric(node.require("fabric"), node.source);
  panel.tag = read_tag(node.require("tag"));
  panel.grain = read_grain(node.require("grain"), scale);

  const auto claim_id = [&](const Node& id_node) {
    std::string id = id_node.id();
    if (!line_ids.insert(id).second)
      id_node.fail("duplicate line id '" + id + "' (line ids are unique in a pattern)");
    return id;
  };

  const Node outline = node.require("outline");
  const std::size_t count = outline.array_size();
  if (count == 0) outline.fail("an outline needs at least one line");
  for (std::size_t i = 0; i < count; ++i) {
    const Node item = outline.element(i);
    item.object();
    item.only_keys({"id", "type", "points", "y_seam"});
    OutlineLine line;
    line.json_path = item.path;
    line.id = claim_id(item.require("id"));
    line.curve = read_curve(item, scale);
    if (item.has("y_seam")) line.y_seam = item.child("y_seam").boolean();
    panel.outline.push_back(std::move(line));
  }
  check_closed(outline, panel, tolerance);
  check_simple(outline, panel, tolerance, flattening);
  const double area = panel.area(flattening);
  if (std::abs(area) <= tolerance * tolerance) outline.fail("the outline encloses no area");
  if (area < 0) {
    // Clockwise in the file: turn round so that every panel is counter-clockwise.
    panel.reversed = true;
    std::reverse(panel.outline.begin(), panel.outline.end());
    for (auto& line : panel.outline) {
      line.curve = line.curve.reversed();
      line.reversed = true;
    }
  }

  if (node.has("interior")) {
    const Node interior = node.child("interior");
    for (std::size_t i = 0; i < interior.array_size(); ++i) {
      const Node item = interior.element(i);
      item.object();
      item.only_keys({"id", "kind", "type", "points", "crease"});
      InteriorLine line;
      line.json_path = item.path;
      line.id = claim_id(item.require("id"));
      const Node kind = item.require("kind");
      const std::string kind_name = kind.text();
      if (kind_name == "fold")
        line.kind = InteriorLine::Kind::fold;
      else if (kind_name == "t_seam")
        line.kind = InteriorLine::Kind::t_seam;
      else
        kind.fail("unknown interior line kind '" + kind_name + "' (expected fold or t_seam)");
      line.curve = read_curve(item, scale);
      if (item.has("crease")) {
        if (line.kind != InteriorLine::Kind::fold)
          item.child("crease").fail("only a fold line has a crease");
        line.crease = read_crease(item.child("crease"), line.curve, flattening);
      }
      panel.interior.push_back(std::move(line));
    }
    // An interior line that ends at a corner ends exactly there, so that the
    // mesher sees one vertex, not two a rounding error apart.
    for (auto& line : panel.interior) {
      for (Vector2d* end : {&line.curve.points.front(), &line.curve.points.back()})
        for (const auto& outline_line : panel.outline)
          if ((outline_line.curve.start() - *end).norm() <= tolerance)
            *end = outline_line.curve.start();
    }
    check_interior(interior, panel, tolerance, flattening);
  }
  if (node.has("darts"))
    panel.darts = read_darts(node.value.at("darts"), node.path + ".darts", node.source, panel);
  return panel;
}

void read_packs(const Node& root, Pattern& pattern, double scale) {
  std::vector<int> packed(pattern.panels.size(), -1);
  std::set<std::string> pack_ids;
  if (root.has("packs")) {
    const Node packs = root.child("packs");
    for (std::size_t p = 0; p < packs.array_size(); ++p) {
      const Node item = packs.element(p);
      item.object();
      item.only_keys({"id", "panels"});
      Pack pack;
      pack.json_path = item.path;
      pack.id = item.require("id").id();
      if (!pack_ids.insert(pack.id).second)
        item.child("id").fail("duplicate pack id '" + pack.id + "'");
      const Node members = item.require("panels");
      if (members.array_size() == 0) members.fail("a pack needs at least one panel");
      for (std::size_t m = 0; m < members.array_size(); ++m) {
        const Node member = members.element(m);
        member.object();
        member.only_keys({"panel", "at", "rotation_deg"});
        const Node panel_node = member.require("panel");
        const std::string panel_id = panel_node.id();
        const Panel* panel = pattern.find_panel(panel_id);
        if (!panel) panel_node.fail("unknown panel '" + panel_id + "'");
        Pack::Member entry;
        entry.panel = int(panel - pattern.panels.data());
        if (packed[entry.panel] >= 0) {
          panel_node.fail("panel '" + panel_id + "' is already in pack '" +
                          pattern.packs[packed[entry.panel]].id +
                          "' (a panel belongs to one pack)");
        }
        if (member.has("at")) entry.placement.translation = member.child("at").point(scale);
        if (member.has("rotation_deg"))
          entry.placement.rotation = member.child("rotation_deg").number() * M_PI / 180;
        const Panel& first =
            pattern.panels[pack.members.empty() ? entry.panel : pack.members.front().panel];
        if (panel->tag != first.tag) {
          // Thesis §3.1.2-3.1.3: a pack is tagged as a whole, so its panels share (alpha, beta,
          // lambda).
          panel_node.fail("pack '" + pack.id + "' mixes tags: panel '" + panel_id + "' is " +
                          to_string(panel->tag) + " but panel '" + first.id + "' is " +
                          to_string(first.tag) + " (the panels of a pack share one tag)");
        }
        packed[entry.panel] = int(pattern.packs.size());
        pack.members.push_back(entry);
      }
      pattern.packs.push_back(std::move(pack));
    }
  }
  for (std::size_t i = 0; i < pattern.panels.size(); ++i) {
    if (packed[i] >= 0) continue;
    // Thesis §3.1.3 step 1: unpacked panels become single-panel packs.
    Pack pack;
    pack.id = pattern.panels[i].id;
    if (!pack_ids.insert(pack.id).second) {
      root.fail("panel '" + pack.id + "' is in no pack, and its own pack would clash with " +
                "the pack of the same id");
    }
    pack.members.push_back({int(i), Placement{}});
    pack.implicit = true;
    pack.json_path = pattern.panels[i].json_path;
    pattern.packs.push_back(std::move(pack));
  }
}

} // namespace

Pattern parse_pattern(const std::string& text, const std::string& source) {
  const json document = parse_json_input(text, source);
  const Node root{document, "", source};
  root.object();
  root.only_keys({"format", "version", "name", "units", "tolerance", "hangs_from", "panels",
                  "packs", "pleats", "parameters"});
  const std::string format = root.require("format").text();
  if (format != "sartor-pattern")
    root.child("format").fail("expected \"sartor-pattern\", got \"" + format + "\"");
  Pattern pattern;
  pattern.source = source;
  pattern.version = root.require("version").integer();
  if (pattern.version != pattern_format_version) {
    root.child("version").fail("unsupported version " + std::to_string(pattern.version) +
                               " (this sartor reads version " +
                               std::to_string(pattern_format_version) + ")");
  }
  if (root.has("name")) pattern.name = root.child("name").text();
  if (root.has("hangs_from")) {
    const std::string from = root.child("hangs_from").text();
    if (from != "shoulders" && from != "waist")
      root.child("hangs_from").fail("expected \"shoulders\" or \"waist\", got \"" + from + "\"");
    pattern.hangs_from_shoulders = from == "shoulders";
  }
  double scale = 1;
  if (root.has("units")) {
    const std::string units = root.child("units").text();
    static const std::map<std::string, double> scales = {{"m", 1}, {"cm", 0.01}, {"mm", 0.001}};
    const auto found = scales.find(units);
    if (found == scales.end())
      root.child("units").fail("unknown units '" + units + "' (expected m, cm or mm)");
    scale = found->second;
  }
  if (root.has("tolerance")) {
    pattern.tolerance = scale * root.child("tolerance").number();
    if (!(pattern.tolerance > 0)) root.child("tolerance").fail("must be > 0");
  }

  const Node panels = root.require("panels");
  if (panels.array_size() == 0) panels.fail("a pattern needs at least one panel");
  // The flattening tolerance is relative to the pattern's size: read the
  // points once to find it.
  double size = 0;
  for (const auto& panel : panels.value)
    if (panel.is_object() && panel.contains("outline") && panel["outline"].is_array())
      for (const auto& line : panel["outline"])
        if (line.is_object() && line.contains("points") && line["points"].is_array())
          for (const auto& p : line["points"])
            if (p.is_array())
              for (const auto& x : p)
                if (x.is_number()) size = std::max(size, scale * std::abs(x.get<double>()));
  const double flattening = std::max(pattern.tolerance, 1e-5 * size);

  std::set<std::string> panel_ids, line_ids;
  for (std::size_t i = 0; i < panels.array_size(); ++i) {
    const Node item = panels.element(i);
    Panel panel = read_panel(item, scale, pattern.tolerance, flattening, line_ids);
    if (!panel_ids.insert(panel.id).second)
      item.child("id").fail("duplicate panel id '" + panel.id + "'");
    pattern.panels.push_back(std::move(panel));
  }
  read_packs(root, pattern, scale);
  if (root.has("pleats")) apply_pleats(pattern, document.at("pleats"), scale);
  if (root.has("parameters"))
    pattern.parameters =
        read_sloper_parameters(document.at("parameters"), "parameters", source, pattern);
  return pattern;
}

Pattern read_pattern(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the pattern file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_pattern(text.str(), path);
}

bool inside_polygon(const std::vector<Vector2d>& polygon, const Vector2d& p) {
  bool in = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Vector2d& a = polygon[i];
    const Vector2d& b = polygon[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      in = !in;
  }
  return in;
}

} // namespace sartor::garment
