#include "garment/pattern_import.hpp"

#include "common/csv.hpp"
#include "common/error.hpp"
#include "common/json_input.hpp"
#include "garment/seam_overrides.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

namespace sartor::garment {

using Eigen::Vector2d;
using nlohmann::json;

namespace {

// Points closer than this are one point; a notch or fold edge this close to
// the boundary lies on it (patterns are drawn to 0.1 mm at best).
constexpr double snap = 5e-4; // m

double cross(const Vector2d& a, const Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

Vector2d start_tangent(const Curve& c) {
  for (std::size_t k = 1; k < c.points.size(); ++k)
    if ((c.points[k] - c.points[0]).norm() > 1e-12) return (c.points[k] - c.points[0]).normalized();
  return Vector2d::UnitX();
}

Vector2d end_tangent(const Curve& c) {
  const Vector2d& last = c.points.back();
  for (std::size_t k = c.points.size() - 1; k-- > 0;)
    if ((last - c.points[k]).norm() > 1e-12) return (last - c.points[k]).normalized();
  return Vector2d::UnitX();
}

std::vector<Vector2d> flattened(const std::vector<Curve>& loop) {
  std::vector<Vector2d> polygon;
  for (const Curve& c : loop) {
    const auto points = c.flatten(1e-5);
    polygon.insert(polygon.end(), points.begin(), points.end() - 1);
  }
  return polygon;
}

double signed_area(const std::vector<Vector2d>& polygon) {
  double twice = 0;
  for (std::size_t i = 0; i < polygon.size(); ++i)
    twice += cross(polygon[i], polygon[(i + 1) % polygon.size()]);
  return 0.5 * twice;
}

// The two halves of a cubic (or a straight) at t, by de Casteljau.
std::array<Curve, 2> split(const Curve& c, double t) {
  std::array<Curve, 2> halves{c, c};
  if (c.kind == Curve::Kind::bezier) {
    const auto& p = c.points;
    const Vector2d a = (1 - t) * p[0] + t * p[1], b = (1 - t) * p[1] + t * p[2],
                   d = (1 - t) * p[2] + t * p[3];
    const Vector2d ab = (1 - t) * a + t * b, bd = (1 - t) * b + t * d;
    const Vector2d m = (1 - t) * ab + t * bd;
    halves[0].points = {p[0], a, ab, m};
    halves[1].points = {m, bd, d, p[3]};
  } else {
    const Vector2d m = c.at(t);
    halves[0].points = {c.start(), m};
    halves[1].points = {m, c.end()};
  }
  return halves;
}

// The parameter of the point of a straight or cubic curve nearest to p:
// sampled, then refined by golden-section search.
double nearest_parameter(const Curve& c, const Vector2d& p) {
  constexpr int samples = 200;
  int best = 0;
  for (int k = 1; k <= samples; ++k)
    if ((c.at(double(k) / samples) - p).norm() < (c.at(double(best) / samples) - p).norm())
      best = k;
  double lo = std::max(0.0, (best - 1.0) / samples), hi = std::min(1.0, (best + 1.0) / samples);
  for (int iteration = 0; iteration < 60; ++iteration) {
    const double m1 = lo + 0.382 * (hi - lo), m2 = lo + 0.618 * (hi - lo);
    if ((c.at(m1) - p).norm() < (c.at(m2) - p).norm())
      hi = m2;
    else
      lo = m1;
  }
  return 0.5 * (lo + hi);
}

// Splits the boundary curves at the notches; returns, per curve, whether a
// line must start at its start (a notch is there).
std::vector<bool> split_at_notches(std::vector<Curve>& loop, const ImportedPiece& piece) {
  std::vector<bool> starts_line(loop.size(), false);
  for (const Vector2d& notch : piece.notches) {
    std::size_t best = 0;
    double best_t = 0, best_distance = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const double t = nearest_parameter(loop[k], notch);
      const double distance = (loop[k].at(t) - notch).norm();
      if (distance < best_distance) best = k, best_t = t, best_distance = distance;
    }
    if (best_distance > snap)
      throw InputError(piece.where + ": the notch at (" + format_number(notch.x()) + ", " +
                       format_number(notch.y()) + ") m is " + format_number(best_distance) +
                       " m from the boundary");
    const Curve& c = loop[best];
    if ((c.at(best_t) - c.start()).norm() <= snap) {
      starts_line[best] = true;
    } else if ((c.at(best_t) - c.end()).norm() <= snap) {
      starts_line[(best + 1) % loop.size()] = true;
    } else {
      auto halves = split(c, best_t);
      loop[best] = halves[0];
      loop.insert(loop.begin() + std::ptrdiff_t(best) + 1, halves[1]);
      starts_line.insert(starts_line.begin() + std::ptrdiff_t(best) + 1, true);
    }
  }
  return starts_line;
}

double distance_to_line(const Vector2d& p, const Segment& line) {
  const Vector2d d = (line[1] - line[0]).normalized();
  return std::abs(cross(d, p - line[0]));
}

Vector2d reflect(const Vector2d& p, const Segment& line) {
  const Vector2d d = (line[1] - line[0]).normalized();
  const Vector2d r = p - line[0];
  return line[0] + 2 * r.dot(d) * d - r;
}

Curve reflected(const Curve& c, const Segment& line) {
  Curve out = c;
  for (auto& p : out.points)
    p = reflect(p, line);
  return out;
}

// Cut on the fold: the piece and its mirror image about the fold line, one
// loop without the fold edge.
void unfold(ImportedPiece& piece) {
  const Segment fold = *piece.fold;
  std::vector<Curve>& loop = piece.boundary;
  const auto on_fold = [&](const Curve& c) {
    return std::all_of(c.points.begin(), c.points.end(),
                       [&](const Vector2d& p) { return distance_to_line(p, fold) <= snap; });
  };
  const std::size_t n = loop.size();
  std::size_t first = n;
  for (std::size_t k = 0; k < n; ++k)
    if (on_fold(loop[k]) && !on_fold(loop[(k + n - 1) % n])) first = k;
  if (first == n)
    throw InputError(piece.where + ": the cut-on-fold line is not an edge of the piece's " +
                     "boundary (no boundary curve lies along it)");
  std::rotate(loop.begin(), loop.begin() + std::ptrdiff_t(first), loop.end());
  std::size_t fold_curves = 0;
  while (fold_curves < n && on_fold(loop[fold_curves]))
    ++fold_curves;
  std::vector<Curve> rest(loop.begin() + std::ptrdiff_t(fold_curves), loop.end());
  if (std::any_of(rest.begin(), rest.end(), on_fold))
    throw InputError(piece.where + ": the boundary runs along the cut-on-fold line twice");
  std::vector<Curve> unfolded = rest;
  for (auto c = rest.rbegin(); c != rest.rend(); ++c)
    unfolded.push_back(reflected(*c, fold).reversed());
  loop = unfolded;
  // A notch on the fold (a centre front mark) lies inside the unfolded panel:
  // it marks, it splits no line. The others get their mirror images.
  std::vector<Vector2d> notches;
  for (const Vector2d& notch : piece.notches)
    if (distance_to_line(notch, fold) > snap) notches.push_back(notch);
  const std::size_t kept = notches.size();
  for (std::size_t k = 0; k < kept; ++k)
    notches.push_back(reflect(notches[k], fold));
  piece.notches = notches;
  const std::size_t internal = piece.internal.size();
  for (std::size_t k = 0; k < internal; ++k) {
    std::vector<Vector2d> mirror;
    for (const Vector2d& p : piece.internal[k])
      mirror.push_back(reflect(p, fold));
    piece.internal.push_back(mirror);
  }
}

// Consecutive curves joined into lines: a line ends at a corner (a turn
// sharper than the corner angle) and where a line must start (a notch).
std::vector<Curve> outline_lines(std::vector<Curve> loop, std::vector<bool> starts_line,
                                 double corner_angle_deg) {
  const std::size_t n = loop.size();
  const double corner = std::cos(corner_angle_deg * M_PI / 180);
  for (std::size_t k = 0; k < n; ++k)
    if (end_tangent(loop[(k + n - 1) % n]).dot(start_tangent(loop[k])) < corner)
      starts_line[k] = true;
  const auto first = std::find(starts_line.begin(), starts_line.end(), true);
  const std::size_t shift =
      first == starts_line.end() ? 0 : std::size_t(first - starts_line.begin());
  std::rotate(loop.begin(), loop.begin() + std::ptrdiff_t(shift), loop.end());
  std::rotate(starts_line.begin(), starts_line.begin() + std::ptrdiff_t(shift), starts_line.end());
  starts_line[0] = true;
  // A closed loop of one smooth line (a circle) is cut in two.
  if (std::count(starts_line.begin(), starts_line.end(), true) == 1 && n > 1)
    starts_line[n / 2] = true;
  std::vector<Curve> lines;
  for (std::size_t k = 0; k < n;) {
    std::size_t end = k + 1;
    while (end < n && !starts_line[end])
      ++end;
    if (end == k + 1) {
      lines.push_back(loop[k]);
    } else {
      Curve polyline;
      polyline.kind = Curve::Kind::polyline;
      polyline.points.push_back(loop[k].start());
      for (std::size_t j = k; j < end; ++j) {
        const auto points = loop[j].flatten(1e-4);
        polyline.points.insert(polyline.points.end(), points.begin() + 1, points.end());
      }
      lines.push_back(polyline);
    }
    k = end;
  }
  if (lines.size() == 1) lines = {split(lines[0], 0.5)[0], split(lines[0], 0.5)[1]};
  return lines;
}

// A dart: two lines meeting at a reflex corner (a V cut into the piece),
// their chords narrower than the largest dart angle, equal in length within
// 5%. The legs may be curves: FreeSewing draws its darts' legs as cubic
// Béziers, shaped to the body.
std::vector<std::array<std::size_t, 2>> find_darts(const std::vector<Curve>& lines,
                                                   bool counter_clockwise, double max_angle_deg) {
  std::vector<std::array<std::size_t, 2>> darts;
  const std::size_t n = lines.size();
  std::vector<bool> used(n, false);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t next = (k + 1) % n;
    const Curve &in = lines[k], &out = lines[next];
    if (used[k] || used[next]) continue;
    const Vector2d a = in.start() - in.end(), b = out.end() - out.start();
    const double turn = cross(in.end() - in.start(), b);
    const bool reflex = counter_clockwise ? turn < 0 : turn > 0;
    const double angle = std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0));
    const double la = in.length(), lb = out.length();
    if (reflex && angle < max_angle_deg * M_PI / 180 &&
        std::abs(la - lb) <= 0.05 * std::max(la, lb)) {
      darts.push_back({k, next});
      used[k] = used[next] = true;
    }
  }
  return darts;
}

json point_json(const Vector2d& p) {
  // Rounded to 1 nm: the file stays readable, far below any pattern's precision.
  return json::array({std::round(p.x() * 1e9) / 1e9, std::round(p.y() * 1e9) / 1e9});
}

json curve_json(const Curve& c) {
  json points = json::array();
  for (const Vector2d& p : c.points)
    points.push_back(point_json(p));
  return {{"type", name_of(c.kind)}, {"points", points}};
}

json tag_json(const PanelTag& tag) {
  return {{"cylinder", name_of(tag.cylinder)}, {"side", name_of(tag.side)}, {"layer", tag.layer}};
}

std::string safe_id(const std::string& name) {
  std::string id = name.empty() ? "piece" : name;
  for (char& c : id)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  return id;
}

json panel_json(const ImportedPiece& piece, const std::string& id, const PanelTag& tag,
                const std::string& fabric, bool darts_wanted, double corner_angle_deg,
                double max_dart_angle_deg, ImportReport* report) {
  std::vector<Curve> loop = piece.boundary;
  const std::vector<bool> starts = split_at_notches(loop, piece);
  const std::vector<Curve> lines = outline_lines(loop, starts, corner_angle_deg);
  const auto polygon = flattened(lines);
  const bool ccw = signed_area(polygon) > 0;
  json panel = {{"id", id}, {"fabric", fabric}, {"tag", tag_json(tag)}};
  if (piece.grain)
    panel["grain"] = {{"from", point_json((*piece.grain)[0])},
                      {"to", point_json((*piece.grain)[1])}};
  else
    panel["grain"] = {{"angle_deg", 90}};
  json outline = json::array();
  for (std::size_t k = 0; k < lines.size(); ++k) {
    json line = curve_json(lines[k]);
    line["id"] = id + "_" + std::to_string(k + 1);
    outline.push_back(line);
  }
  panel["outline"] = outline;
  json darts = json::array();
  if (darts_wanted) {
    for (const auto& dart : find_darts(lines, ccw, max_dart_angle_deg))
      darts.push_back({{"id", id + "_dart" + std::to_string(darts.size() + 1)},
                       {"legs", {outline[dart[0]]["id"], outline[dart[1]]["id"]}}});
  }
  if (!darts.empty()) panel["darts"] = darts;
  json interior = json::array();
  int skipped = 0;
  for (const auto& line : piece.internal) {
    const bool within = line.size() >= 2 && std::all_of(line.begin(), line.end(), [&](auto& p) {
                          return inside_polygon(polygon, p);
                        });
    if (!within) {
      ++skipped;
      continue;
    }
    Curve curve;
    curve.kind = line.size() == 2 ? Curve::Kind::straight : Curve::Kind::polyline;
    curve.points = line;
    json entry = curve_json(curve);
    entry["id"] = id + "_in" + std::to_string(interior.size() + 1);
    entry["kind"] = "fold";
    interior.push_back(entry);
  }
  if (!interior.empty()) panel["interior"] = interior;
  if (report) {
    report->lines.push_back(
        "panel '" + id + "' " + to_string(tag) + ": " + std::to_string(lines.size()) + " lines, " +
        std::to_string(darts.size()) + " darts, " + std::to_string(piece.notches.size()) +
        " notches, " + std::to_string(interior.size()) + " internal lines as fold lines" +
        (skipped ? " (" + std::to_string(skipped) + " not inside the panel left out)" : ""));
  }
  return panel;
}

PieceSettings read_piece_settings(const json& value, const std::string& where) {
  if (!value.is_object()) throw InputError(where + ": expected an object");
  PieceSettings settings;
  for (const auto& item : value.items()) {
    const std::string at = where + "." + item.key();
    const json& v = item.value();
    if (item.key() == "tag") {
      settings.tag = read_panel_tag(v, at);
    } else if (item.key() == "twin_tag") {
      settings.twin_tag = read_panel_tag(v, at);
    } else if (item.key() == "fabric") {
      if (!v.is_string()) throw InputError(at + ": expected a fabric name (string)");
      settings.fabric = v.get<std::string>();
    } else if (item.key() == "cut") {
      if (!v.is_number_integer() || v.get<int>() < 1 || v.get<int>() > 2)
        throw InputError(at + ": expected 1 or 2");
      settings.quantity = v.get<int>();
    } else if (item.key() == "mirror") {
      if (!v.is_string() || (v != "left" && v != "right"))
        throw InputError(at +
                         ": expected \"left\" or \"right\" (the edge a twin is mirrored about)");
      settings.mirror_right = v == "right";
    } else if (item.key() == "darts") {
      if (!v.is_boolean()) throw InputError(at + ": expected true or false");
      settings.darts = v.get<bool>();
    } else if (item.key() == "import") {
      if (!v.is_boolean()) throw InputError(at + ": expected true or false");
      settings.imported = v.get<bool>();
    } else {
      throw InputError(at + ": unknown key (expected one of: tag, twin_tag, fabric, cut, mirror, "
                            "darts, import)");
    }
  }
  return settings;
}

ImportedPiece mirrored_twin(const ImportedPiece& piece, bool about_right) {
  double edge = about_right ? -std::numeric_limits<double>::infinity()
                            : std::numeric_limits<double>::infinity();
  for (const Vector2d& p : flattened(piece.boundary))
    edge = about_right ? std::max(edge, p.x()) : std::min(edge, p.x());
  const Segment axis{Vector2d(edge, 0), Vector2d(edge, 1)};
  ImportedPiece twin = piece;
  for (Curve& c : twin.boundary)
    c = reflected(c, axis);
  for (auto& line : twin.internal)
    for (Vector2d& p : line)
      p = reflect(p, axis);
  for (Vector2d& p : twin.notches)
    p = reflect(p, axis);
  if (twin.grain)
    twin.grain = Segment{reflect((*twin.grain)[0], axis), reflect((*twin.grain)[1], axis)};
  return twin;
}

} // namespace

ImportSettings read_import_settings(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the tag file");
  std::ostringstream text;
  text << in.rdbuf();
  const json document = parse_json_input(text.str(), path);
  const auto fail = [&](const std::string& where, const std::string& message) {
    throw InputError(path + ": " + where + ": " + message);
  };
  if (!document.is_object()) fail("(top)", "expected a JSON object");
  ImportSettings settings;
  settings.source = path;
  for (const auto& item : document.items()) {
    const json& value = item.value();
    if (item.key() == "fabric") {
      if (!value.is_string()) fail("fabric", "expected a fabric name (string)");
      settings.fabric = value.get<std::string>();
    } else if (item.key() == "corner_angle_deg") {
      if (!value.is_number() || !(value.get<double>() > 0 && value.get<double>() < 90))
        fail("corner_angle_deg", "expected a number of degrees in (0, 90)");
      settings.corner_angle_deg = value.get<double>();
    } else if (item.key() == "pieces") {
      if (!value.is_object()) fail("pieces", "expected an object {PIECE: {...}}");
      for (const auto& piece : value.items())
        settings.pieces[piece.key()] =
            read_piece_settings(piece.value(), path + ": pieces." + piece.key());
    } else if (item.key() == "max_dart_angle_deg") {
      if (!value.is_number() || !(value.get<double>() > 0 && value.get<double>() < 90))
        fail("max_dart_angle_deg", "expected a number of degrees in (0, 90)");
      settings.max_dart_angle_deg = value.get<double>();
    } else if (item.key() == "hangs_from") {
      if (!value.is_string() || (value != "shoulders" && value != "waist"))
        fail("hangs_from", "expected \"shoulders\" or \"waist\"");
      settings.hangs_from = value.get<std::string>();
    } else {
      fail(item.key(),
           "unknown key (expected one of: fabric, corner_angle_deg, max_dart_angle_deg, "
           "hangs_from, pieces)");
    }
  }
  return settings;
}

Curve mapped(const Curve& curve, const Affine2& map) {
  Curve out = curve;
  for (auto& p : out.points)
    p = map(p);
  return out;
}

json imported_pattern(const std::vector<ImportedPiece>& pieces, const ImportSettings& settings,
                      const std::string& name, ImportReport* report) {
  std::set<std::string> known;
  for (const ImportedPiece& piece : pieces)
    known.insert(piece.name);
  for (const auto& entry : settings.pieces)
    if (!known.count(entry.first))
      throw InputError(settings.source + ": pieces." + entry.first + ": no piece '" + entry.first +
                       "' in the imported file");
  json panels = json::array(), packs = json::array();
  std::set<std::string> ids;
  for (ImportedPiece piece : pieces) {
    const auto found = settings.pieces.find(piece.name);
    const PieceSettings given = found == settings.pieces.end() ? PieceSettings{} : found->second;
    if (!given.imported) {
      if (report)
        report->lines.push_back("piece '" + piece.name + "': left out (\"import\": false)");
      continue;
    }
    const PanelTag tag = given.tag.value_or(PanelTag{});
    const std::string fabric = given.fabric.empty() ? settings.fabric : given.fabric;
    if (piece.fold) {
      unfold(piece);
      if (report)
        report->lines.push_back("piece '" + piece.name +
                                "': cut on the fold: mirrored about it into one panel");
    }
    std::string id = safe_id(piece.name);
    while (!ids.insert(id).second)
      id += "_";
    panels.push_back(panel_json(piece, id, tag, fabric, given.darts, settings.corner_angle_deg,
                                settings.max_dart_angle_deg, report));
    const int quantity = given.quantity.value_or(piece.quantity);
    if (quantity < 1 || quantity > 2)
      throw InputError(piece.where + ": cut " + std::to_string(quantity) +
                       " (Sartor imports a piece cut once, or twice as a mirrored pair)");
    if (quantity == 2) {
      const std::string twin_id = id + "_2";
      ids.insert(twin_id);
      const ImportedPiece twin = mirrored_twin(piece, given.mirror_right);
      panels.push_back(panel_json(twin, twin_id, given.twin_tag.value_or(tag), fabric, given.darts,
                                  settings.corner_angle_deg, settings.max_dart_angle_deg, report));
      if (!given.twin_tag) {
        packs.push_back({{"id", id + "_pair"},
                         {"panels", json::array({{{"panel", id}}, {{"panel", twin_id}}})}});
      }
      if (report)
        report->lines.push_back("piece '" + piece.name + "': cut 2: twin '" + twin_id +
                                "' mirrored about the piece's " +
                                (given.mirror_right ? "right" : "left") + " edge");
    }
    if (report && found == settings.pieces.end())
      report->lines.push_back("piece '" + piece.name + "': not in the tag file: tagged " +
                              to_string(tag) + ", fabric " + fabric);
  }
  json pattern = {{"format", "sartor-pattern"}, {"version", 1},    {"name", name}, {"units", "m"},
                  {"tolerance", 1e-6},          {"panels", panels}};
  if (!settings.hangs_from.empty()) pattern["hangs_from"] = settings.hangs_from;
  if (!packs.empty()) pattern["packs"] = packs;
  return pattern;
}

} // namespace sartor::garment
