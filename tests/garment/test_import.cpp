// Pattern import (garment/import_dxf, import_svg, pattern_import): a DXF-AAMA
// file written here from the format's definition (ASTM D6673 layers: 1
// boundary, 4 notches, 7 grain line; "Piece Name:" texts; a "Units:" text),
// SVG path data and transforms against the SVG 1.1 definitions, and the
// FreeSewing-style pencil skirt of cases/import: cut on the fold, cut 2,
// darts sewn by construction.

#include "common/error.hpp"
#include "contact/mannequin.hpp"
#include "contact/mesh_shape.hpp"
#include "garment/import_dxf.hpp"
#include "garment/import_svg.hpp"
#include "garment/tagcon.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace sartor::garment {
namespace {

using Eigen::Vector2d;

const std::string cases_import = SARTOR_PATTERN_SAMPLES_DIR "/../import";

// DXF group code / value pairs, one per line, as the DXF reference writes them.
class DxfText {
public:
  DxfText& operator()(int code, const std::string& value) {
    text_ << code << "\n" << value << "\n";
    return *this;
  }
  DxfText& point(int code, const Vector2d& p) {
    return (*this)(code, std::to_string(p.x()))(code + 10, std::to_string(p.y()))(code + 20, "0");
  }
  DxfText& polyline(const std::string& layer, const std::vector<Vector2d>& points) {
    (*this)(0, "POLYLINE")(8, layer)(66, "1").point(10, {0, 0})(70, "1");
    for (const Vector2d& p : points)
      (*this)(0, "VERTEX")(8, layer).point(10, p);
    return (*this)(0, "SEQEND")(8, layer);
  }
  DxfText& line(const std::string& layer, const Vector2d& a, const Vector2d& b) {
    return (*this)(0, "LINE")(8, layer).point(10, a).point(11, b);
  }
  DxfText& text(const std::string& layer, const std::string& value) {
    return (*this)(0, "TEXT")(8, layer).point(10, {0, 0})(40, "5")(1, value);
  }
  std::string str() const { return text_.str(); }

private:
  std::ostringstream text_;
};

std::string write_file(const std::string& name, const std::string& content) {
  const auto path = std::filesystem::temp_directory_path() / ("sartor_import_" + name);
  std::ofstream(path) << content;
  return path.string();
}

// Two pieces in mm: "front", a 400 x 600 rectangle as a closed polyline with
// a notch (a POINT) halfway up its right side and a vertical grain line;
// "back", a trapezoid drawn as four LINEs, a notch as a short LINE from the
// left side inwards, and a grain line at 45 degrees (cut on the bias).
std::string aama_file(bool with_units) {
  DxfText dxf;
  dxf(0, "SECTION")(2, "BLOCKS");
  dxf(0, "BLOCK")(8, "0")(2, "P1")(70, "0").point(10, {0, 0})(3, "P1");
  dxf.polyline("1", {{0, 0}, {400, 0}, {400, 600}, {0, 600}});
  dxf(0, "POINT")(8, "4").point(10, {400, 300});
  dxf.line("7", {200, 100}, {200, 500});
  dxf.text("1", "Piece Name: front").text("1", "Quantity: 1");
  dxf(0, "ENDBLK")(8, "0");
  dxf(0, "BLOCK")(8, "0")(2, "P2")(70, "0").point(10, {0, 0})(3, "P2");
  dxf.line("1", {0, 0}, {360, 0}).line("1", {360, 0}, {330, 500});
  dxf.line("1", {30, 500}, {330, 500}).line("1", {30, 500}, {0, 0});
  dxf.line("4", {15, 250}, {21, 250}); // 15 = the left side's x at y = 250
  dxf.line("7", {100, 100}, {300, 300});
  dxf.text("1", "Piece Name: back");
  dxf(0, "ENDBLK")(8, "0");
  dxf(0, "ENDSEC");
  dxf(0, "SECTION")(2, "ENTITIES");
  if (with_units) dxf.text("0", "Units: METRIC");
  dxf(0, "INSERT")(8, "0")(2, "P1").point(10, {0, 0});
  dxf(0, "INSERT")(8, "0")(2, "P2").point(10, {500, 0});
  dxf(0, "ENDSEC")(0, "EOF");
  return dxf.str();
}

// Every outline line's start, in metres.
std::vector<Vector2d> corners(const Panel& panel) {
  std::vector<Vector2d> points;
  for (const OutlineLine& line : panel.outline)
    points.push_back(line.curve.start());
  return points;
}

bool has_point(const std::vector<Vector2d>& points, const Vector2d& p) {
  for (const Vector2d& q : points)
    if ((q - p).norm() < 1e-9) return true;
  return false;
}

TEST(ImportDxf, AamaPiecesOutlinesGrainAndNotches) {
  const std::string path = write_file("two_pieces.dxf", aama_file(true));
  const auto pieces = read_dxf_pieces(path);
  ASSERT_EQ(pieces.size(), 2u);
  const Pattern pattern = parse_pattern(imported_pattern(pieces, {}, "aama").dump(), path);
  ASSERT_EQ(pattern.panels.size(), 2u);

  const Panel& front = pattern.panels[0];
  EXPECT_EQ(front.id, "front");
  // The rectangle's corners plus the notch at (0.4, 0.3) m, which starts a line.
  const auto front_corners = corners(front);
  EXPECT_EQ(front_corners.size(), 5u);
  for (const Vector2d& p :
       {Vector2d(0, 0), Vector2d(0.4, 0), Vector2d(0.4, 0.3), Vector2d(0.4, 0.6), Vector2d(0, 0.6)})
    EXPECT_TRUE(has_point(front_corners, p)) << p.transpose();
  EXPECT_NEAR(front.area(1e-6), 0.4 * 0.6, 1e-12);
  EXPECT_NEAR(front.grain.warp.x(), 0.0, 1e-12);
  EXPECT_NEAR(front.grain.warp.y(), 1.0, 1e-12);
  EXPECT_NEAR((front.grain.origin - Vector2d(0.2, 0.1)).norm(), 0.0, 1e-12);

  const Panel& back = pattern.panels[1];
  EXPECT_EQ(back.id, "back");
  const auto back_corners = corners(back);
  EXPECT_EQ(back_corners.size(), 5u);
  for (const Vector2d& p : {Vector2d(0, 0), Vector2d(0.36, 0), Vector2d(0.33, 0.5),
                            Vector2d(0.03, 0.5), Vector2d(0.015, 0.25)})
    EXPECT_TRUE(has_point(back_corners, p)) << p.transpose();
  // Trapezoid: (0.36 + 0.30) / 2 * 0.5.
  EXPECT_NEAR(back.area(1e-6), 0.165, 1e-12);
  EXPECT_NEAR(back.grain.warp.x(), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(back.grain.warp.y(), std::sqrt(0.5), 1e-12);
}

TEST(ImportDxf, UnitsFromTheCallerOrAnError) {
  const std::string path = write_file("no_units.dxf", aama_file(false));
  try {
    read_dxf_pieces(path);
    ADD_FAILURE() << "no error for a file without units";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("does not give its units"), std::string::npos);
  }
  // In centimetres the same numbers are ten times larger pieces.
  const auto pieces = read_dxf_pieces(path, 0.01);
  EXPECT_NEAR(pieces[0].boundary[0].length(), 4.0, 1e-12);
  EXPECT_THROW(read_dxf_pieces(write_file("missing.dxf", "") + ".none"), InputError);
}

std::string svg(const std::string& body) {
  return R"(<svg xmlns="http://www.w3.org/2000/svg" width="200mm" height="100mm" viewBox="0 0 400 200">)" +
         body + "</svg>";
}

TEST(ImportSvg, PathCommandsTransformsAndUnits) {
  // 2 user units per mm; the group moves by (10, 20) units and the path is
  // scaled by 2: the relative square of side 50 units is 100 units = 50 mm.
  const auto pieces =
      parse_svg_pieces(svg(R"svg(<g id="fs-part-square" transform="translate(10 20)">
               <path class="fabric" transform="scale(2)" d="m0 0 h50 v50 h-50 z"/></g>)svg"),
                       "square.svg");
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_EQ(pieces[0].name, "square");
  ASSERT_EQ(pieces[0].boundary.size(), 4u);
  // (10, 20) units = (5, 10) mm, y down: (0.005, -0.010) m.
  EXPECT_NEAR((pieces[0].boundary[0].start() - Vector2d(0.005, -0.010)).norm(), 0, 1e-12);
  EXPECT_NEAR((pieces[0].boundary[1].start() - Vector2d(0.055, -0.010)).norm(), 0, 1e-12);
  EXPECT_NEAR((pieces[0].boundary[2].start() - Vector2d(0.055, -0.060)).norm(), 0, 1e-12);

  // A quadratic (Q) and its smooth continuation (T): the quadratic through
  // p0, q, p1 has its midpoint at (p0 + 2 q + p1) / 4.
  const auto curved = parse_svg_pieces(
      svg(R"svg(<g id="arch"><path class="fabric" d="M 0,0 Q 50,-80 100,0 T 200,0 L 200,40 L 0,40 Z"/></g>)svg"),
      "arch.svg");
  const Curve& q = curved[0].boundary[0];
  ASSERT_EQ(q.kind, Curve::Kind::bezier);
  const Vector2d mid_units = (Vector2d(0, 0) + 2 * Vector2d(50, -80) + Vector2d(100, 0)) / 4;
  const Vector2d mid_m(mid_units.x() * 5e-4, -mid_units.y() * 5e-4);
  EXPECT_NEAR((q.at(0.5) - mid_m).norm(), 0, 1e-12);
  // T reflects the control point: (150, 80), so its midpoint is at y = +40 units.
  const Curve& t = curved[0].boundary[1];
  EXPECT_NEAR(t.at(0.5).y(), -40 * 5e-4, 1e-12);

  // Rotation about a point and a matrix give the same map.
  const auto rotated = parse_svg_pieces(
      svg(R"svg(<g id="r" transform="rotate(90 100 100)"><path class="fabric" d="M 100,100 L 150,100 L 150,120 Z"/></g>)svg"),
      "r.svg");
  const auto matrix = parse_svg_pieces(
      svg(R"svg(<g id="r" transform="matrix(0 1 -1 0 200 0)"><path class="fabric" d="M 100,100 L 150,100 L 150,120 Z"/></g>)svg"),
      "m.svg");
  for (std::size_t k = 0; k < 3; ++k)
    EXPECT_NEAR((rotated[0].boundary[k].start() - matrix[0].boundary[k].start()).norm(), 0, 1e-12);
  // (150, 100) rotated 90 degrees about (100, 100) is (100, 150) units.
  EXPECT_NEAR((rotated[0].boundary[1].start() - Vector2d(0.05, -0.075)).norm(), 0, 1e-12);
}

TEST(ImportSvg, ErrorsNameTheFileAndElement) {
  const auto expect_error = [](const std::string& text, const std::string& fragment) {
    try {
      parse_svg_pieces(text, "bad.svg");
      ADD_FAILURE() << "no error; expected: " << fragment;
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos) << error.what();
    }
  };
  expect_error(
      svg(R"svg(<g id="a"><path id="p" class="fabric" d="M 0,0 A 5 5 0 0 1 10,10 Z"/></g>)svg"),
      "bad.svg: <path id=\"p\">: path data: elliptical arcs (A) are not read");
  expect_error(svg(R"svg(<g id="a"><path class="fabric" d="M 0,0 L 10,0 L 10,10"/></g>)svg"),
               "piece 'a': path \"\": the outline (class \"fabric\") is not closed");
  expect_error("<svg><g>", "bad.svg: not valid XML");
  expect_error(R"svg(<svg width="10%" viewBox="0 0 1 1"><g id="a"/></svg>)svg",
               "cannot tell the units of \"10%\"");
  expect_error(svg(R"svg(<g id="a"><path class="note" d="M 0,0 L 1,1"/></g>)svg"),
               "no pattern piece");
}

Construction build(const Pattern& pattern) {
  static const auto shape = contact::make_mannequin_shape();
  const BodyDistance distance = [](const Eigen::Vector3d& p, Eigen::Vector3d* gradient) {
    const auto q = shape->query(p);
    if (gradient) *gradient = q.normal;
    return q.distance;
  };
  return construct(pattern, default_mannequin(), distance);
}

// cases/import/pencil_skirt.svg (mm; the front's stack moved by (20, 30)):
// the half front unfolded about its centre line x = 20 mm, the back cut
// twice, four darts, and TAGCON sews every dart leg to its partner.
// What FreeSewing 4 itself writes (cases/import/freesewing/): no viewBox but
// millimetres, a part's group "fs-stack-D.P-part-D.P", the grain and fold
// marks known by their markers and data-text, an open hem fold line drawn
// as fabric, and darts whose legs are cubic curves.
TEST(ImportSvg, FreeSewingFourOutput) {
  const std::string text =
      R"svg(<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" freesewing="4.10.2" width="300mm" height="700mm">
  <g id="fs-stack-d.front" transform="translate(10, 20)">
  <g id="fs-stack-d.front-part-d.front" transform="translate(0, 0)">
  <path class="fabric stroke-sm" id="fs-1" d="M 0,590 L 200,590" />
  <path class="fabric" id="fs-2" d="M 0,0 L 0,600 L 200,600 L 200,0 L 120,0 C 119,40 112,80 110,100 C 108,80 101,40 100,0 L 0,0 z" />
  <path class="note" marker-start="url(#cutonfoldFrom)" marker-end="url(#cutonfoldTo)" data-text="plugin-annotations:cutOnFold" d="M 0,30 L 15,30 L 15,570 L 0,570" />
  <use x="200" y="300" xlink:href="#notch" /><use x="60" y="300" xlink:href="#notch" />
  <path class="note" marker-start="url(#grainlineFrom)" marker-end="url(#grainlineTo)" data-text="plugin-annotations:grainline" d="M 50,70 L 50,540" />
  </g></g></svg>)svg";
  const auto pieces = parse_svg_pieces(text, "fs4.svg");
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_EQ(pieces[0].name, "front");
  // User units are mm: the hem corner (200, 600) moved by (10, 20), y up.
  EXPECT_NEAR((pieces[0].boundary[2].start() - Vector2d(0.21, -0.62)).norm(), 0, 1e-12);
  EXPECT_TRUE(pieces[0].internal.empty()); // the open hem fold line is not an internal line
  // The notch on the side seam splits the outline; the one inside is a mark.
  ASSERT_EQ(pieces[0].notches.size(), 1u);
  EXPECT_NEAR((pieces[0].notches[0] - Vector2d(0.21, -0.32)).norm(), 0, 1e-12);
  ASSERT_TRUE(pieces[0].fold.has_value());
  EXPECT_NEAR(((*pieces[0].fold)[0] - Vector2d(0.01, -0.05)).norm(), 0, 1e-12);
  EXPECT_NEAR(((*pieces[0].fold)[1] - Vector2d(0.01, -0.59)).norm(), 0, 1e-12);
  ASSERT_TRUE(pieces[0].grain.has_value());
  EXPECT_NEAR(((*pieces[0].grain)[1] - (*pieces[0].grain)[0]).norm(), 0.47, 1e-12);

  // Unfolded: the dart (20 mm wide, 100 mm deep, curved legs) and its mirror.
  const Pattern pattern =
      parse_pattern(imported_pattern(pieces, ImportSettings{}, "fs4").dump(), "fs4.json");
  ASSERT_EQ(pattern.panels.size(), 1u);
  const Panel& front = pattern.panels[0];
  ASSERT_EQ(front.darts.size(), 2u);
  for (const Dart& dart : front.darts)
    for (const OutlineLine& line : front.outline)
      if (line.id == dart.first_leg || line.id == dart.second_leg) {
        EXPECT_EQ(line.curve.kind, Curve::Kind::bezier) << line.id;
        // Longer than the chord of 10 mm across and 100 mm down, shorter
        // than the control polygon.
        const double chord = std::hypot(0.010, 0.100);
        const double polygon =
            std::hypot(0.001, 0.040) + std::hypot(0.007, 0.040) + std::hypot(0.002, 0.020);
        EXPECT_GT(line.curve.length(), chord) << line.id;
        EXPECT_LT(line.curve.length(), polygon) << line.id;
      }
}

// The tag file's keys for FreeSewing's patterns: pieces left out, the widest
// dart, where the torso hangs (written into the pattern, read back); bad
// values are errors naming the file and key.
TEST(ImportSvg, TagFileLeavesOutPiecesAndSetsTheAnchor) {
  const std::string two = svg(
      R"svg(<g id="fs-stack-d.a-part-d.a"><path class="fabric" d="M 0,0 L 100,0 L 100,100 L 0,100 Z"/></g>
      <g id="fs-stack-d.b-part-d.b"><path class="fabric" d="M 200,0 L 300,0 L 300,100 L 200,100 Z"/></g>)svg");
  const auto pieces = parse_svg_pieces(two, "two.svg");
  ASSERT_EQ(pieces.size(), 2u);
  const ImportSettings settings = read_import_settings(write_file(
      "tags_two.json",
      R"({"hangs_from": "shoulders", "max_dart_angle_deg": 40, "pieces": {"b": {"import": false}}})"));
  EXPECT_EQ(settings.max_dart_angle_deg, 40);
  const Pattern pattern =
      parse_pattern(imported_pattern(pieces, settings, "two").dump(), "two.json");
  ASSERT_EQ(pattern.panels.size(), 1u);
  EXPECT_EQ(pattern.panels[0].id, "a");
  ASSERT_TRUE(pattern.hangs_from_shoulders.has_value());
  EXPECT_TRUE(*pattern.hangs_from_shoulders);

  const auto expect_error = [](const std::string& text, const std::string& fragment) {
    try {
      read_import_settings(write_file("tags_bad.json", text));
      ADD_FAILURE() << "no error; expected: " << fragment;
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos) << error.what();
    }
  };
  expect_error(R"({"hangs_from": "knees"})", "tags_bad.json: hangs_from: expected");
  expect_error(R"({"max_dart_angle_deg": 95})", "tags_bad.json: max_dart_angle_deg: expected");
  expect_error(R"({"pieces": {"a": {"import": "no"}}})", "pieces.a.import: expected true or false");
  try {
    parse_pattern(R"({"format": "sartor-pattern", "version": 1, "hangs_from": "knees",
                      "panels": []})",
                  "p.json");
    ADD_FAILURE() << "no error for hangs_from knees";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("hangs_from"), std::string::npos) << error.what();
  }
}

TEST(ImportSvg, FreeSewingStylePencilSkirt) {
  const auto pieces = read_svg_pieces(cases_import + "/pencil_skirt.svg");
  ASSERT_EQ(pieces.size(), 2u);
  EXPECT_TRUE(pieces[0].fold.has_value());
  const ImportSettings settings = read_import_settings(cases_import + "/pencil_skirt_tags.json");
  const Pattern pattern =
      parse_pattern(imported_pattern(pieces, settings, "pencil").dump(), "pencil.json");
  ASSERT_EQ(pattern.panels.size(), 3u);
  const Panel& front = pattern.panels[0];
  // Hem corners: (240, 600) and its mirror (-240, 600) about x = 0, moved by (20, 30).
  const auto front_corners = corners(front);
  EXPECT_TRUE(has_point(front_corners, Vector2d(0.26, -0.63)));
  EXPECT_TRUE(has_point(front_corners, Vector2d(-0.22, -0.63)));
  // The hip notch (245, 250) and its mirror start lines.
  EXPECT_TRUE(has_point(front_corners, Vector2d(0.265, -0.28)));
  EXPECT_TRUE(has_point(front_corners, Vector2d(-0.225, -0.28)));
  for (const OutlineLine& line : front.outline) // the fold is gone
    EXPECT_FALSE(std::abs(line.curve.start().x() - 0.02) < 1e-9 &&
                 std::abs(line.curve.end().x() - 0.02) < 1e-9)
        << line.id;
  ASSERT_EQ(front.darts.size(), 2u);
  EXPECT_EQ(pattern.panels[1].tag.side, Side::back);
  EXPECT_EQ(pattern.panels[2].id, "back_2");
  EXPECT_EQ(pattern.packs.front().members.size(), 2u); // back and its twin, packed
  // Each back dart's legs: 15 mm across and 130 mm down.
  const Panel& back = pattern.panels[1];
  ASSERT_EQ(back.darts.size(), 1u);
  for (const OutlineLine& line : back.outline) {
    if (line.id == back.darts[0].first_leg || line.id == back.darts[0].second_leg) {
      EXPECT_NEAR(line.curve.length(), std::hypot(0.015, 0.13), 1e-12) << line.id;
    }
  }

  const Construction construction = build(pattern);
  int darts = 0, back_seam = 0;
  for (const FoundSeam& seam : construction.seams) {
    darts += seam.kind == SeamKind::dart;
    const std::string a = construction.lines[std::size_t(seam.line_a)].id;
    const std::string b = construction.lines[std::size_t(seam.line_b)].id;
    back_seam += (a == "back_8" && b == "back_2_8") || (a == "back_2_8" && b == "back_8");
  }
  EXPECT_EQ(darts, 4);
  EXPECT_EQ(back_seam, 1); // the centre back, between the twins
  for (const UnseamedLine& line : construction.unseamed) {
    for (const Panel& panel : pattern.panels)
      for (const Dart& dart : panel.darts)
        EXPECT_TRUE(construction.lines[std::size_t(line.line)].id != dart.first_leg &&
                    construction.lines[std::size_t(line.line)].id != dart.second_leg);
  }
}

} // namespace
} // namespace sartor::garment
