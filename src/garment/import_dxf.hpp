#pragma once
// Pattern pieces from a DXF-AAMA file (ASTM D6673, the apparel industry's
// exchange format; docs/patterns.md#dxf-aama), read with dxflib: one block
// per piece; layer 1 its boundary (the cut line; layer 14, the sew line,
// when the block has a closed one: Sartor sews along it), layer 4 notches
// (points, or short lines from the boundary), layer 6 the mirror line (cut
// on the fold), layer 7 the grain line, layer 8 internal lines; texts "Piece
// Name: X" and "Quantity: N". Units from $INSUNITS, else a text "Units:
// METRIC" (mm) or "ENGLISH" (inches), else the caller's.

#include "garment/pattern_import.hpp"

#include <string>
#include <vector>

namespace sartor::garment {

// metres_per_unit > 0 overrides the file's units. Throws InputError naming
// the file and block for an unreadable file, a block without a closed
// boundary, arcs (bulges) in a boundary, or units the file does not give and
// the caller did not either.
std::vector<ImportedPiece> read_dxf_pieces(const std::string& path, double metres_per_unit = 0);

} // namespace sartor::garment
