#include "garment/import_dxf.hpp"

#include "common/csv.hpp"
#include "common/error.hpp"

#include <dl_creationadapter.h>
#include <dl_dxf.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>

namespace sartor::garment {

using Eigen::Vector2d;

namespace {

// Points this close (in drawing units scaled to m) are one point.
constexpr double snap = 5e-4; // m

std::string lower(std::string text) {
  for (char& c : text)
    c = char(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t\r\n") - first + 1);
}

struct Polyline {
  std::string layer;
  std::vector<Vector2d> points;
  bool closed = false;
  bool arcs = false;
};

struct Block {
  std::string name;
  std::vector<Polyline> polylines;                      // POLYLINE, LWPOLYLINE and LINE (2 points)
  std::vector<std::pair<std::string, Vector2d>> points; // layer, POINT
  std::vector<std::string> texts;
};

// dxflib calls these as it reads; entities go to the open block.
class AamaCollector : public DL_CreationAdapter {
public:
  void addBlock(const DL_BlockData& data) override {
    blocks.push_back({data.name, {}, {}, {}});
    in_block = true;
  }
  void endBlock() override { in_block = false; }
  void addPolyline(const DL_PolylineData& data) override {
    if (!in_block) return;
    Polyline line;
    line.layer = attributes.getLayer();
    line.closed = (data.flags & 1) != 0;
    blocks.back().polylines.push_back(line);
    polyline_open = true;
  }
  void addVertex(const DL_VertexData& data) override {
    if (!in_block || !polyline_open) return;
    Polyline& line = blocks.back().polylines.back();
    line.points.emplace_back(data.x, data.y);
    line.arcs = line.arcs || std::abs(data.bulge) > 1e-12;
  }
  void endSequence() override { polyline_open = false; }
  void addLine(const DL_LineData& data) override {
    polyline_open = false;
    if (!in_block) return;
    blocks.back().polylines.push_back({attributes.getLayer(),
                                       {Vector2d(data.x1, data.y1), Vector2d(data.x2, data.y2)},
                                       false,
                                       false});
  }
  void addPoint(const DL_PointData& data) override {
    polyline_open = false;
    if (in_block)
      blocks.back().points.emplace_back(attributes.getLayer(), Vector2d(data.x, data.y));
  }
  void addText(const DL_TextData& data) override { add_text(data.text); }
  void addMText(const DL_MTextData& data) override { add_text(data.text); }
  void setVariableInt(const std::string& key, int value, int) override {
    if (key == "$INSUNITS") insunits = value;
  }

  std::vector<Block> blocks;
  std::vector<std::string> loose_texts; // outside blocks: units, style
  int insunits = 0;

private:
  void add_text(const std::string& text) {
    polyline_open = false;
    (in_block ? blocks.back().texts : loose_texts).push_back(text);
  }
  bool in_block = false;
  bool polyline_open = false;
};

// "Key: value" texts of AAMA (case-insensitive key).
std::optional<std::string> text_value(const std::vector<std::string>& texts,
                                      const std::string& key) {
  for (const std::string& text : texts) {
    const auto colon = text.find(':');
    if (colon != std::string::npos && lower(trim(text.substr(0, colon))) == key)
      return trim(text.substr(colon + 1));
  }
  return std::nullopt;
}

double file_units(const AamaCollector& dxf, const std::string& path) {
  // $INSUNITS codes of the DXF reference: 1 inch, 4 mm, 5 cm, 6 m.
  static const std::map<int, double> codes = {{1, 0.0254}, {4, 1e-3}, {5, 1e-2}, {6, 1.0}};
  if (dxf.insunits != 0) {
    const auto found = codes.find(dxf.insunits);
    if (found == codes.end())
      throw InputError(
          path + ": $INSUNITS " + std::to_string(dxf.insunits) +
          " is not a unit of length Sartor reads (1 in, 4 mm, 5 cm, 6 m); give --units");
    return found->second;
  }
  std::vector<std::string> texts = dxf.loose_texts;
  for (const Block& block : dxf.blocks)
    texts.insert(texts.end(), block.texts.begin(), block.texts.end());
  if (const auto units = text_value(texts, "units")) {
    if (lower(*units) == "metric") return 1e-3;
    if (lower(*units) == "english") return 0.0254;
    throw InputError(path + ": unknown units \"" + *units + "\" (expected METRIC or ENGLISH)");
  }
  throw InputError(path + ": the file does not give its units ($INSUNITS or a text \"Units: "
                          "METRIC\"); give --units");
}

double polygon_area(const std::vector<Vector2d>& p) {
  double twice = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    twice += p[i].x() * p[(i + 1) % p.size()].y() - p[i].y() * p[(i + 1) % p.size()].x();
  return 0.5 * std::abs(twice);
}

// Lines of one layer joined end to end into closed loops where they meet.
std::vector<std::vector<Vector2d>> closed_loops(const std::vector<Polyline>& lines, double unit) {
  std::vector<std::vector<Vector2d>> loops, open;
  for (const Polyline& line : lines) {
    if (line.points.size() < 2) continue;
    const bool ends_meet = (line.points.front() - line.points.back()).norm() * unit <= snap;
    if (line.closed || (ends_meet && line.points.size() > 3)) {
      std::vector<Vector2d> loop = line.points;
      if (ends_meet) loop.pop_back();
      loops.push_back(loop);
    } else {
      open.push_back(line.points);
    }
  }
  // Chain the open pieces (a boundary drawn as LINEs).
  while (!open.empty()) {
    std::vector<Vector2d> chain = open.back();
    open.pop_back();
    bool grown = true;
    while (grown) {
      grown = false;
      for (std::size_t k = 0; k < open.size(); ++k) {
        auto piece = open[k];
        if ((piece.back() - chain.back()).norm() * unit <= snap)
          std::reverse(piece.begin(), piece.end());
        if ((piece.front() - chain.back()).norm() * unit > snap) continue;
        chain.insert(chain.end(), piece.begin() + 1, piece.end());
        open.erase(open.begin() + std::ptrdiff_t(k));
        grown = true;
        break;
      }
    }
    if (chain.size() > 3 && (chain.front() - chain.back()).norm() * unit <= snap) {
      chain.pop_back();
      loops.push_back(chain);
    }
  }
  return loops;
}

ImportedPiece piece_of(const Block& block, double unit, const std::string& path) {
  ImportedPiece piece;
  piece.name = text_value(block.texts, "piece name").value_or(block.name);
  piece.where = path + ": block '" + block.name + "'";
  if (const auto quantity = text_value(block.texts, "quantity")) {
    try {
      piece.quantity = std::stoi(*quantity);
    } catch (const std::exception&) {
      throw InputError(piece.where + ": cannot read \"Quantity: " + *quantity + "\"");
    }
  }
  std::map<std::string, std::vector<Polyline>> layers;
  for (const Polyline& line : block.polylines) {
    if (line.arcs && (line.layer == "1" || line.layer == "14"))
      throw InputError(piece.where + ": the boundary has arcs (bulges), which Sartor does not "
                                     "read; export the pattern with polylines");
    layers[line.layer].push_back(line);
  }
  // The sew line (layer 14) when the block has one; else the boundary (1).
  auto loops = closed_loops(layers["14"], unit);
  if (loops.empty()) loops = closed_loops(layers["1"], unit);
  if (loops.empty())
    throw InputError(piece.where + ": no closed boundary on layer 1 (or sew line on layer 14)");
  const auto outline = *std::max_element(loops.begin(), loops.end(), [](auto& a, auto& b) {
    return polygon_area(a) < polygon_area(b);
  });
  for (std::size_t k = 0; k < outline.size(); ++k) {
    Curve segment;
    segment.points = {unit * outline[k], unit * outline[(k + 1) % outline.size()]};
    if (segment.length() > 0) piece.boundary.push_back(segment);
  }
  const auto segment_of = [&](const std::string& layer,
                              const char* what) -> std::optional<Segment> {
    const auto& lines = layers[layer];
    if (lines.empty()) return std::nullopt;
    if (lines.size() > 1 || lines[0].points.size() < 2)
      throw InputError(piece.where + ": expected one " + what + " on layer " + layer + ", got " +
                       std::to_string(lines.size()) + " lines");
    return Segment{unit * lines[0].points.front(), unit * lines[0].points.back()};
  };
  piece.grain = segment_of("7", "grain line");
  piece.fold = segment_of("6", "mirror line");
  for (const Polyline& line : layers["8"]) {
    std::vector<Vector2d> points;
    for (const Vector2d& p : line.points)
      points.push_back(unit * p);
    piece.internal.push_back(points);
  }
  // A notch: a point, or a short line whose end nearer the boundary marks it.
  std::vector<Vector2d> corners;
  for (const Curve& c : piece.boundary)
    corners.push_back(c.start());
  const auto boundary_distance = [&](const Vector2d& p) {
    double best = std::numeric_limits<double>::infinity();
    for (const Curve& c : piece.boundary) {
      const Vector2d d = c.end() - c.start();
      const double t = std::clamp((p - c.start()).dot(d) / d.squaredNorm(), 0.0, 1.0);
      best = std::min(best, (c.start() + t * d - p).norm());
    }
    return best;
  };
  for (const auto& [layer, p] : block.points)
    if (layer == "4") piece.notches.push_back(unit * p);
  for (const Polyline& line : layers["4"]) {
    const Vector2d a = unit * line.points.front(), b = unit * line.points.back();
    piece.notches.push_back(boundary_distance(a) <= boundary_distance(b) ? a : b);
  }
  return piece;
}

} // namespace

std::vector<ImportedPiece> read_dxf_pieces(const std::string& path, double metres_per_unit) {
  if (!std::filesystem::is_regular_file(path))
    throw InputError(path + ": cannot open the DXF file");
  AamaCollector collector;
  DL_Dxf dxf;
  if (!dxf.in(path, &collector)) throw InputError(path + ": dxflib cannot read the file as DXF");
  const double unit = metres_per_unit > 0 ? metres_per_unit : file_units(collector, path);
  std::vector<ImportedPiece> pieces;
  for (const Block& block : collector.blocks) {
    // *Model_Space and *Paper_Space (and anonymous blocks) are not pieces.
    if (block.name.empty() || block.name[0] == '*') continue;
    if (block.polylines.empty()) continue;
    pieces.push_back(piece_of(block, unit, path));
  }
  if (pieces.empty()) throw InputError(path + ": no piece: no block with a boundary on layer 1");
  return pieces;
}

} // namespace sartor::garment
