#pragma once
// A sewing pattern as TAGCON (thesis ch. 3) consumes it: flat panels with
// closed outlines made of lines (the units a seam joins), interior lines,
// a grain line, a fabric and a panel tag (alpha, beta, lambda) per panel, and
// packs of panels arranged together in 2D. Read from the JSON pattern format
// of docs/pattern-format.md, validated, in metres, every outline
// counter-clockwise. Serial; knows nothing of PETSc.

#include <Eigen/Core>
#include <nlohmann/json_fwd.hpp>

#include <optional>
#include <string>
#include <tuple>
#include <vector>

namespace sartor::garment {

// alpha: the cylinder of the cylindrical abstraction (thesis §3.1.1) a panel
// wraps around. The set is fixed (the thesis' "fixed key words").
enum class Cylinder { torso, arm_l, arm_r, leg_l, leg_r, neck, head };
// beta: the half cylinder.
enum class Side { front, back };

const char* name_of(Cylinder cylinder);
const char* name_of(Side side);
const std::vector<Cylinder>& all_cylinders();

// (alpha, beta, lambda). lambda orders layers in-to-out where panels overlap
// (T- and Y-seams); 0 for almost every panel, +1, +2, ... outer, -1, ... inner.
struct PanelTag {
  Cylinder cylinder = Cylinder::torso;
  Side side = Side::front;
  int layer = 0;
  bool operator==(const PanelTag& other) const {
    return cylinder == other.cylinder && side == other.side && layer == other.layer;
  }
  bool operator!=(const PanelTag& other) const { return !(*this == other); }
};
std::string to_string(const PanelTag& tag); // "(torso, front, 0)"

// One piece of curve in panel coordinates (metres): a straight segment
// (2 points), a cubic Bezier (4 points: start, control 1, control 2, end) or
// a polyline (2 or more points).
struct Curve {
  enum class Kind { straight, bezier, polyline };
  Kind kind = Kind::straight;
  std::vector<Eigen::Vector2d> points;

  const Eigen::Vector2d& start() const { return points.front(); }
  const Eigen::Vector2d& end() const { return points.back(); }
  // Point at parameter t in [0, 1]: the Bezier parameter, or the segment
  // index plus fraction over the number of segments for a polyline.
  Eigen::Vector2d at(double t) const;
  // Points from start to end, both included, no further than `tolerance`
  // from the curve (Beziers by adaptive subdivision; straight and polyline
  // curves exactly). parameters (optional) receives each point's t.
  std::vector<Eigen::Vector2d> flatten(double tolerance,
                                       std::vector<double>* parameters = nullptr) const;
  // Arc length (Beziers by Gauss-Legendre quadrature, to about 1e-12 relative).
  double length() const;
  // pieces + 1 points on the curve (start and end included) that split it
  // into pieces of equal arc length (to a relative 1e-9 of its length).
  // parameters (optional) receives each point's t, as at() takes it.
  std::vector<Eigen::Vector2d>
  split_equal_arc_length(int pieces, std::vector<double>* parameters = nullptr) const;
  Curve reversed() const;
};
const char* name_of(Curve::Kind kind);

// A line of a panel's outline. Seams join lines.
struct OutlineLine {
  std::string id;
  Curve curve;
  bool y_seam = false;   // secondary tag: part of a Y-seam (thesis §3.2)
  bool reversed = false; // the file gave the outline clockwise; turned round
  std::string json_path; // where it was defined, e.g. panels[1].outline[3]
};

// The crease of a fold line (thesis §6.2): the part of the panel on `side`
// of the line (the warping region) turns about the line's chord by `angle`
// towards the outside of the garment (away from the body) or its inside.
// The angle is the crease's bending rest angle, and pre-folding rotates the
// warping region by it before the simulation (docs/pleats.md).
struct Crease {
  enum class Side { left, right }; // of the line from its start to its end
  Side side = Side::left;
  double angle = 0.0; // rad, in (0, pi)
  bool outside = true;
  double pressed = 1.0; // the crease's bending stiffness over the fabric's
  std::string json_path;
};

// A line inside a panel: a fold line, or the line a T-seam sews to.
struct InteriorLine {
  enum class Kind { fold, t_seam };
  std::string id;
  Kind kind = Kind::fold;
  Curve curve;
  std::optional<Crease> crease; // fold lines only
  std::string json_path;
};
const char* name_of(InteriorLine::Kind kind);

// The warp direction and the origin of the material (u, v) coordinates:
// u = (p - origin) . warp, v = (p - origin) . weft, with weft the warp turned
// 90 degrees counter-clockwise, so (u, v) keeps the panel's orientation.
struct GrainLine {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  Eigen::Vector2d warp = Eigen::Vector2d::UnitY(); // unit vector
  Eigen::Vector2d weft() const { return {-warp.y(), warp.x()}; }
  Eigen::Vector2d material_uv(const Eigen::Vector2d& p) const {
    return {(p - origin).dot(warp), (p - origin).dot(weft())};
  }
};

// A dart (a V cut into the outline, sewn shut): two consecutive outline
// lines, the first ending at the apex inside the panel where the second
// starts; seam creation sews them to each other (docs/pattern-format.md#darts).
struct Dart {
  std::string id;
  std::string first_leg;  // the line that ends at the apex (counter-clockwise order)
  std::string second_leg; // the line that starts there
  std::string json_path;
};

struct Panel {
  std::string id;
  std::string fabric; // a fabric preset name, or a fabric YAML file path
  PanelTag tag;
  std::vector<OutlineLine> outline; // closed, counter-clockwise, not self-intersecting
  std::vector<InteriorLine> interior;
  std::vector<Dart> darts;
  GrainLine grain;
  bool reversed = false; // the outline was given clockwise
  std::string json_path;

  // The outline as a polygon (each line's points but its last), counter-clockwise.
  std::vector<Eigen::Vector2d> outline_polygon(double tolerance) const;
  double area(double tolerance) const; // of outline_polygon
};

// A rigid motion of the plane: rotate about the origin, then translate.
struct Placement {
  Eigen::Vector2d translation = Eigen::Vector2d::Zero();
  double rotation = 0; // radians, counter-clockwise
  Eigen::Vector2d apply(const Eigen::Vector2d& p) const;
  Placement then(const Placement& outer) const; // outer.apply(apply(p))
};

// Panels arranged together in 2D (thesis §3.1.2); they share one tag. Panels
// the file packs nowhere get a pack of their own (implicit).
struct Pack {
  struct Member {
    int panel = 0; // index into Pattern::panels
    Placement placement;
  };
  std::string id;
  std::vector<Member> members;
  bool implicit = false;
  std::string json_path;
};

// Two lines of one pattern sewn together by construction (the pleat
// generator's side-line segments), whatever TAGCON finds: line_a's start
// meets line_b's end when `reverse`.
struct Stitch {
  std::string line_a, line_b;
  bool reverse = false;
  std::string origin; // what made it, for messages and summaries
};

// Which corners of an outline line a move of the line moves.
enum class LineCorners { both, start, end };

// A point of a panel's outline: corner `index` (the start of outline line
// `index`) where `control` is 0, else Bezier control point `control` (1 or
// 2) of line `index`.
struct OutlinePoint {
  std::size_t panel = 0, index = 0;
  int control = 0;
  bool operator<(const OutlinePoint& other) const {
    return std::tie(panel, index, control) < std::tie(other.panel, other.index, other.control);
  }
};

// A sloper parameter (Sensitive Couture §3): a named dimension of the
// pattern (a skirt's length, a waist's width) that outline corners follow
// linearly. A change g of it moves each move's corners by g * per_unit
// (docs/pattern-format.md#parameters); `sartor edit` sets it by a slider
// (an edit step's `change`) or by a drag of the drape.
struct ParameterMove {
  std::string line; // an outline line
  using Corner = LineCorners;
  Corner corner = Corner::both;
  Eigen::Vector2d per_unit = Eigen::Vector2d::Zero(); // m per m of the parameter
};
struct SloperParameter {
  std::string id;
  std::string description;
  std::vector<ParameterMove> moves;
  std::string json_path;
};

struct Pattern {
  int version = 1;
  std::string name;
  std::string source;      // the file read, for messages
  double tolerance = 1e-6; // m: closure and coincidence tolerance
  // Where TAGCON hangs the torso cylinder: from the shoulders (a top, a
  // dress) or the waist; unset: decided from the packs (docs/tagcon.md).
  std::optional<bool> hangs_from_shoulders;
  std::vector<Panel> panels;
  std::vector<Pack> packs; // every panel in exactly one
  std::vector<Stitch> stitches;
  std::vector<SloperParameter> parameters;

  const Panel* find_panel(const std::string& id) const;
  int pack_of(int panel) const; // index into packs
  PanelTag pack_tag(int pack) const { return panels[packs[pack].members.front().panel].tag; }
  // Flattening tolerance for geometry checks and areas: a small fraction of
  // the pattern's size, never below `tolerance`.
  double flattening_tolerance() const;
};

constexpr int pattern_format_version = 1;

// Reads and validates a pattern file. Throws InputError "FILE: JSON_PATH:
// what is wrong" for malformed JSON, missing fields, wrong types, unknown
// keys or tags or fabrics, non-positive sizes, duplicate ids, outlines that
// do not close or intersect themselves, interior lines outside their panel,
// and packs whose panels carry different tags.
Pattern read_pattern(const std::string& path);
// The same from text already read; `source` names it in messages.
Pattern parse_pattern(const std::string& text, const std::string& source);

// The panel's "darts" (JSON array at `path` of `source`), validated against
// its counter-clockwise outline: each names two consecutive lines of it that
// meet at a reflex corner (the apex) and whose lengths differ by at most 5%.
// Throws InputError naming the dart's JSON path. pattern_darts.cpp.
std::vector<Dart> read_darts(const nlohmann::json& darts, const std::string& path,
                             const std::string& source, const Panel& panel);

// The pattern's "parameters" (JSON array at `path` of `source`), validated
// against its outline lines (after pleats): ids unique, every move an
// outline line's, per-unit moves finite and at most 10 m per m, no corner
// moved two ways by one parameter. Throws InputError naming the JSON path.
// pattern_parameters.cpp.
std::vector<SloperParameter> read_sloper_parameters(const nlohmann::json& parameters,
                                                    const std::string& path,
                                                    const std::string& source,
                                                    const Pattern& pattern);

// The points a move of outline line `line` moves, in every panel that has
// the line: its start and/or end corner, or, where `control` > 0, that
// control point of it. Empty when no panel has the line. Sloper parameters
// and `sartor edit` move corners by it. pattern_parameters.cpp.
std::vector<OutlinePoint> moved_outline_points(const Pattern& pattern, const std::string& line,
                                               LineCorners corners, int control = 0);

// Each panel's placement on the flat sheet where the pattern is drawn: packs
// as the file places them, packs side by side left to right in file order,
// `gap` metres apart.
std::vector<Placement> sheet_layout(const Pattern& pattern, double gap);

// Crossing-number test of a point against a closed polygon; the point is
// assumed off the polygon's boundary.
bool inside_polygon(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p);

} // namespace sartor::garment
