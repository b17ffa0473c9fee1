#include "garment/dart_insertion.hpp"

#include "common/csv.hpp"
#include "common/error.hpp"
#include "garment/pattern.hpp"

#include <array>
#include <cmath>
#include <map>

namespace sartor::garment {

namespace {

using Vector2d = Eigen::Vector2d;

// Where the line is: its panel and place in the outline, in the file.
struct LinePlace {
  std::size_t panel = 0, index = 0;
  bool reversed = false; // the panel's outline runs clockwise in the file
};

LinePlace find_line(const nlohmann::json& document, const Pattern& pattern, const std::string& line,
                    const std::string& source) {
  const nlohmann::json& panels = document.at("panels");
  for (std::size_t p = 0; p < panels.size(); ++p) {
    const nlohmann::json& outline = panels[p].at("outline");
    for (std::size_t i = 0; i < outline.size(); ++i)
      if (outline[i].value("id", "") == line) return {p, i, pattern.panels.at(p).reversed};
  }
  throw InputError(source + ": add dart: '" + line + "' is not an outline line of the pattern");
}

// The file's curve of the line, in metres.
Curve file_curve(const nlohmann::json& line, double scale) {
  Curve curve;
  const std::string type = line.at("type").get<std::string>();
  curve.kind = type == "bezier" ? Curve::Kind::bezier : Curve::Kind::straight;
  for (const auto& point : line.at("points"))
    curve.points.emplace_back(scale * point.at(0).get<double>(), scale * point.at(1).get<double>());
  return curve;
}

// The curve parameter at arc length s: a straight line's fraction, a
// Bezier's from its fine flattening (to 1e-10 of its length).
double parameter_at(const Curve& curve, double s) {
  const double length = curve.length();
  if (curve.kind == Curve::Kind::straight) return s / length;
  std::vector<double> t;
  const std::vector<Vector2d> points = curve.flatten(1e-10 * length, &t);
  double along = 0.0;
  for (std::size_t k = 1; k < points.size(); ++k) {
    const double piece = (points[k] - points[k - 1]).norm();
    if (along + piece >= s) return t[k - 1] + (t[k] - t[k - 1]) * (s - along) / piece;
    along += piece;
  }
  return 1.0;
}

// The control points of a cubic's piece from t0 to t1 (de Casteljau).
std::array<Vector2d, 4> bezier_piece(const std::vector<Vector2d>& p, double t0, double t1) {
  const auto split_right = [](const std::array<Vector2d, 4>& q, double t) {
    const Vector2d a = (1 - t) * q[0] + t * q[1], b = (1 - t) * q[1] + t * q[2],
                   c = (1 - t) * q[2] + t * q[3];
    const Vector2d d = (1 - t) * a + t * b, e = (1 - t) * b + t * c;
    const Vector2d f = (1 - t) * d + t * e;
    return std::array<std::array<Vector2d, 4>, 2>{{{q[0], a, d, f}, {f, e, c, q[3]}}};
  };
  const std::array<Vector2d, 4> whole{p[0], p[1], p[2], p[3]};
  const std::array<Vector2d, 4> right = split_right(whole, t0)[1];
  return t1 >= 1.0 ? right : split_right(right, (t1 - t0) / (1 - t0))[0];
}

nlohmann::json points_json(const std::vector<Vector2d>& points, double scale) {
  nlohmann::json json = nlohmann::json::array();
  for (const Vector2d& p : points)
    json.push_back({p.x() / scale, p.y() / scale});
  return json;
}

// The line's piece from t0 to t1 as a line of the file, id `id`.
nlohmann::json line_piece(const nlohmann::json& line, const Curve& curve, double t0, double t1,
                          const std::string& id, double scale) {
  nlohmann::json piece = line;
  piece["id"] = id;
  if (curve.kind == Curve::Kind::bezier) {
    const std::array<Vector2d, 4> q = bezier_piece(curve.points, t0, t1);
    piece["points"] = points_json({q.begin(), q.end()}, scale);
  } else {
    piece["points"] = points_json({curve.at(t0), curve.at(t1)}, scale);
  }
  return piece;
}

// Whether the JSON value holds the string `text` anywhere.
bool mentions(const nlohmann::json& value, const std::string& text) {
  if (value.is_string()) return value.get<std::string>() == text;
  for (const auto& item : value)
    if (mentions(item, text)) return true;
  return false;
}

// Sloper parameters' moves of the line's corners become moves of its pieces'
// (the outline as read runs counter-clockwise: a clockwise file's line is
// turned round, so its start is the second piece's).
void move_parameters_to_pieces(nlohmann::json& document, const std::string& line,
                               const LinePlace& place) {
  if (!document.contains("parameters") || !document["parameters"].is_array()) return;
  const std::string first = line + "_a", second = line + "_b";
  const std::string& start_piece = place.reversed ? second : first;
  const std::string& end_piece = place.reversed ? first : second;
  for (auto& parameter : document["parameters"]) {
    if (!parameter.contains("moves") || !parameter["moves"].is_array()) continue;
    nlohmann::json moves = nlohmann::json::array();
    for (const auto& move : parameter["moves"]) {
      if (move.value("line", "") != line) {
        moves.push_back(move);
        continue;
      }
      const std::string corner = move.value("corner", "both");
      for (const auto& [piece, which] : {std::pair{start_piece, "start"}, {end_piece, "end"}}) {
        if (corner != "both" && corner != which) continue;
        nlohmann::json moved = move;
        moved["line"] = piece;
        moved["corner"] = which;
        moves.push_back(moved);
      }
    }
    parameter["moves"] = moves;
  }
}

double units_scale(const nlohmann::json& document) {
  static const std::map<std::string, double> scales = {{"m", 1}, {"cm", 0.01}, {"mm", 0.001}};
  return scales.at(document.value("units", "m"));
}

} // namespace

nlohmann::json add_dart(const nlohmann::json& document, const std::string& source,
                        const DartInsertion& dart) {
  const Pattern pattern = parse_pattern(document.dump(), source);
  const auto fail = [&](const std::string& what) {
    throw InputError(source + ": add dart on '" + dart.line + "': " + what);
  };
  const LinePlace place = find_line(document, pattern, dart.line, source);
  if (document.contains("pleats") && mentions(document["pleats"], dart.line))
    fail("a pleat names the line; add the dart to the pleated pattern's file instead");
  if (!(dart.width > 0.0) || !(dart.depth > 0.0)) fail("the width and the depth must be > 0");
  const nlohmann::json& line = document["panels"][place.panel]["outline"][place.index];
  const std::string type = line.value("type", "");
  if (type != "straight" && type != "bezier")
    fail("a " + type + " line: darts go on straight and Bezier lines");
  const double scale = units_scale(document);
  const Curve curve = file_curve(line, scale);
  const double length = curve.length();
  const double first = dart.at * length - 0.5 * dart.width, second = first + dart.width;
  if (!(first > pattern.tolerance && second < length - pattern.tolerance)) {
    fail("the cut from " + format_number(first) + " to " + format_number(second) +
         " m along it leaves the line (" + format_number(length) + " m long)");
  }
  const double t1 = parameter_at(curve, first), t2 = parameter_at(curve, second);
  const Vector2d base1 = curve.at(t1), base2 = curve.at(t2);
  const Vector2d chord = base2 - base1;
  // Inside lies left of a counter-clockwise outline, right of a clockwise one.
  const Vector2d left = Vector2d(-chord.y(), chord.x()).normalized();
  const Vector2d apex = 0.5 * (base1 + base2) + dart.depth * (place.reversed ? -left : left);
  const std::string id = dart.id.empty() ? dart.line + "_dart" : dart.id;

  nlohmann::json result = document;
  nlohmann::json& panel = result["panels"][place.panel];
  nlohmann::json outline = nlohmann::json::array();
  for (std::size_t i = 0; i < panel["outline"].size(); ++i) {
    if (i != place.index) {
      outline.push_back(panel["outline"][i]);
      continue;
    }
    outline.push_back(line_piece(line, curve, 0.0, t1, dart.line + "_a", scale));
    outline.push_back(
        {{"id", id + "_in"}, {"type", "straight"}, {"points", points_json({base1, apex}, scale)}});
    outline.push_back(
        {{"id", id + "_out"}, {"type", "straight"}, {"points", points_json({apex, base2}, scale)}});
    outline.push_back(line_piece(line, curve, t2, 1.0, dart.line + "_b", scale));
  }
  panel["outline"] = outline;
  panel["darts"].push_back({{"id", id}, {"legs", {id + "_in", id + "_out"}}});
  move_parameters_to_pieces(result, dart.line, place);
  parse_pattern(result.dump(), source + " with dart '" + id + "'");
  return result;
}

} // namespace sartor::garment
