#pragma once
// Patterns of other programs into Sartor's pattern format
// (docs/patterns.md): the pieces that a DXF-AAMA file (garment/import_dxf)
// or an SVG drawing (garment/import_svg) holds, turned into panels: a piece
// cut on the fold is mirrored about the fold into one panel, a piece cut
// twice gets a mirrored twin, the outline is split into lines at corners and
// notches, and V-shaped notches of two equal straight lines become darts.
// Tags and fabrics come from a small tag file. Serial, no PETSc.

#include "garment/pattern.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace sartor::garment {

using Segment = std::array<Eigen::Vector2d, 2>;

// One piece as the source file draws it, in metres with y up.
struct ImportedPiece {
  std::string name;
  std::string where;           // "FILE: block 'X'", for messages
  std::vector<Curve> boundary; // closed: each curve starts where the last ended
  std::vector<std::vector<Eigen::Vector2d>> internal; // internal lines (polylines)
  std::optional<Segment> grain;                       // from, to (the warp)
  std::optional<Segment> fold;          // cut on the fold / mirror line: two of its points
  std::vector<Eigen::Vector2d> notches; // on the boundary
  int quantity = 1;                     // cut this many (2: a mirrored twin)
};

// What the tag file (docs/patterns.md#tag-file) says of a piece.
struct PieceSettings {
  std::optional<PanelTag> tag;
  std::optional<PanelTag> twin_tag; // of a cut-2 piece's mirrored twin: then in a pack of its own
  std::string fabric;
  std::optional<int> quantity;
  bool mirror_right = false; // twin mirrored about the piece's right edge, not its left
  bool darts = true;         // find darts
  bool imported = true;      // false: the piece is left out (a waistband, a binding)
};

struct ImportSettings {
  std::string fabric = "cotton_twill";
  std::map<std::string, PieceSettings> pieces;
  double corner_angle_deg = 20; // a turn sharper than this between curves starts a new line
  double max_dart_angle_deg = 35;
  std::string hangs_from; // "shoulders", "waist" or empty: the pattern's hangs_from
  std::string source;     // the tag file, for messages; empty: none
};

// Reads a tag file. Throws InputError naming file and key.
ImportSettings read_import_settings(const std::string& path);

// What the import did, for the command's report.
struct ImportReport {
  std::vector<std::string> lines; // one per piece and per notable choice
};

// The pattern JSON (format sartor-pattern, version 1, metres) of the pieces.
// Throws InputError for a piece the pattern format cannot hold (an open or
// self-touching boundary, a fold line that is not an edge of the piece, a
// tag file naming a piece that is not there).
nlohmann::json imported_pattern(const std::vector<ImportedPiece>& pieces,
                                const ImportSettings& settings, const std::string& name,
                                ImportReport* report = nullptr);

// The affine map of 2D points: x -> linear x + offset.
struct Affine2 {
  Eigen::Matrix2d linear = Eigen::Matrix2d::Identity();
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();
  Eigen::Vector2d operator()(const Eigen::Vector2d& p) const { return linear * p + offset; }
  Affine2 after(const Affine2& inner) const { // this(inner(p))
    return {linear * inner.linear, linear * inner.offset + offset};
  }
};

// A bezier/straight curve mapped point by point (exact for affine maps).
Curve mapped(const Curve& curve, const Affine2& map);

} // namespace sartor::garment
