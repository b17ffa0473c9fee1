#pragma once
// The TAGCON placement drawn as SVG: a front view (looking at the body's
// front, its left to the right) and a left side view (front to the left),
// orthographic, with the body's silhouette, every panel's outline as placed
// in 3D (filled, translucent, outer layers drawn last) and every seam as a
// line between its two lines' middles coloured by certainty (blue certain,
// red uncertain). 1 SVG unit = 1 mm.

#include "garment/tagcon.hpp"

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace sartor::garment {

std::string placement_svg(const Construction& construction,
                          const std::vector<Eigen::Vector3d>& body_vertices,
                          const std::vector<std::array<int, 3>>& body_faces);

} // namespace sartor::garment
