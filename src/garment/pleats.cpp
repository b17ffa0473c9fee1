#include "garment/pleats.hpp"

#include "common/csv.hpp"
#include "common/error.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <set>

namespace sartor::garment {

using Eigen::Vector2d;

const char* name_of(PleatType type) {
  switch (type) {
  case PleatType::knife:
    return "knife";
  case PleatType::box:
    return "box";
  case PleatType::inverted_box:
    return "inverted_box";
  }
  return "?";
}

std::vector<PleatCrease> pleat_creases(PleatType type) {
  switch (type) {
  case PleatType::knife:
    return {{0, true}, {1, false}};
  case PleatType::box:
    return {{0, false}, {1, true}, {3, true}, {4, false}};
  case PleatType::inverted_box:
    return {{0, true}, {1, false}, {3, false}, {4, true}};
  }
  return {};
}

double insert_width(PleatType type) {
  return type == PleatType::knife ? 2.0 : 4.0;
}

namespace {

[[noreturn]] void fail(const Pattern& pattern, const std::string& path, const std::string& what) {
  throw InputError(pattern.source + ": " + path + ": " + what);
}

// The slash lines of a pleat specification on its panel, and how the
// pieces between them move.
struct Slashing {
  int side_a = 0, side_b = 0;       // outline indices of the side lines
  std::vector<bool> moves;          // per outline line: beyond every slash (shifted)
  bool from_a_start = true;         // the stationary side is at side line a's start
  Vector2d t = Vector2d::UnitX();   // unit spread direction
  double depth = 0.0;               // m
  int width = 2;                    // of an insert, depths
  std::vector<Vector2d> on_a, on_b; // slash k's ends, k from the stationary side
  // A point moved `depths` depths along t. Every point of the pleated panel
  // is made by this one expression from an integer count, so that a corner
  // two lines share is the same double in both (no round-off gap).
  Vector2d moved(const Vector2d& p, int depths) const { return p + (double(depths) * depth) * t; }
  // Slashes a point lies beyond (its piece index); a point on a slash line
  // (within a nanometre) is not beyond it.
  int piece_of(const Vector2d& p) const {
    int beyond = 0;
    for (std::size_t k = 0; k < on_a.size(); ++k) {
      const Vector2d d = on_b[k] - on_a[k];
      Vector2d normal = Vector2d(-d.y(), d.x()).normalized();
      if (normal.dot(t) < 0) normal = -normal;
      if ((p - on_a[k]).dot(normal) > 1e-9) ++beyond;
    }
    return beyond;
  }
};

int outline_index(const Pattern& pattern, const Panel& panel, const PleatSpec& spec,
                  const std::string& id, const std::string& what) {
  for (std::size_t l = 0; l < panel.outline.size(); ++l)
    if (panel.outline[l].id == id) return int(l);
  fail(pattern, spec.json_path,
       what + " '" + id + "' is not an outline line of panel '" + panel.id + "'");
}

Slashing slash(const Pattern& pattern, const Panel& panel, const PleatSpec& spec) {
  Slashing s;
  s.side_a = outline_index(pattern, panel, spec, spec.side_lines[0], "side line");
  s.side_b = outline_index(pattern, panel, spec, spec.side_lines[1], "side line");
  const int fixed = outline_index(pattern, panel, spec, spec.stationary, "stationary line");
  if (s.side_a == s.side_b) fail(pattern, spec.json_path, "the two side lines are the same line");
  if (fixed == s.side_a || fixed == s.side_b)
    fail(pattern, spec.json_path, "the stationary line must not be a side line");
  for (int l : {s.side_a, s.side_b})
    if (panel.outline[std::size_t(l)].curve.kind != Curve::Kind::straight)
      fail(pattern, spec.json_path,
           "side line '" + panel.outline[std::size_t(l)].id +
               "' must be straight (split a curved side line into straight lines)");
  const int n = int(panel.outline.size());
  // Lines after side line a up to side line b run from a's end to b's start.
  std::vector<bool> after_a(std::size_t(n), false);
  for (int l = (s.side_a + 1) % n; l != s.side_b; l = (l + 1) % n)
    after_a[std::size_t(l)] = true;
  s.from_a_start = !after_a[std::size_t(fixed)];
  s.moves.assign(std::size_t(n), false);
  for (int l = 0; l < n; ++l)
    if (l != s.side_a && l != s.side_b)
      s.moves[std::size_t(l)] = after_a[std::size_t(l)] == s.from_a_start;
  const Curve& a = panel.outline[std::size_t(s.side_a)].curve;
  const Curve& b = panel.outline[std::size_t(s.side_b)].curve;
  const Vector2d a_near = s.from_a_start ? a.start() : a.end();
  const Vector2d a_far = s.from_a_start ? a.end() : a.start();
  const Vector2d b_near = s.from_a_start ? b.end() : b.start();
  const Vector2d b_far = s.from_a_start ? b.start() : b.end();
  s.t = (a_far - a_near).normalized();
  s.depth = spec.depth;
  s.width = int(std::lround(insert_width(spec.type)));
  const std::vector<Vector2d> polygon = panel.outline_polygon(pattern.flattening_tolerance());
  for (int k = 1; k <= spec.slash_lines; ++k) {
    const double f = double(k) / double(spec.slash_lines + 1);
    s.on_a.push_back(a_near + f * (a_far - a_near));
    s.on_b.push_back(b_near + f * (b_far - b_near));
    for (int i = 0; i < 8; ++i) {
      const Vector2d p = s.on_a.back() + (i + 0.5) / 8 * (s.on_b.back() - s.on_a.back());
      if (!inside_polygon(polygon, p))
        fail(pattern, spec.json_path,
             "slash line " + std::to_string(k) + " from (" + format_number(s.on_a.back().x()) +
                 ", " + format_number(s.on_a.back().y()) + ") to (" +
                 format_number(s.on_b.back().x()) + ", " + format_number(s.on_b.back().y()) +
                 ") leaves the panel: the side lines must face each other across it");
    }
  }
  return s;
}

OutlineLine straight_line(const std::string& id, const Vector2d& from, const Vector2d& to,
                          const std::string& json_path) {
  OutlineLine line;
  line.id = id;
  line.curve.kind = Curve::Kind::straight;
  line.curve.points = {from, to};
  line.json_path = json_path;
  return line;
}

// Side line `index` cut at the slashes: its pieces, moved with their
// pieces, and between them each pleat's insert, split at every depth. The
// stitches of each pleat's insert segments go to `stitches` when `sew`.
std::vector<OutlineLine> split_side_line(const Panel& panel, const Slashing& s,
                                         const PleatSpec& spec, int index, bool sew,
                                         std::vector<Stitch>* stitches) {
  const OutlineLine& side = panel.outline[std::size_t(index)];
  const std::vector<Vector2d>& crossings = index == s.side_a ? s.on_a : s.on_b;
  // Does the line run away from the stationary side?
  const bool away = (index == s.side_a) == s.from_a_start;
  const int count = int(crossings.size());
  const std::string at = spec.json_path + " (side line '" + side.id + "')";
  const int segments = int(std::lround(insert_width(spec.type)));
  std::vector<OutlineLine> lines;
  Vector2d from = s.moved(side.curve.start(), (away ? 0 : count) * s.width);
  for (int step = 0; step < count; ++step) {
    const int k = away ? step : count - 1 - step; // slash index, 0-based
    const int before = away ? k : k + 1, after = away ? k + 1 : k;
    const Vector2d q = crossings[std::size_t(k)];
    lines.push_back(straight_line(side.id + "_" + std::to_string(before), from,
                                  s.moved(q, before * s.width), at));
    std::vector<std::string> ids;
    for (int i = 0; i < segments; ++i) {
      // Segment i + 1 of the insert counted from its stationary edge.
      const int m = away ? i : segments - 1 - i;
      const Vector2d near = s.moved(q, k * s.width + m);
      const Vector2d far = s.moved(q, k * s.width + m + 1);
      const std::string id =
          side.id + "_pleat" + std::to_string(k + 1) + "_" + std::to_string(m + 1);
      lines.push_back(straight_line(id, away ? near : far, away ? far : near, at));
      ids.push_back(id);
    }
    if (!away) std::reverse(ids.begin(), ids.end());
    if (sew) {
      // Segments 1-2 (and 3-4) fold onto each other: one's start meets the
      // other's end.
      for (std::size_t i = 0; i + 1 < ids.size(); i += 2)
        stitches->push_back({ids[i], ids[i + 1], true, spec.id});
    }
    from = s.moved(q, after * s.width);
  }
  lines.push_back(straight_line(side.id + "_" + std::to_string(away ? count : 0), from,
                                s.moved(side.curve.end(), (away ? count : 0) * s.width), at));
  return lines;
}

std::vector<InteriorLine> pleat_crease_lines(const Slashing& s, const PleatSpec& spec) {
  std::vector<InteriorLine> lines;
  const std::vector<PleatCrease> creases = pleat_creases(spec.type);
  for (std::size_t k = 0; k < s.on_a.size(); ++k) {
    for (std::size_t c = 0; c < creases.size(); ++c) {
      const int depths = int(k) * s.width + creases[c].offset;
      InteriorLine line;
      line.id = spec.id + "_" + std::to_string(k + 1) + "_" + std::to_string(c + 1) +
                (creases[c].out_fold ? "_out" : "_in");
      line.kind = InteriorLine::Kind::fold;
      line.curve.kind = Curve::Kind::straight;
      line.curve.points = {s.moved(s.on_a[k], depths), s.moved(s.on_b[k], depths)};
      line.json_path = spec.json_path;
      const Vector2d d = line.curve.end() - line.curve.start();
      Crease crease;
      // The warping region is the side away from the stationary one.
      crease.side = Vector2d(-d.y(), d.x()).dot(s.t) > 0 ? Crease::Side::left : Crease::Side::right;
      crease.angle = creases[c].out_fold ? spec.out_fold : spec.in_fold;
      crease.outside = !creases[c].out_fold;
      crease.pressed = spec.pressed;
      crease.json_path = spec.json_path;
      line.crease = crease;
      lines.push_back(line);
    }
  }
  return lines;
}

} // namespace

void apply_pleat(Pattern& pattern, const PleatSpec& spec) {
  auto found = std::find_if(pattern.panels.begin(), pattern.panels.end(),
                            [&](const Panel& p) { return p.id == spec.panel; });
  if (found == pattern.panels.end())
    fail(pattern, spec.json_path, "unknown panel '" + spec.panel + "'");
  Panel& panel = *found;
  const Slashing s = slash(pattern, panel, spec);
  std::vector<OutlineLine> outline;
  for (int l = 0; l < int(panel.outline.size()); ++l) {
    if (l == s.side_a || l == s.side_b) {
      const bool sew =
          spec.sew == PleatSpec::Sew::both || (spec.sew == PleatSpec::Sew::first && l == s.side_a);
      for (auto& line : split_side_line(panel, s, spec, l, sew, &pattern.stitches))
        outline.push_back(std::move(line));
      continue;
    }
    OutlineLine line = panel.outline[std::size_t(l)];
    if (s.moves[std::size_t(l)])
      for (auto& p : line.curve.points)
        p = s.moved(p, spec.slash_lines * s.width);
    outline.push_back(std::move(line));
  }
  for (auto& line : panel.interior) {
    const auto points = line.curve.flatten(pattern.flattening_tolerance());
    const int piece = s.piece_of(points.front());
    for (const auto& p : points)
      if (s.piece_of(p) != piece)
        fail(pattern, spec.json_path,
             "interior line '" + line.id +
                 "' crosses a slash line: pleat a panel whose "
                 "interior lines lie between the slash lines");
    for (auto& p : line.curve.points)
      p = s.moved(p, piece * s.width);
  }
  panel.outline = std::move(outline);
  for (auto& line : pleat_crease_lines(s, spec)) {
    // Each crease ends exactly at its insert's corners (computed in another
    // order, the two could differ by round-off and give the mesher two
    // vertices where there is one).
    for (Vector2d* end : {&line.curve.points.front(), &line.curve.points.back()})
      for (const auto& outline_line : panel.outline)
        if ((outline_line.curve.start() - *end).norm() <= pattern.tolerance)
          *end = outline_line.curve.start();
    panel.interior.push_back(std::move(line));
  }
  std::set<std::string> ids;
  for (const auto& p : pattern.panels) {
    for (const auto& line : p.outline)
      if (!ids.insert(line.id).second)
        fail(pattern, spec.json_path, "the pleats make line id '" + line.id + "' twice");
    for (const auto& line : p.interior)
      if (!ids.insert(line.id).second)
        fail(pattern, spec.json_path, "the pleats make line id '" + line.id + "' twice");
  }
}

namespace {

const nlohmann::json& field(const Pattern& pattern, const nlohmann::json& entry,
                            const std::string& path, const std::string& key) {
  if (!entry.contains(key)) fail(pattern, path, "missing field '" + key + "'");
  return entry.at(key);
}

std::string text_field(const Pattern& pattern, const nlohmann::json& entry, const std::string& path,
                       const std::string& key) {
  const nlohmann::json& value = field(pattern, entry, path, key);
  if (!value.is_string() || value.get<std::string>().empty())
    fail(pattern, path + "." + key, "expected a non-empty string");
  return value.get<std::string>();
}

double number_field(const Pattern& pattern, const nlohmann::json& entry, const std::string& path,
                    const std::string& key, double low, double high) {
  const nlohmann::json& value = field(pattern, entry, path, key);
  if (!value.is_number()) fail(pattern, path + "." + key, "expected a number");
  const double x = value.get<double>();
  if (!(x > low && x < high))
    fail(pattern, path + "." + key,
         "must lie in (" + format_number(low) + ", " + format_number(high) + "), got " +
             format_number(x));
  return x;
}

PleatSpec read_pleat(const Pattern& pattern, const nlohmann::json& entry, const std::string& path,
                     double scale) {
  if (!entry.is_object()) fail(pattern, path, "expected an object");
  static const std::set<std::string> keys{
      "id",    "panel",       "side_lines",   "stationary", "type",   "slash_lines",
      "depth", "in_fold_deg", "out_fold_deg", "sew",        "pressed"};
  for (const auto& item : entry.items())
    if (!keys.count(item.key()))
      fail(pattern, path,
           "unknown key '" + item.key() +
               "' (expected one of: id, panel, side_lines, stationary, type, slash_lines, depth, "
               "in_fold_deg, out_fold_deg, sew, pressed)");
  PleatSpec spec;
  spec.json_path = "pleats" + path.substr(path.find('['));
  spec.id = text_field(pattern, entry, path, "id");
  spec.panel = text_field(pattern, entry, path, "panel");
  const nlohmann::json& sides = field(pattern, entry, path, "side_lines");
  if (!sides.is_array() || sides.size() != 2 || !sides[0].is_string() || !sides[1].is_string())
    fail(pattern, path + ".side_lines", "expected two line ids");
  spec.side_lines = {sides[0].get<std::string>(), sides[1].get<std::string>()};
  spec.stationary = text_field(pattern, entry, path, "stationary");
  const std::string type = text_field(pattern, entry, path, "type");
  if (type == "knife")
    spec.type = PleatType::knife;
  else if (type == "box")
    spec.type = PleatType::box;
  else if (type == "inverted_box")
    spec.type = PleatType::inverted_box;
  else
    fail(pattern, path + ".type",
         "unknown pleat type '" + type + "' (expected knife, box or inverted_box)");
  const nlohmann::json& slashes = field(pattern, entry, path, "slash_lines");
  if (!slashes.is_number_integer() || slashes.get<int>() < 1 || slashes.get<int>() > 100)
    fail(pattern, path + ".slash_lines", "expected an integer from 1 to 100");
  spec.slash_lines = slashes.get<int>();
  spec.depth = scale * number_field(pattern, entry, path, "depth", 0, 1e3 / scale);
  spec.in_fold = number_field(pattern, entry, path, "in_fold_deg", 0, 180) * M_PI / 180;
  spec.out_fold = number_field(pattern, entry, path, "out_fold_deg", 0, 180) * M_PI / 180;
  if (entry.contains("pressed"))
    spec.pressed = number_field(pattern, entry, path, "pressed", 1.0 - 1e-12, 1e4);
  if (entry.contains("sew")) {
    const std::string sew = text_field(pattern, entry, path, "sew");
    if (sew == "first")
      spec.sew = PleatSpec::Sew::first;
    else if (sew == "both")
      spec.sew = PleatSpec::Sew::both;
    else if (sew == "none")
      spec.sew = PleatSpec::Sew::none;
    else
      fail(pattern, path + ".sew", "unknown value '" + sew + "' (expected first, both or none)");
  }
  return spec;
}

} // namespace

void apply_pleats(Pattern& pattern, const nlohmann::json& pleats, double scale) {
  if (!pleats.is_array()) fail(pattern, "pleats", "expected an array");
  std::set<std::string> ids;
  for (std::size_t i = 0; i < pleats.size(); ++i) {
    const std::string path = "pleats[" + std::to_string(i) + "]";
    const PleatSpec spec = read_pleat(pattern, pleats[i], path, scale);
    if (!ids.insert(spec.id).second)
      fail(pattern, path + ".id", "duplicate pleat id '" + spec.id + "'");
    apply_pleat(pattern, spec);
  }
}

} // namespace sartor::garment
