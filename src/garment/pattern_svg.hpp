#pragma once
// The pattern drawn as SVG, for a person to check what was read: panels laid
// out as sheet_layout() places them (packs as the file arranges them, packs
// side by side), outlines (Y-seam lines in red), interior lines dashed, grain
// lines as arrows along the warp, line ids at each line's middle, panel ids
// and tags (alpha, beta, lambda) at each panel's centre. 1 SVG unit = 1 mm.

#include "garment/pattern.hpp"

#include <string>
#include <vector>

namespace sartor::garment {

// A seam drawn over the pattern: its two lines thick, and a dashed line
// between their middles, coloured by certainty from red (0) to blue (1).
struct SvgSeam {
  std::string line_a;
  std::string line_b;
  double certainty = 1;
};

struct SvgOptions {
  double gap = 0.05;       // m between packs
  bool line_labels = true; // write each line's id
  std::vector<SvgSeam> seams;
};

// "#rrggbb" from blue (certainty 1) through purple to red (certainty 0).
std::string certainty_colour(double certainty);

// SVG elements (user units = mm, not grouped) with their lower left corner at (x, y): a
// 10 cm scale bar and, when `seams`, the seam colours for certainty 0 to 1.
std::string svg_legend(double x, double y, bool seams);

std::string pattern_svg(const Pattern& pattern, const SvgOptions& options = {});
// Written atomically (complete or not at all).
void write_pattern_svg(const std::string& path, const Pattern& pattern,
                       const SvgOptions& options = {});

} // namespace sartor::garment
