#pragma once
// Small patterns built in code, so that each test can break one thing.

#include "garment/pattern.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace sartor::garment::testing {

inline nlohmann::json straight(const std::string& id, double x0, double y0, double x1, double y1) {
  return {{"id", id}, {"type", "straight"}, {"points", {{x0, y0}, {x1, y1}}}};
}

// A counter-clockwise square panel of side `size` with its lower-left corner
// at (x0, 0); lines PREFIXbottom, PREFIXright, PREFIXtop, PREFIXleft.
inline nlohmann::json square_panel(const std::string& id, const std::string& prefix,
                                   double size = 0.4, double x0 = 0) {
  const double x1 = x0 + size;
  return {
      {"id", id},
      {"fabric", "silk"},
      {"tag", {{"cylinder", "torso"}, {"side", "front"}}},
      {"grain", {{"angle_deg", 90}}},
      {"outline",
       {straight(prefix + "bottom", x0, 0, x1, 0), straight(prefix + "right", x1, 0, x1, size),
        straight(prefix + "top", x1, size, x0, size), straight(prefix + "left", x0, size, x0, 0)}}};
}

inline nlohmann::json pattern_of(const std::vector<nlohmann::json>& panels) {
  return {{"format", "sartor-pattern"},
          {"version", 1},
          {"units", "m"},
          {"panels", nlohmann::json(panels)}};
}

inline Pattern parse(const nlohmann::json& document) {
  return parse_pattern(document.dump(), "test.json");
}

} // namespace sartor::garment::testing
