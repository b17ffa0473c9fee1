#pragma once
// The pattern drawn as SVG, for a person to check what was read: panels laid
// out as sheet_layout() places them (packs as the file arranges them, packs
// side by side), outlines (Y-seam lines in red), interior lines dashed, grain
// lines as arrows along the warp, line ids at each line's middle, panel ids
// and tags (alpha, beta, lambda) at each panel's centre. 1 SVG unit = 1 mm.

#include "garment/pattern.hpp"

#include <string>

namespace sartor::garment {

struct SvgOptions {
  double gap = 0.05;       // m between packs
  bool line_labels = true; // write each line's id
};

std::string pattern_svg(const Pattern& pattern, const SvgOptions& options = {});
// Written atomically (complete or not at all).
void write_pattern_svg(const std::string& path, const Pattern& pattern,
                       const SvgOptions& options = {});

} // namespace sartor::garment
