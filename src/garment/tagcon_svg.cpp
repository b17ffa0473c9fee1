#include "garment/tagcon_svg.hpp"

#include "garment/pattern_svg.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace sartor::garment {

namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

constexpr double pixel = 0.005; // m: the silhouette's raster cell

std::string number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f", value);
  return buffer;
}

struct View {
  std::string title;
  Vector3d right;       // screen x
  double left_edge = 0; // m, in the view's x
  Vector2d operator()(const Vector3d& p, double top) const {
    return {1000 * (p.dot(right) - left_edge), 1000 * (top - p.z())};
  }
};

double cross(const Vector2d& a, const Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// The body's silhouette in a view as runs of raster cells, one rect per run.
std::string silhouette(const View& view, const std::vector<Vector3d>& vertices,
                       const std::vector<std::array<int, 3>>& faces, double top, double offset_x) {
  Eigen::AlignedBox2d box;
  std::vector<Vector2d> flat;
  for (const auto& v : vertices) {
    flat.emplace_back(v.dot(view.right), v.z());
    box.extend(flat.back());
  }
  const int columns = int(std::ceil(box.sizes().x() / pixel)) + 1;
  const int rows = int(std::ceil(box.sizes().y() / pixel)) + 1;
  std::vector<char> covered(std::size_t(columns) * std::size_t(rows), 0);
  for (const auto& f : faces) {
    const Vector2d a = flat[std::size_t(f[0])], b = flat[std::size_t(f[1])],
                   c = flat[std::size_t(f[2])];
    const double area = cross(b - a, c - a);
    if (std::abs(area) < 1e-14) continue;
    Eigen::AlignedBox2d t;
    t.extend(a);
    t.extend(b);
    t.extend(c);
    const int c0 = int((t.min().x() - box.min().x()) / pixel);
    const int c1 = int((t.max().x() - box.min().x()) / pixel);
    const int r0 = int((t.min().y() - box.min().y()) / pixel);
    const int r1 = int((t.max().y() - box.min().y()) / pixel);
    for (int r = r0; r <= r1; ++r)
      for (int col = c0; col <= c1; ++col) {
        const Vector2d p = box.min() + pixel * Vector2d(col + 0.5, r + 0.5);
        const double w0 = cross(b - p, c - p) / area, w1 = cross(c - p, a - p) / area;
        if (w0 >= 0 && w1 >= 0 && w0 + w1 <= 1)
          covered[std::size_t(r) * std::size_t(columns) + std::size_t(col)] = 1;
      }
  }
  std::ostringstream svg;
  svg << "<g class=\"body\">\n";
  for (int r = 0; r < rows; ++r) {
    int start = -1;
    for (int col = 0; col <= columns; ++col) {
      const bool on =
          col < columns && covered[std::size_t(r) * std::size_t(columns) + std::size_t(col)];
      if (on && start < 0) start = col;
      if (!on && start >= 0) {
        const double x = box.min().x() + start * pixel;
        const double z = box.min().y() + (r + 1) * pixel;
        svg << "<rect x=\"" << number(1000 * (x - view.left_edge) + offset_x) << "\" y=\""
            << number(1000 * (top - z)) << "\" width=\"" << number(1000 * (col - start) * pixel)
            << "\" height=\"" << number(1000 * pixel) << "\"/>\n";
        start = -1;
      }
    }
  }
  svg << "</g>\n";
  return svg.str();
}

} // namespace

std::string placement_svg(const Construction& construction,
                          const std::vector<Vector3d>& body_vertices,
                          const std::vector<std::array<int, 3>>& body_faces) {
  const Pattern& pattern = *construction.pattern;
  Eigen::AlignedBox3d box;
  for (const auto& v : body_vertices)
    box.extend(v);
  for (const auto& line : construction.lines)
    for (const auto& p : line.samples)
      box.extend(p);
  const double margin = 0.05;
  const double top = box.max().z() + margin;
  const double height = 1000 * (box.sizes().z() + 2 * margin);
  View front{"front", Vector3d::UnitX(), box.min().x() - margin};
  View side{"left side", Vector3d::UnitY(), box.min().y() - margin};
  const double front_width = 1000 * (box.sizes().x() + 2 * margin);
  const double side_width = 1000 * (box.sizes().y() + 2 * margin);

  std::ostringstream svg;
  svg << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << number(front_width + side_width)
      << "mm\" height=\"" << number(height) << "mm\" viewBox=\"0 0 "
      << number(front_width + side_width) << " " << number(height) << "\">\n"
      << "<title>TAGCON placement: " << pattern.name << "</title>\n"
      << "<style>\n"
         ".body rect { fill: #c8c8c8; stroke: none; }\n"
         ".panel { fill: #f0d890; fill-opacity: 0.45; stroke: #604000; stroke-width: 1; }\n"
         ".sweep { stroke-width: 2.5; }\n"
         ".label { font: 24px sans-serif; }\n"
         "</style>\n";
  double offset_x = 0;
  for (const View* view : {&front, &side}) {
    svg << "<g id=\"view-" << (view == &front ? "front" : "side") << "\">\n"
        << silhouette(*view, body_vertices, body_faces, top, offset_x);
    // Panels from the inner layer out.
    std::vector<std::size_t> order(pattern.panels.size());
    for (std::size_t k = 0; k < order.size(); ++k)
      order[k] = k;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return pattern.panels[a].tag.layer < pattern.panels[b].tag.layer;
    });
    for (std::size_t panel : order) {
      std::string points;
      for (const auto& line : construction.lines) {
        if (line.panel != int(panel) || line.interior) continue;
        for (std::size_t k = 0; k + 1 < line.samples.size(); ++k) {
          const Vector2d q = (*view)(line.samples[k], top) + Vector2d(offset_x, 0);
          points += number(q.x()) + "," + number(q.y()) + " ";
        }
      }
      svg << "<polygon class=\"panel\" points=\"" << points << "\"><title>"
          << pattern.panels[panel].id << "</title></polygon>\n";
    }
    for (const auto& seam : construction.seams) {
      const Vector2d a =
          (*view)(construction.lines[std::size_t(seam.line_a)].centre, top) + Vector2d(offset_x, 0);
      const Vector2d b =
          (*view)(construction.lines[std::size_t(seam.line_b)].centre, top) + Vector2d(offset_x, 0);
      svg << "<line class=\"sweep\" stroke=\"" << certainty_colour(seam.certainty) << "\" x1=\""
          << number(a.x()) << "\" y1=\"" << number(a.y()) << "\" x2=\"" << number(b.x())
          << "\" y2=\"" << number(b.y()) << "\"><title>"
          << construction.lines[std::size_t(seam.line_a)].id << " + "
          << construction.lines[std::size_t(seam.line_b)].id << "</title></line>\n";
    }
    svg << "<text class=\"label\" x=\"" << number(offset_x + 20) << "\" y=\"40\">" << view->title
        << "</text>\n</g>\n";
    offset_x += view == &front ? front_width : side_width;
  }
  svg << svg_legend(20, height - 20, !construction.seams.empty()) << "</svg>\n";
  return svg.str();
}

} // namespace sartor::garment
