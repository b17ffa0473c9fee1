#include "garment/pattern_svg.hpp"

#include "common/output.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace sartor::garment {

namespace {

using Eigen::Vector2d;

std::string escape_xml(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
    case '&':
      out += "&amp;";
      break;
    case '<':
      out += "&lt;";
      break;
    case '>':
      out += "&gt;";
      break;
    case '"':
      out += "&quot;";
      break;
    case '\'':
      out += "&apos;";
      break;
    default:
      out += c;
    }
  }
  return out;
}

// Sheet metres to SVG millimetres, y pointing down.
struct Canvas {
  double top = 0; // sheet y of the drawing's top edge, m
  Vector2d operator()(const Vector2d& sheet) const {
    return {1000 * sheet.x(), 1000 * (top - sheet.y())};
  }
};

std::string number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3f", value);
  return buffer;
}

std::string xy(const Vector2d& p) {
  return number(p.x()) + "," + number(p.y());
}

// An SVG path of one curve after placing it: Beziers stay Beziers under a
// rigid motion.
std::string path_of(const Curve& curve, const Placement& placement, const Canvas& canvas,
                    bool move_first) {
  std::string d;
  const auto at = [&](const Vector2d& p) { return xy(canvas(placement.apply(p))); };
  if (move_first) d += "M " + at(curve.start()) + " ";
  if (curve.kind == Curve::Kind::bezier) {
    d += "C " + at(curve.points[1]) + " " + at(curve.points[2]) + " " + at(curve.points[3]) + " ";
  } else {
    for (std::size_t k = 1; k < curve.points.size(); ++k)
      d += "L " + at(curve.points[k]) + " ";
  }
  return d;
}

std::string label(const Vector2d& at, const std::string& text, const char* css_class) {
  return "<text class=\"" + std::string(css_class) + "\" x=\"" + number(at.x()) + "\" y=\"" +
         number(at.y()) + "\">" + escape_xml(text) + "</text>\n";
}

// The SVG element (its size in mm, the view box in canvas units), the title,
// the grain arrow's marker and the style sheet.
std::string svg_head(const Pattern& pattern, double left, double width, double height) {
  std::ostringstream svg;
  svg << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << number(width) << "mm\" height=\""
      << number(height) << "mm\" viewBox=\"" << number(left) << " 0 " << number(width) << " "
      << number(height) << "\">\n"
      << "<title>" << escape_xml(pattern.name.empty() ? pattern.source : pattern.name)
      << "</title>\n"
      << "<defs><marker id=\"arrow\" viewBox=\"0 0 10 10\" refX=\"10\" refY=\"5\" "
         "markerWidth=\"6\" markerHeight=\"6\" orient=\"auto\"><path d=\"M 0 0 L 10 5 L 0 10 "
         "z\" fill=\"#2060c0\"/></marker></defs>\n"
      << "<style>\n"
         ".outline { fill: #f4efe4; stroke: #000; stroke-width: 1; }\n"
         ".yseam { fill: none; stroke: #d02020; stroke-width: 2.5; }\n"
         ".interior { fill: none; stroke: #606060; stroke-width: 1; stroke-dasharray: 6 4; }\n"
         ".grain { stroke: #2060c0; stroke-width: 1.2; marker-end: url(#arrow); }\n"
         ".panel { font: 16px sans-serif; text-anchor: middle; }\n"
         ".line { font: 9px sans-serif; fill: #404040; text-anchor: middle; }\n"
         ".seam { fill: none; stroke-width: 3; stroke-opacity: 0.8; }\n"
         ".sweep { stroke-width: 1.5; stroke-dasharray: 5 3; }\n"
         "</style>\n";
  return svg.str();
}

} // namespace

std::string pattern_svg(const Pattern& pattern, const SvgOptions& options) {
  const std::vector<Placement> layout = sheet_layout(pattern, options.gap);
  const double tolerance = pattern.flattening_tolerance();
  Eigen::AlignedBox2d sheet;
  for (std::size_t i = 0; i < pattern.panels.size(); ++i)
    for (const auto& p : pattern.panels[i].outline_polygon(tolerance))
      sheet.extend(layout[i].apply(p));
  const double margin = options.gap;
  Canvas canvas;
  canvas.top = sheet.max().y() + margin;
  const double width = 1000 * (sheet.sizes().x() + 2 * margin);
  const double height = 1000 * (sheet.sizes().y() + 2 * margin);
  const double left = 1000 * (sheet.min().x() - margin);

  std::ostringstream svg;
  svg << svg_head(pattern, left, width, height);

  for (std::size_t i = 0; i < pattern.panels.size(); ++i) {
    const Panel& panel = pattern.panels[i];
    const Placement& placement = layout[i];
    svg << "<g id=\"panel-" << escape_xml(panel.id) << "\">\n";
    std::string outline;
    for (std::size_t l = 0; l < panel.outline.size(); ++l)
      outline += path_of(panel.outline[l].curve, placement, canvas, l == 0);
    svg << "<path class=\"outline\" d=\"" << outline << "Z\"/>\n";
    for (const auto& line : panel.outline) {
      if (line.y_seam) {
        svg << "<path class=\"yseam\" d=\"" << path_of(line.curve, placement, canvas, true)
            << "\"/>\n";
      }
    }
    for (const auto& line : panel.interior) {
      svg << "<path class=\"interior\" d=\"" << path_of(line.curve, placement, canvas, true)
          << "\"/>\n";
    }

    Eigen::AlignedBox2d box;
    for (const auto& p : panel.outline_polygon(tolerance))
      box.extend(p);
    const Vector2d centre = box.center();
    const double half = 0.25 * box.sizes().minCoeff();
    svg << "<line class=\"grain\" x1=\""
        << number(canvas(placement.apply(centre - half * panel.grain.warp)).x()) << "\" y1=\""
        << number(canvas(placement.apply(centre - half * panel.grain.warp)).y()) << "\" x2=\""
        << number(canvas(placement.apply(centre + half * panel.grain.warp)).x()) << "\" y2=\""
        << number(canvas(placement.apply(centre + half * panel.grain.warp)).y()) << "\"/>\n";
    const Vector2d text_at = canvas(placement.apply(centre + 0.5 * half * panel.grain.weft()));
    svg << label(text_at, panel.id, "panel")
        << label(text_at + Vector2d(0, 20), to_string(panel.tag) + " " + panel.fabric, "line");
    if (options.line_labels) {
      for (const auto& line : panel.outline)
        svg << label(canvas(placement.apply(line.curve.at(0.5))), line.id, "line");
      for (const auto& line : panel.interior)
        svg << label(canvas(placement.apply(line.curve.at(0.5))), line.id, "line");
    }
    svg << "</g>\n";
  }
  for (const SvgSeam& seam : options.seams) {
    std::vector<Vector2d> middles;
    const std::string colour = certainty_colour(seam.certainty);
    for (const std::string* id : {&seam.line_a, &seam.line_b}) {
      for (std::size_t i = 0; i < pattern.panels.size(); ++i) {
        const Panel& panel = pattern.panels[i];
        const auto draw = [&](const Curve& curve) {
          svg << "<path class=\"seam\" stroke=\"" << colour << "\" d=\""
              << path_of(curve, layout[i], canvas, true) << "\"/>\n";
          middles.push_back(canvas(layout[i].apply(curve.at(0.5))));
        };
        for (const auto& line : panel.outline)
          if (line.id == *id) draw(line.curve);
        for (const auto& line : panel.interior)
          if (line.id == *id) draw(line.curve);
      }
    }
    if (middles.size() == 2) {
      svg << "<line class=\"sweep\" stroke=\"" << colour << "\" x1=\"" << number(middles[0].x())
          << "\" y1=\"" << number(middles[0].y()) << "\" x2=\"" << number(middles[1].x())
          << "\" y2=\"" << number(middles[1].y()) << "\"><title>" << escape_xml(seam.line_a)
          << " + " << escape_xml(seam.line_b) << ": certainty " << number(seam.certainty)
          << "</title></line>\n";
    }
  }
  svg << svg_legend(left + 20, height - 20, !options.seams.empty()) << "</svg>\n";
  return svg.str();
}

std::string certainty_colour(double certainty) {
  const double c = std::clamp(certainty, 0.0, 1.0);
  char buffer[8];
  std::snprintf(buffer, sizeof buffer, "#%02x%02x%02x", int(std::lround(230 * (1 - c))), 40,
                int(std::lround(230 * c)));
  return buffer;
}

std::string svg_legend(double x, double y, bool seams) {
  std::ostringstream svg;
  // Not a group: a group per panel is the drawing's structure.
  const char* font = "\" font-family=\"sans-serif\" font-size=\"12";
  svg << "<line x1=\"" << number(x) << "\" y1=\"" << number(y) << "\" x2=\"" << number(x + 100)
      << "\" y2=\"" << number(y) << "\" stroke=\"#000\" stroke-width=\"2\"/>\n"
      << "<text x=\"" << number(x + 50) << "\" y=\"" << number(y - 5) << font
      << "\" text-anchor=\"middle\">10 cm</text>\n";
  if (seams) {
    const double top = y - 50;
    svg << "<text x=\"" << number(x) << "\" y=\"" << number(top - 8) << font
        << "\">seam certainty</text>\n";
    for (int k = 0; k <= 4; ++k) {
      const double at = x + 30 * k;
      svg << "<rect x=\"" << number(at) << "\" y=\"" << number(top) << "\" width=\"28\" "
          << "height=\"12\" fill=\"" << certainty_colour(0.25 * k) << "\"/>\n"
          << "<text x=\"" << number(at + 14) << "\" y=\"" << number(top + 26) << font
          << "\" text-anchor=\"middle\">" << number(0.25 * k) << "</text>\n";
    }
  }
  return svg.str();
}

void write_pattern_svg(const std::string& path, const Pattern& pattern, const SvgOptions& options) {
  write_file_atomically(path, pattern_svg(pattern, options));
}

} // namespace sartor::garment
