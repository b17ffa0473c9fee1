#pragma once
// The pleat generator (thesis §6.2): from two side lines of a panel, a
// stationary side, a pleat type, a number of slash lines, a depth and the
// in-fold and out-fold angles it slashes the panel between the side lines,
// spreads it away from the stationary side, and adds the creases (fold lines
// with their rest angles, which pre-folding also uses) and the stitches that
// sew the side-line segments of each pleat together. docs/pleats.md has the
// geometry and the `pleats` block of the pattern format.

#include "garment/pattern.hpp"

#include <nlohmann/json_fwd.hpp>

#include <string>
#include <vector>

namespace sartor::garment {

enum class PleatType { knife, box, inverted_box };
const char* name_of(PleatType type);

struct PleatSpec {
  std::string id;
  std::string panel;
  std::array<std::string, 2> side_lines; // outline lines the slash lines join
  std::string stationary;                // an outline line on the side that stays
  PleatType type = PleatType::knife;
  int slash_lines = 1;   // = pleats
  double depth = 0.0;    // m: how far each pleat folds under
  double in_fold = 0.0;  // rad, the hidden creases' angle, (0, pi)
  double out_fold = 0.0; // rad, the visible creases' angle, (0, pi)
  double pressed = 1.0;  // the creases' bending stiffness over the fabric's
  enum class Sew { first, both, none };
  Sew sew = Sew::first; // which side lines get the pleats' stitches
  std::string json_path;
};

// One crease of a pleat, at `offset` depths from the insert's stationary edge:
// out-folds turn the rest of the panel towards the inside of the garment (a
// ridge seen from outside), in-folds towards the outside.
struct PleatCrease {
  int offset = 0; // in depths
  bool out_fold = true;
};
// Knife: out at 0, in at 1 (insert 2 depths). Box: in at 0, out at 1 and 3,
// in at 4; inverted box: out at 0, in at 1 and 3, out at 4 (insert 4 depths).
std::vector<PleatCrease> pleat_creases(PleatType type);
double insert_width(PleatType type); // in depths

// Reads the `pleats` array (lengths scaled by `scale` to metres) and applies
// each entry to its panel in `pattern` (already read and validated): the
// panel's outline gets the spread pieces and inserts, its interior the
// creases, and pattern.stitches the side-line seams. Throws InputError
// naming the file and the entry for a bad entry or geometry.
void apply_pleats(Pattern& pattern, const nlohmann::json& pleats, double scale);

// Applies one pleat specification (in metres).
void apply_pleat(Pattern& pattern, const PleatSpec& spec);

} // namespace sartor::garment
