#include "app/edit_design.hpp"

#include "common/error.hpp"
#include "garment/pattern_edit.hpp"

#include <algorithm>
#include <fstream>
#include <map>

namespace sartor {

namespace {

// A point along an outline line: where, its arc-length fraction, its
// curve parameter.
struct LinePoint {
  Eigen::Vector2d at;
  double s = 0.0;
  double t = 0.0;
};

// Points along an outline line, its end left out (the next line's start):
// a straight line its start, a polyline its points, a Bezier 16 pieces of
// equal arc length.
std::vector<LinePoint> line_points(const garment::Curve& curve) {
  std::vector<LinePoint> points;
  if (curve.kind == garment::Curve::Kind::bezier) {
    constexpr int pieces = 16;
    std::vector<double> t;
    const auto split = curve.split_equal_arc_length(pieces, &t);
    for (int k = 0; k < pieces; ++k)
      points.push_back({split[std::size_t(k)], double(k) / pieces, t[std::size_t(k)]});
    return points;
  }
  double total = 0.0;
  for (std::size_t k = 1; k < curve.points.size(); ++k)
    total += (curve.points[k] - curve.points[k - 1]).norm();
  double along = 0.0;
  for (std::size_t k = 0; k + 1 < curve.points.size(); ++k) {
    points.push_back({curve.points[k], along / total, 0.0});
    along += (curve.points[k + 1] - curve.points[k]).norm();
  }
  return points;
}

// The Bernstein weights of a cubic's inner control points at t.
Eigen::Vector2d inner_bernstein(double t) {
  return {3.0 * t * (1.0 - t) * (1.0 - t), 3.0 * t * t * (1.0 - t)};
}

} // namespace

EditDesign::EditDesign(const garment::Pattern& pattern, const TriangleMesh& mesh,
                       const std::vector<int>& panel_of_triangle,
                       garment::InteriorCoordinates interior)
    : pattern_(pattern), mesh_(mesh) {
  for (const garment::Panel& panel : pattern.panels) {
    first_corner_of_panel_.push_back(corners_);
    corners_ += int(panel.outline.size());
  }
  slots_ = corners_;
  for (std::size_t panel = 0; panel < pattern.panels.size(); ++panel) {
    const auto& outline = pattern.panels[panel].outline;
    const int first = first_corner_of_panel_[panel];
    const int n = int(outline.size());
    std::vector<OutlinePoint> polygon;
    for (int i = 0; i < n; ++i) {
      const garment::Curve& curve = outline[std::size_t(i)].curve;
      int control = -1;
      if (curve.kind == garment::Curve::Kind::bezier) {
        control = slots_;
        first_control_[{panel, std::size_t(i)}] = control;
        slots_ += 2;
      }
      for (const LinePoint& point : line_points(curve))
        polygon.push_back({point.at, first + i, first + (i + 1) % n, point.s, control, point.t});
    }
    polygons_.push_back(polygon);
  }
  vertices_.resize(mesh.vertex_count());
  std::vector<Eigen::Vector2d> uv(mesh.vertex_count(), Eigen::Vector2d::Zero());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    for (std::size_t c = 0; c < 3; ++c) {
      const auto v = std::size_t(mesh.triangles[t][c]);
      uv[v] = mesh.material_uv[t][c];
      vertices_[v].panel = panel_of_triangle.at(t);
    }
  for (std::size_t v = 0; v < vertices_.size(); ++v) {
    const int panel = vertices_[v].panel;
    if (panel < 0) continue;
    const garment::GrainLine& grain = pattern.panels[std::size_t(panel)].grain;
    const Eigen::Vector2d at = grain.origin + uv[v].x() * grain.warp + uv[v].y() * grain.weft();
    std::vector<Eigen::Vector2d> polygon;
    for (const OutlinePoint& point : polygons_[std::size_t(panel)])
      polygon.push_back(point.at);
    const std::vector<double> lambda = garment::panel_coordinates(interior, polygon, at);
    std::map<int, double> weights;
    for (std::size_t k = 0; k < polygon.size(); ++k) {
      const OutlinePoint& point = polygons_[std::size_t(panel)][k];
      weights[point.first_corner] += lambda[k] * (1.0 - point.s);
      weights[point.second_corner] += lambda[k] * point.s;
      if (point.first_control < 0) continue;
      const Eigen::Vector2d bernstein = inner_bernstein(point.t);
      weights[point.first_control] += lambda[k] * bernstein[0];
      weights[point.first_control + 1] += lambda[k] * bernstein[1];
    }
    vertices_[v].slots.assign(weights.begin(), weights.end());
  }
}

std::vector<int> EditDesign::moved_slots(const CornerMove& move) const {
  std::vector<int> slots;
  for (const garment::OutlinePoint& point :
       garment::moved_outline_points(pattern_, move.line, move.which, move.control)) {
    // read_edit_file lets control moves name Bezier lines only.
    slots.push_back(point.control > 0
                        ? first_control_.at({point.panel, point.index}) + point.control - 1
                        : first_corner_of_panel_[point.panel] + int(point.index));
  }
  return slots;
}

Eigen::VectorXd EditDesign::parameters(const std::vector<CornerMove>& moves) const {
  // A corner named by several moves of a step (the shared end of two lines
  // moved together) moves once (read_edit_file refuses different moves).
  std::map<int, Eigen::Vector2d> moved;
  for (const CornerMove& move : moves)
    for (int slot : moved_slots(move))
      moved.emplace(slot, move.by);
  Eigen::VectorXd p = Eigen::VectorXd::Zero(size());
  for (const auto& [slot, move] : moved)
    p.segment<2>(2 * slot) = move;
  return p;
}

RestChange EditDesign::rest_change(const Eigen::VectorXd& p, const TriangleMesh& mesh) const {
  std::vector<Eigen::Vector2d> delta(vertices_.size(), Eigen::Vector2d::Zero());
  for (std::size_t v = 0; v < vertices_.size(); ++v) {
    if (vertices_[v].panel < 0) continue;
    Eigen::Vector2d move = Eigen::Vector2d::Zero();
    for (const auto& [slot, weight] : vertices_[v].slots)
      move += weight * p.segment<2>(2 * slot);
    const garment::GrainLine& grain = pattern_.panels[std::size_t(vertices_[v].panel)].grain;
    delta[v] = {move.dot(grain.warp), move.dot(grain.weft())};
  }
  return rest_change_per_vertex(mesh, delta);
}

std::vector<std::vector<Eigen::Vector2d>> EditDesign::outlines(const Eigen::VectorXd& p) const {
  std::vector<std::vector<Eigen::Vector2d>> result;
  for (const auto& polygon : polygons_) {
    std::vector<Eigen::Vector2d> moved;
    for (const OutlinePoint& point : polygon) {
      Eigen::Vector2d at = point.at + (1.0 - point.s) * p.segment<2>(2 * point.first_corner) +
                           point.s * p.segment<2>(2 * point.second_corner);
      if (point.first_control >= 0) {
        const Eigen::Vector2d bernstein = inner_bernstein(point.t);
        at += bernstein[0] * p.segment<2>(2 * point.first_control) +
              bernstein[1] * p.segment<2>(2 * point.first_control + 2);
      }
      moved.push_back(at);
    }
    result.push_back(moved);
  }
  return result;
}

double EditDesign::largest_move(const Eigen::VectorXd& p) const {
  double largest = 0.0;
  for (int slot = 0; slot < slots_; ++slot)
    largest = std::max(largest, p.segment<2>(2 * slot).norm());
  return largest;
}

void write_edit_svg(const std::string& path, const garment::Pattern& pattern,
                    const std::vector<std::vector<Eigen::Vector2d>>& before,
                    const std::vector<std::vector<Eigen::Vector2d>>& after,
                    const std::string& title) {
  const std::vector<garment::Placement> layout = garment::sheet_layout(pattern, 0.05);
  Eigen::Vector2d low = Eigen::Vector2d::Constant(1e300), high = -low;
  const auto place = [&](std::size_t panel, const Eigen::Vector2d& q) {
    return layout[panel].apply(q);
  };
  for (const auto* outlines : {&before, &after})
    for (std::size_t panel = 0; panel < outlines->size(); ++panel)
      for (const Eigen::Vector2d& q : (*outlines)[panel]) {
        low = low.cwiseMin(place(panel, q));
        high = high.cwiseMax(place(panel, q));
      }
  const double margin = 0.03, scale = 1000.0; // 1 mm per user unit
  const Eigen::Vector2d size = (high - low).array() + 2.0 * margin;
  std::ofstream out(path);
  if (!out) throw InputError(path + ": cannot write the edited pattern");
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << size.x() * scale
      << "mm\" height=\"" << size.y() * scale + 8 << "mm\" viewBox=\"0 -8 " << size.x() * scale
      << " " << size.y() * scale + 8 << "\">\n<title>" << title << "</title>\n"
      << "<text x=\"2\" y=\"-2\" font-size=\"6\">" << title
      << " (grey: before, red: after; mm)</text>\n";
  const auto polygon = [&](const std::vector<std::vector<Eigen::Vector2d>>& outlines,
                           const char* style) {
    for (std::size_t panel = 0; panel < outlines.size(); ++panel) {
      out << "<polygon " << style << " points=\"";
      for (const Eigen::Vector2d& q : outlines[panel]) {
        const Eigen::Vector2d at = place(panel, q);
        out << (at.x() - low.x() + margin) * scale << "," << (high.y() - at.y() + margin) * scale
            << " ";
      }
      out << "\"/>\n";
    }
  };
  polygon(before, "fill=\"none\" stroke=\"#999\" stroke-width=\"1\"");
  polygon(after, "fill=\"none\" stroke=\"#c00\" stroke-width=\"1\"");
  out << "</svg>\n";
}

nlohmann::json edit_outlines_json(const garment::Pattern& pattern,
                                  const std::vector<std::vector<Eigen::Vector2d>>& before,
                                  const std::vector<std::vector<Eigen::Vector2d>>& after,
                                  const std::string& title) {
  const std::vector<garment::Placement> layout = garment::sheet_layout(pattern, 0.05);
  const auto placed = [&](std::size_t panel, const std::vector<Eigen::Vector2d>& outline) {
    nlohmann::json points = nlohmann::json::array();
    for (const Eigen::Vector2d& q : outline) {
      const Eigen::Vector2d at = layout[panel].apply(q);
      points.push_back({at.x(), at.y()});
    }
    return points;
  };
  nlohmann::json panels = nlohmann::json::array();
  for (std::size_t panel = 0; panel < before.size(); ++panel)
    panels.push_back({{"id", pattern.panels[panel].id},
                      {"before", placed(panel, before[panel])},
                      {"after", placed(panel, after[panel])}});
  return {{"title", title}, {"units", "m"}, {"panels", panels}};
}

} // namespace sartor
