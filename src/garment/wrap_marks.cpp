// The inputs of wrapping: marks in the pattern and the marks file, and the
// panels sewn into one mesh (garment/wrap.hpp; formats in docs/wrapping.md).

#include "garment/wrap.hpp"

#include "common/error.hpp"
#include "common/json_input.hpp"
#include "mesh/merge.hpp"
#include "mesh/panel_mesher.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

namespace sartor::garment {

namespace {

std::string read_text(const std::string& path, const std::string& what) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the " + what);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

int panel_index(const Pattern& pattern, const std::string& id, const std::string& where) {
  for (std::size_t p = 0; p < pattern.panels.size(); ++p)
    if (pattern.panels[p].id == id) return int(p);
  throw InputError(where + ": no panel '" + id + "' in the pattern");
}

// `count`-vectors of finite numbers, at least two of them.
template <int count>
std::vector<Eigen::Matrix<double, count, 1>> read_points(const nlohmann::json& value,
                                                         const std::string& where) {
  if (!value.is_array() || value.size() < 2)
    throw InputError(where + ": a polyline of at least two points is needed");
  std::vector<Eigen::Matrix<double, count, 1>> points;
  for (std::size_t i = 0; i < value.size(); ++i) {
    const nlohmann::json& point = value[i];
    if (!point.is_array() || point.size() != std::size_t(count))
      throw InputError(where + "[" + std::to_string(i) + "]: a point of " + std::to_string(count) +
                       " numbers is needed");
    Eigen::Matrix<double, count, 1> p;
    for (int k = 0; k < count; ++k) {
      if (!point[std::size_t(k)].is_number() || !std::isfinite(point[std::size_t(k)].get<double>()))
        throw InputError(where + "[" + std::to_string(i) + "]: not a finite number");
      p[k] = point[std::size_t(k)].get<double>();
    }
    if (!points.empty() && (p - points.back()).norm() == 0.0)
      throw InputError(where + "[" + std::to_string(i) + "]: repeats the point before it");
    points.push_back(p);
  }
  return points;
}

ClothMark read_cloth_mark(const nlohmann::json& entry, const Pattern& pattern,
                          const std::string& where) {
  if (!entry.is_object() || !entry.contains("panel") || !entry["panel"].is_string() ||
      !entry.contains("points"))
    throw InputError(where + ": a cloth mark needs \"panel\" (an id) and \"points\"");
  ClothMark mark;
  mark.panel = panel_index(pattern, entry["panel"].get<std::string>(), where + ".panel");
  mark.points = read_points<2>(entry["points"], where + ".points");
  if (entry.contains("id") && entry["id"].is_string()) mark.id = entry["id"].get<std::string>();
  mark.where = where;
  return mark;
}

void check_keys(const nlohmann::json& object, const std::vector<std::string>& known,
                const std::string& where) {
  for (const auto& item : object.items())
    if (std::find(known.begin(), known.end(), item.key()) == known.end())
      throw InputError(where + ": unknown key '" + item.key() + "'");
}

} // namespace

Pattern read_pattern_with_marks(const std::string& path, std::vector<ClothMark>& marks) {
  nlohmann::json document = parse_json_input(read_text(path, "pattern file"), path);
  nlohmann::json cloth_marks;
  if (document.is_object() && document.contains("marks")) {
    cloth_marks = document["marks"];
    document.erase("marks");
  }
  Pattern pattern = parse_pattern(document.dump(), path);
  if (cloth_marks.is_null()) return pattern;
  if (!cloth_marks.is_array()) throw InputError(path + ": marks: an array of marks is needed");
  for (std::size_t i = 0; i < cloth_marks.size(); ++i) {
    const std::string where = path + ": marks[" + std::to_string(i) + "]";
    check_keys(cloth_marks[i], {"id", "panel", "points"}, where);
    ClothMark mark = read_cloth_mark(cloth_marks[i], pattern, where);
    if (mark.id.empty()) throw InputError(where + ": a mark of the pattern needs an \"id\"");
    marks.push_back(mark);
  }
  return pattern;
}

WrapMarks read_marks(const std::string& path, const Pattern& pattern,
                     const std::vector<ClothMark>& pattern_marks) {
  const nlohmann::json document = parse_json_input(read_text(path, "marks file"), path);
  if (!document.is_object()) throw InputError(path + ": a JSON object is needed");
  check_keys(document, {"format", "version", "body", "seams", "marks", "pins"}, path);
  if (!document.contains("format") || document["format"] != "sartor-marks")
    throw InputError(path + ": format: \"sartor-marks\" is needed");
  if (!document.contains("version") || document["version"] != 1)
    throw InputError(path + ": version: 1 is needed");
  WrapMarks marks;
  if (!document.contains("body") || !document["body"].is_string())
    throw InputError(path + ": body: a body specification (a string) is needed");
  marks.body = document["body"].get<std::string>();
  const nlohmann::json seams = document.value("seams", nlohmann::json::array());
  for (std::size_t i = 0; i < seams.size(); ++i) {
    const std::string where = path + ": seams[" + std::to_string(i) + "]";
    check_keys(seams[i], {"a", "b", "reverse"}, where);
    if (!seams[i].contains("a") || !seams[i].contains("b") || !seams[i]["a"].is_string() ||
        !seams[i]["b"].is_string())
      throw InputError(where + ": \"a\" and \"b\" (line ids) are needed");
    marks.seams.push_back({seams[i]["a"].get<std::string>(), seams[i]["b"].get<std::string>(),
                           seams[i].value("reverse", false), where});
  }
  if (!document.contains("marks") || !document["marks"].is_array() || document["marks"].empty())
    throw InputError(path + ": marks: an array of at least one mark pair is needed");
  const nlohmann::json& pairs = document["marks"];
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const std::string where = path + ": marks[" + std::to_string(i) + "]";
    check_keys(pairs[i], {"id", "cloth", "body"}, where);
    if (!pairs[i].contains("cloth") || !pairs[i].contains("body"))
      throw InputError(where + ": \"cloth\" and \"body\" are needed");
    MarkPair pair;
    pair.id = pairs[i].value("id", "mark " + std::to_string(i));
    const nlohmann::json& cloth = pairs[i]["cloth"];
    if (cloth.is_string()) {
      const auto found =
          std::find_if(pattern_marks.begin(), pattern_marks.end(),
                       [&](const ClothMark& mark) { return mark.id == cloth.get<std::string>(); });
      if (found == pattern_marks.end())
        throw InputError(where + ".cloth: no mark '" + cloth.get<std::string>() +
                         "' in the pattern's marks");
      pair.cloth = *found;
    } else {
      check_keys(cloth, {"panel", "points"}, where + ".cloth");
      pair.cloth = read_cloth_mark(cloth, pattern, where + ".cloth");
    }
    pair.body = read_points<3>(pairs[i]["body"], where + ".body");
    marks.pairs.push_back(pair);
  }
  const nlohmann::json pins = document.value("pins", nlohmann::json::array());
  for (std::size_t i = 0; i < pins.size(); ++i) {
    PinRef pin;
    pin.where = path + ": pins[" + std::to_string(i) + "]";
    if (pins[i].is_number_integer()) {
      pin.vertex = pins[i].get<int>();
      if (pin.vertex < 0) throw InputError(pin.where + ": a vertex index is >= 0");
    } else {
      const nlohmann::json& point = pins[i];
      if (!point.is_array() || point.size() != 3 ||
          !std::all_of(point.begin(), point.end(), [](const nlohmann::json& x) {
            return x.is_number() && std::isfinite(x.get<double>());
          }))
        throw InputError(pin.where + ": a vertex index or a point [x, y, z] is needed");
      pin.point = {point[0].get<double>(), point[1].get<double>(), point[2].get<double>()};
    }
    marks.pins.push_back(pin);
  }
  return marks;
}

int pinned_vertex(const PinRef& pin, const std::vector<Eigen::Vector3d>& positions) {
  if (pin.vertex >= 0) {
    if (std::size_t(pin.vertex) >= positions.size())
      throw InputError(pin.where + ": vertex " + std::to_string(pin.vertex) +
                       " is not in the garment (0.." + std::to_string(positions.size() - 1) + ")");
    return pin.vertex;
  }
  std::size_t nearest = 0;
  for (std::size_t v = 1; v < positions.size(); ++v)
    if ((positions[v] - pin.point).norm() < (positions[nearest] - pin.point).norm()) nearest = v;
  return int(nearest);
}

TriangleMesh sew_panels(const Pattern& pattern, const std::vector<SewnLines>& seams,
                        double edge_length, double min_angle_deg) {
  std::vector<SewnLines> all = seams;
  for (const Stitch& stitch : pattern.stitches)
    all.push_back({stitch.line_a, stitch.line_b, stitch.reverse, "stitch " + stitch.origin});
  std::map<std::string, double> line_length;
  for (const Panel& panel : pattern.panels)
    for (const OutlineLine& line : panel.outline)
      line_length[line.id] = line.curve.length();
  PanelMeshOptions options;
  options.edge_length = edge_length;
  options.min_angle_deg = min_angle_deg;
  for (const SewnLines& seam : all) {
    for (const std::string* id : {&seam.a, &seam.b})
      if (!line_length.count(*id))
        throw InputError(seam.where + ": no outline line '" + *id + "' in the pattern");
    const int pieces = std::max(pieces_for(line_length[seam.a], edge_length),
                                pieces_for(line_length[seam.b], edge_length));
    for (const std::string* id : {&seam.a, &seam.b})
      options.pieces[*id] = std::max(options.pieces[*id], pieces);
  }
  TriangleMesh mesh;
  std::map<std::string, std::vector<int>> line_vertices;
  for (std::size_t p = 0; p < pattern.panels.size(); ++p) {
    const PanelMesh panel = mesh_panel(pattern.panels[p], options);
    const int first = int(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), panel.mesh.positions.begin(),
                          panel.mesh.positions.end());
    for (std::size_t t = 0; t < panel.mesh.triangle_count(); ++t) {
      const auto& c = panel.mesh.triangles[t];
      mesh.triangles.push_back({c[0] + first, c[1] + first, c[2] + first});
      mesh.material_uv.push_back(panel.mesh.material_uv[t]);
      mesh.material_ids.push_back(int(p));
    }
    for (const MeshedLine& line : panel.lines) {
      std::vector<int>& vertices = line_vertices[line.id];
      for (int v : line.vertices)
        vertices.push_back(v + first);
    }
  }
  std::vector<std::pair<int, int>> pairs;
  for (const SewnLines& seam : all) {
    const std::vector<int>&a = line_vertices[seam.a], &b = line_vertices[seam.b];
    if (a.size() != b.size())
      throw InputError(seam.where + ": lines '" + seam.a + "' and '" + seam.b +
                       "' were meshed with " + std::to_string(a.size()) + " and " +
                       std::to_string(b.size()) + " vertices; try another --edge-length");
    for (std::size_t i = 0; i < a.size(); ++i)
      pairs.emplace_back(a[i], seam.reverse ? b[b.size() - 1 - i] : b[i]);
  }
  return merge_vertices(mesh, pairs).mesh;
}

} // namespace sartor::garment
