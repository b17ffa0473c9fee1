#include "garment/import_svg.hpp"

#include "common/csv.hpp"
#include "common/error.hpp"

#include <boost/property_tree/ptree.hpp>
#include <boost/property_tree/xml_parser.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

namespace sartor::garment {

using Eigen::Vector2d;
namespace pt = boost::property_tree;

namespace {

std::string attribute(const pt::ptree& node, const std::string& name) {
  return node.get<std::string>("<xmlattr>." + name, "");
}

// Numbers of an SVG attribute (path data, viewBox, transform arguments):
// separated by spaces or commas, or by nothing where the next sign or a
// second decimal point starts a new number ("1.5.5", "3-4").
class Scanner {
public:
  explicit Scanner(const std::string& text) : text_(text) {}
  void skip() {
    while (pos_ < text_.size() &&
           (std::isspace(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == ','))
      ++pos_;
  }
  bool done() {
    skip();
    return pos_ >= text_.size();
  }
  char peek() {
    skip();
    return pos_ < text_.size() ? text_[pos_] : '\0';
  }
  bool number_next() {
    const char c = peek();
    return std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.';
  }
  char command() { return peek() != '\0' ? text_[pos_++] : '\0'; }
  double number(const std::string& where) {
    skip();
    const std::size_t start = pos_;
    if (pos_ < text_.size() && (text_[pos_] == '+' || text_[pos_] == '-')) ++pos_;
    bool dot = false, digits = false;
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (std::isdigit(static_cast<unsigned char>(c))) {
        digits = true;
      } else if (c == '.' && !dot) {
        dot = true;
      } else {
        break;
      }
      ++pos_;
    }
    if (digits && pos_ < text_.size() && (text_[pos_] == 'e' || text_[pos_] == 'E')) {
      std::size_t e = pos_ + 1;
      if (e < text_.size() && (text_[e] == '+' || text_[e] == '-')) ++e;
      if (e < text_.size() && std::isdigit(static_cast<unsigned char>(text_[e]))) {
        pos_ = e;
        while (pos_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[pos_])))
          ++pos_;
      }
    }
    if (!digits)
      throw InputError(where + ": expected a number at character " + std::to_string(start + 1) +
                       " of \"" + text_ + "\"");
    return std::stod(text_.substr(start, pos_ - start));
  }

private:
  const std::string& text_;
  std::size_t pos_ = 0;
};

// The transform attribute: a list applied right to left, as SVG composes it.
Affine2 parse_transform(const std::string& text, const std::string& where) {
  Affine2 result;
  std::size_t pos = 0;
  while (true) {
    while (pos < text.size() &&
           (std::isspace(static_cast<unsigned char>(text[pos])) || text[pos] == ','))
      ++pos;
    if (pos >= text.size()) break;
    const std::size_t open = text.find('(', pos), close = text.find(')', pos);
    if (open == std::string::npos || close == std::string::npos || close < open)
      throw InputError(where + ": cannot read the transform \"" + text + "\"");
    std::string name = text.substr(pos, open - pos);
    name.erase(std::remove_if(name.begin(), name.end(), ::isspace), name.end());
    const std::string arguments = text.substr(open + 1, close - open - 1);
    Scanner scan(arguments);
    std::vector<double> a;
    while (!scan.done())
      a.push_back(scan.number(where + ": transform " + name));
    Affine2 t;
    const auto need = [&](std::size_t low, std::size_t high) {
      if (a.size() < low || a.size() > high)
        throw InputError(where + ": transform " + name + " takes " + std::to_string(low) +
                         (low == high ? "" : " to " + std::to_string(high)) + " numbers, got " +
                         std::to_string(a.size()));
    };
    if (name == "matrix") {
      need(6, 6);
      t.linear << a[0], a[2], a[1], a[3];
      t.offset = Vector2d(a[4], a[5]);
    } else if (name == "translate") {
      need(1, 2);
      t.offset = Vector2d(a[0], a.size() > 1 ? a[1] : 0.0);
    } else if (name == "scale") {
      need(1, 2);
      t.linear = Vector2d(a[0], a.size() > 1 ? a[1] : a[0]).asDiagonal();
    } else if (name == "rotate") {
      if (a.size() != 1 && a.size() != 3) need(1, 1);
      const double r = a[0] * M_PI / 180;
      t.linear << std::cos(r), -std::sin(r), std::sin(r), std::cos(r);
      if (a.size() == 3) {
        const Vector2d c(a[1], a[2]);
        t.offset = c - t.linear * c;
      }
    } else if (name == "skewX" || name == "skewY") {
      need(1, 1);
      const double k = std::tan(a[0] * M_PI / 180);
      t.linear(name == "skewX" ? 0 : 1, name == "skewX" ? 1 : 0) = k;
    } else {
      throw InputError(where + ": unknown transform \"" + name + "\"");
    }
    result = result.after(t);
    pos = close + 1;
  }
  return result;
}

struct Subpath {
  std::vector<Curve> curves;
  bool closed = false;
};

Curve straight(const Vector2d& a, const Vector2d& b) {
  Curve c;
  c.kind = Curve::Kind::straight;
  c.points = {a, b};
  return c;
}

Curve cubic(const Vector2d& a, const Vector2d& b, const Vector2d& c, const Vector2d& d) {
  Curve curve;
  curve.kind = Curve::Kind::bezier;
  curve.points = {a, b, c, d};
  return curve;
}

// Path data (SVG 1.1 §8.3) to subpaths of straight and cubic pieces. A
// quadratic's control point q becomes the cubic's p0 + 2/3 (q - p0) and
// p1 + 2/3 (q - p1), the same curve.
std::vector<Subpath> parse_path_data(const std::string& d, const std::string& where) {
  std::vector<Subpath> subpaths;
  Scanner scan(d);
  Vector2d current = Vector2d::Zero(), start = Vector2d::Zero(), last_control = Vector2d::Zero();
  char previous = ' ', command = ' ';
  const auto add = [&](const Curve& c) {
    if (subpaths.empty()) throw InputError(where + ": path data must start with M");
    if (c.length() > 0) subpaths.back().curves.push_back(c);
  };
  while (!scan.done()) {
    if (!scan.number_next()) {
      command = scan.command();
    } else if (command == 'M') {
      command = 'L'; // further pairs after a moveto are linetos
    } else if (command == 'm') {
      command = 'l';
    } else if (command == ' ' || command == 'Z' || command == 'z') {
      throw InputError(where + ": path data: a number where a command was expected in \"" + d +
                       "\"");
    }
    const bool relative = std::islower(static_cast<unsigned char>(command));
    const Vector2d origin = relative ? current : Vector2d::Zero();
    const auto point = [&]() -> Vector2d {
      const double x = scan.number(where + ": path data");
      const double y = scan.number(where + ": path data");
      return Vector2d(x, y) + origin;
    };
    const char upper = char(std::toupper(static_cast<unsigned char>(command)));
    Vector2d control = current;
    switch (upper) {
    case 'M':
      current = start = point();
      subpaths.push_back({});
      break;
    case 'L': {
      const Vector2d p = point();
      add(straight(current, p));
      current = p;
      break;
    }
    case 'H':
    case 'V': {
      const double value = scan.number(where + ": path data");
      Vector2d p = current;
      (upper == 'H' ? p.x() : p.y()) =
          value + (relative ? (upper == 'H' ? current.x() : current.y()) : 0.0);
      add(straight(current, p));
      current = p;
      break;
    }
    case 'C':
    case 'S': {
      const bool smooth = upper == 'S';
      const std::string prior = "CcSs";
      const Vector2d c1 =
          smooth ? (prior.find(previous) != std::string::npos ? Vector2d(2 * current - last_control)
                                                              : current)
                 : point();
      const Vector2d c2 = point(), p = point();
      add(cubic(current, c1, c2, p));
      control = c2;
      current = p;
      break;
    }
    case 'Q':
    case 'T': {
      const std::string prior = "QqTt";
      const Vector2d q = upper == 'T' ? (prior.find(previous) != std::string::npos
                                             ? Vector2d(2 * current - last_control)
                                             : current)
                                      : point();
      const Vector2d p = point();
      add(cubic(current, current + 2.0 / 3.0 * (q - current), p + 2.0 / 3.0 * (q - p), p));
      control = q;
      current = p;
      break;
    }
    case 'Z':
      if (subpaths.empty()) throw InputError(where + ": path data must start with M");
      add(straight(current, start));
      subpaths.back().closed = true;
      current = start;
      break;
    case 'A':
      throw InputError(where + ": path data: elliptical arcs (A) are not read; convert them to "
                               "curves (e.g. Inkscape: Path > Object to Path)");
    default:
      throw InputError(where + ": path data: unknown command '" + std::string(1, command) + "'");
    }
    last_control = control;
    previous = command;
  }
  return subpaths;
}

bool has_token(const std::string& text, const std::string& token) {
  std::istringstream words(text);
  std::string word;
  while (words >> word)
    if (word == token) return true;
  return false;
}

// FreeSewing 4 names a part's group "fs-stack-DESIGN.PART-part-DESIGN.PART"
// (older releases "fs-part-PART" or "part-PART"): the piece is PART.
std::string piece_name(const std::string& id) {
  std::string name = id;
  const std::size_t part = name.rfind("-part-");
  if (part != std::string::npos) name = name.substr(part + 6);
  for (const std::string prefix : {"fs-part-", "fs-stack-", "part-"})
    if (name.rfind(prefix, 0) == 0) name = name.substr(prefix.size());
  const std::size_t design = name.rfind('.');
  return design == std::string::npos ? name : name.substr(design + 1);
}

std::string lower(std::string text) {
  for (char& c : text)
    c = char(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

// Whether a path is a grain or fold mark: its id or class says so, or, as
// FreeSewing 4 draws them, its markers (url(#grainlineFrom),
// url(#cutonfoldFrom)) or its data-text (plugin-annotations:cutOnFold,
// plugin-annotations:cutOnFoldAndGrainline).
bool marks(const pt::ptree& node, const std::string& id, const std::string& what) {
  for (const std::string& text : {id, attribute(node, "class"), attribute(node, "marker-start"),
                                  attribute(node, "marker-end"), attribute(node, "data-text")})
    if (lower(text).find(what) != std::string::npos) return true;
  return false;
}

double length_unit(const std::string& value, const std::string& where) {
  std::size_t end = 0;
  double number = 0;
  try {
    number = std::stod(value, &end);
  } catch (const std::exception&) {
    throw InputError(where + ": cannot read the length \"" + value + "\"");
  }
  std::string unit = value.substr(end);
  unit.erase(std::remove_if(unit.begin(), unit.end(), ::isspace), unit.end());
  static const std::map<std::string, double> metres = {
      {"mm", 1e-3},       {"cm", 1e-2},        {"in", 0.0254},   {"pt", 0.0254 / 72},
      {"pc", 0.0254 / 6}, {"px", 0.0254 / 96}, {"", 0.0254 / 96}};
  const auto found = metres.find(unit);
  if (found == metres.end() || !(number > 0))
    throw InputError(where + ": cannot tell the units of \"" + value +
                     "\" (expected a positive length in mm, cm, in, pt, pc or px)");
  return number * found->second;
}

// FreeSewing also marks points inside a piece with its notch snippet (a
// bust point, a dart's tip): only notches on the outline split it.
void drop_interior_notches(ImportedPiece& piece) {
  constexpr double on_outline = 1e-3; // m
  std::vector<Vector2d> outline;
  for (const Curve& c : piece.boundary) {
    const auto points = c.flatten(1e-5);
    outline.insert(outline.end(), points.begin(), points.end());
  }
  const auto near_outline = [&](const Vector2d& p) {
    for (std::size_t k = 0; k + 1 < outline.size(); ++k) {
      const Vector2d a = outline[k], ab = outline[k + 1] - a;
      const double t =
          ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
      if ((a + t * ab - p).norm() <= on_outline) return true;
    }
    return false;
  };
  piece.notches.erase(std::remove_if(piece.notches.begin(), piece.notches.end(),
                                     [&](const Vector2d& p) { return !near_outline(p); }),
                      piece.notches.end());
}

struct PieceDraft {
  ImportedPiece piece;
  std::vector<std::pair<std::string, Subpath>> outlines; // path id, closed subpath
};

class SvgWalker {
public:
  SvgWalker(const std::string& source) : source_(source) {}

  void walk(const pt::ptree& node, const Affine2& to_metres, const std::string& piece) {
    for (const auto& [tag, child] : node) {
      if (tag == "<xmlattr>" || tag == "<xmlcomment>" || tag == "defs" || tag == "marker" ||
          tag == "symbol" || tag == "clipPath" || tag == "mask" || tag == "pattern")
        continue;
      const std::string id = attribute(child, "id");
      const std::string where =
          source_ + ": <" + tag + (id.empty() ? "" : " id=\"" + id + "\"") + ">";
      const Affine2 map = to_metres.after(parse_transform(attribute(child, "transform"), where));
      if (tag == "g") {
        walk(child, map, id.empty() ? piece : piece_name(id));
      } else if (tag == "path") {
        add_path(child, map, piece, id, where);
      } else if (tag == "use") {
        const std::string href = attribute(child, "xlink:href") + attribute(child, "href");
        if (href.find("notch") == std::string::npos) continue;
        const double x = child.get<double>("<xmlattr>.x", 0.0),
                     y = child.get<double>("<xmlattr>.y", 0.0);
        draft(piece).piece.notches.push_back(map(Vector2d(x, y)));
      }
    }
  }

  std::vector<ImportedPiece> pieces() {
    std::vector<ImportedPiece> result;
    for (PieceDraft& d : drafts_) {
      if (d.outlines.empty()) {
        if (d.piece.grain || d.piece.fold) {
          throw InputError(d.piece.where + ": has a grain or fold line but no outline (a closed "
                                           "path of class \"fabric\")");
        }
        continue;
      }
      // The largest closed fabric path is the outline; others (dart or
      // placement lines drawn as fabric) are internal lines.
      std::size_t best = 0;
      double best_area = -1;
      for (std::size_t k = 0; k < d.outlines.size(); ++k) {
        double twice = 0;
        std::vector<Vector2d> poly;
        for (const Curve& c : d.outlines[k].second.curves) {
          const auto pts = c.flatten(1e-5);
          poly.insert(poly.end(), pts.begin(), pts.end() - 1);
        }
        for (std::size_t i = 0; i < poly.size(); ++i) {
          const Vector2d& a = poly[i];
          const Vector2d& b = poly[(i + 1) % poly.size()];
          twice += a.x() * b.y() - a.y() * b.x();
        }
        if (std::abs(twice) > best_area) best_area = std::abs(twice), best = k;
      }
      for (std::size_t k = 0; k < d.outlines.size(); ++k) {
        // Open cut-line paths are marks on the outline, e.g. FreeSewing's
        // hem fold line (class "fabric stroke-sm") across a hem allowance.
        if (k == best || !d.outlines[k].second.closed) continue;
        std::vector<Vector2d> line{d.outlines[k].second.curves.front().start()};
        for (const Curve& c : d.outlines[k].second.curves) {
          const auto pts = c.flatten(1e-4);
          line.insert(line.end(), pts.begin() + 1, pts.end());
        }
        d.piece.internal.push_back(line);
      }
      const Subpath& outline = d.outlines[best].second;
      if (!outline.closed)
        throw InputError(
            d.piece.where + ": path \"" + d.outlines[best].first +
            "\": the outline (class \"fabric\") is not closed: its last point is " +
            format_number((outline.curves.back().end() - outline.curves.front().start()).norm()) +
            " m from its first");
      d.piece.boundary = outline.curves;
      d.piece.boundary.back().points.back() = d.piece.boundary.front().start();
      drop_interior_notches(d.piece);
      result.push_back(d.piece);
    }
    if (result.empty())
      throw InputError(source_ + ": no pattern piece: no group holds a closed path of class "
                                 "\"fabric\" (docs/patterns.md#svg)");
    return result;
  }

private:
  PieceDraft& draft(const std::string& piece) {
    const std::string name = piece.empty() ? "piece" : piece;
    for (PieceDraft& d : drafts_)
      if (d.piece.name == name) return d;
    drafts_.push_back({});
    drafts_.back().piece.name = name;
    drafts_.back().piece.where = source_ + ": piece '" + name + "'";
    return drafts_.back();
  }

  void add_path(const pt::ptree& node, const Affine2& map, const std::string& piece,
                const std::string& id, const std::string& where) {
    const std::string cls = attribute(node, "class");
    const bool grain = marks(node, id, "grainline");
    const bool fold = marks(node, id, "cutonfold");
    const bool cut_line =
        (has_token(cls, "fabric") || has_token(cls, "lining") || has_token(cls, "interfacing")) &&
        !has_token(cls, "sa");
    if (!grain && !fold && !cut_line) return;
    std::vector<Subpath> subpaths = parse_path_data(attribute(node, "d"), where);
    for (Subpath& s : subpaths)
      for (Curve& c : s.curves)
        c = mapped(c, map);
    subpaths.erase(std::remove_if(subpaths.begin(), subpaths.end(),
                                  [](const Subpath& s) { return s.curves.empty(); }),
                   subpaths.end());
    if (subpaths.empty()) return;
    PieceDraft& d = draft(piece);
    if (grain || fold) {
      const Segment ends{subpaths.front().curves.front().start(),
                         subpaths.back().curves.back().end()};
      if ((ends[1] - ends[0]).norm() <= 0)
        throw InputError(where + ": the " + std::string(grain ? "grain" : "fold") +
                         " line's first and last points coincide");
      if (grain) d.piece.grain = ends;
      if (fold) d.piece.fold = ends;
      return;
    }
    for (Subpath& s : subpaths) {
      if (!s.closed && (s.curves.back().end() - s.curves.front().start()).norm() <= 1e-6)
        s.closed = true;
      d.outlines.emplace_back(id, s);
    }
  }

  std::string source_;
  std::vector<PieceDraft> drafts_;
};

} // namespace

std::vector<ImportedPiece> parse_svg_pieces(const std::string& text, const std::string& source) {
  pt::ptree tree;
  std::istringstream in(text);
  try {
    pt::read_xml(in, tree, pt::xml_parser::no_comments);
  } catch (const pt::xml_parser_error& error) {
    throw InputError(source + ": not valid XML: " + error.message() + " at line " +
                     std::to_string(error.line()));
  }
  const auto svg = tree.get_child_optional("svg");
  if (!svg) throw InputError(source + ": no <svg> element at the top");
  // User units to metres: the width over the viewBox's width (FreeSewing:
  // width="...mm" and a viewBox in mm); without a viewBox user units are px.
  const std::string width = attribute(*svg, "width"), view_box = attribute(*svg, "viewBox");
  double scale = 0.0254 / 96;
  Vector2d view_origin = Vector2d::Zero();
  if (!view_box.empty()) {
    Scanner scan(view_box);
    std::vector<double> v;
    while (!scan.done())
      v.push_back(scan.number(source + ": <svg viewBox>"));
    if (v.size() != 4 || !(v[2] > 0))
      throw InputError(source + ": <svg viewBox=\"" + view_box +
                       "\">: expected four numbers, a positive width third");
    view_origin = Vector2d(v[0], v[1]);
    if (width.empty())
      throw InputError(source + ": <svg> has a viewBox but no width: cannot tell the units");
    scale = length_unit(width, source + ": <svg width>") / v[2];
  } else if (!attribute(*svg, "freesewing").empty()) {
    // FreeSewing 4 writes no viewBox but draws in millimetres, the width in
    // mm being the drawing's extent in user units.
    scale = 1e-3;
  } else if (!width.empty()) {
    length_unit(width, source + ": <svg width>"); // checked; user units stay px
  }
  Affine2 to_metres;
  to_metres.linear = Eigen::Vector2d(scale, -scale).asDiagonal();
  to_metres.offset = Vector2d(-scale * view_origin.x(), scale * view_origin.y());
  SvgWalker walker(source);
  walker.walk(*svg, to_metres, "");
  return walker.pieces();
}

std::vector<ImportedPiece> read_svg_pieces(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the SVG file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_svg_pieces(text.str(), path);
}

} // namespace sartor::garment
