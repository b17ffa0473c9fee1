#pragma once
// Adding a dart to a pattern (Sensitive Couture §3, "the designer adds a
// dart by drawing a line"): an outline line is cut at two points `width`
// apart (arc length) around `at`, and a V of two equal legs reaching
// `depth` into the panel from the cut's midpoint, square to the cut, is
// inserted between them and declared a dart (docs/pattern-format.md#darts).
// The line becomes LINE_a and LINE_b (a Bezier is split by de Casteljau, so
// both pieces lie on the old curve); the legs are DART_in and DART_out;
// sloper parameters that moved the line's corners move the pieces'.
// Done on the pattern file's JSON, in its units and orientation, and the
// result is read again (parse_pattern): every check of a pattern applies
// (the apex inside the panel, the legs clear of the outline).

#include <nlohmann/json.hpp>

#include <string>

namespace sartor::garment {

struct DartInsertion {
  std::string line;   // an outline line of the pattern
  double at = 0.5;    // where its middle is: the fraction of the line's arc length
  double width = 0.0; // m, along the line
  double depth = 0.0; // m, into the panel
  std::string id;     // the dart's id; empty: LINE_dart
};

// The pattern file `document` (read from `source`) with the dart added.
// Throws InputError naming `source` for a line that is not an outline line
// (or is a polyline), a cut that leaves the line (at -+ width/2 outside
// (0, 1) of it), a non-positive width or depth, an id already taken, and
// for whatever parse_pattern finds wrong with the result.
nlohmann::json add_dart(const nlohmann::json& document, const std::string& source,
                        const DartInsertion& dart);

} // namespace sartor::garment
