#pragma once
// Pattern pieces from an SVG drawing laid out as FreeSewing draws its
// patterns (docs/patterns.md#svg): one group per piece (its id names it,
// less a "fs-part-", "part-" or "fs-stack-" prefix), in it a closed path of
// class "fabric" (the seam line: the outline), paths of class "sa" (seam
// allowance: ignored), a path whose id or class holds "grainline" (the warp,
// first to last point) and one whose id or class holds "cutonfold" (its
// first and last points lie on the fold). Paths: M L H V C S Q T Z, absolute
// and relative; transforms on groups and paths (matrix, translate, scale,
// rotate, skewX, skewY); units from the root's width and viewBox. Pattern
// coordinates are metres with y up (SVG's y runs down).

#include "garment/pattern_import.hpp"

#include <string>
#include <vector>

namespace sartor::garment {

// Throws InputError naming the file and the element for unreadable XML, a
// path command it cannot read (arcs: A), a piece without or with an open
// outline, or units it cannot tell.
std::vector<ImportedPiece> read_svg_pieces(const std::string& path);
std::vector<ImportedPiece> parse_svg_pieces(const std::string& text, const std::string& source);

} // namespace sartor::garment
