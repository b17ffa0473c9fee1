#include "app/drape_outcome.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace sartor {

const char* name_of(DrapeEnd end) {
  switch (end) {
  case DrapeEnd::on_body:
    return "on_body";
  case DrapeEnd::slid_down:
    return "slid_down";
  case DrapeEnd::on_floor:
    return "on_floor";
  case DrapeEnd::off_body:
    return "off_body";
  }
  return "?";
}

namespace {
// Millimetres are what a reader compares.
std::string metres(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f m", value);
  return text;
}
} // namespace

std::string DrapeOutcome::description() const {
  switch (end) {
  case DrapeEnd::on_body:
    return "on the body";
  case DrapeEnd::slid_down:
    return "slid down " + metres(centroid_drop);
  case DrapeEnd::on_floor:
    return "on the floor (lowest point " + metres(lowest - floor) + " above it)";
  case DrapeEnd::off_body:
    return "off the body (nearest point " + metres(nearest_body_distance) + " from it)";
  }
  return "?";
}

DrapeOutcome classify_drape_end(const std::vector<Eigen::Vector3d>& initial,
                                const std::vector<Eigen::Vector3d>& final, double floor,
                                const std::function<double(const Eigen::Vector3d&)>& body_distance,
                                const DrapeEndLimits& limits) {
  if (initial.empty() || initial.size() != final.size())
    throw std::invalid_argument("classify_drape_end: the initial and final vertex lists differ");
  DrapeOutcome outcome;
  outcome.floor = floor;
  outcome.lowest = std::numeric_limits<double>::infinity();
  outcome.nearest_body_distance = std::numeric_limits<double>::infinity();
  double start_height = 0.0, end_height = 0.0;
  for (std::size_t v = 0; v < final.size(); ++v) {
    start_height += initial[v].z();
    end_height += final[v].z();
    outcome.lowest = std::min(outcome.lowest, final[v].z());
    outcome.nearest_body_distance =
        std::min(outcome.nearest_body_distance, body_distance(final[v]));
  }
  outcome.centroid_drop = (start_height - end_height) / double(final.size());
  outcome.slid_down = outcome.centroid_drop > limits.drop_tolerance;
  outcome.on_floor = outcome.lowest <= floor + limits.floor_clearance;
  outcome.off_body = outcome.nearest_body_distance > limits.touch_distance;
  outcome.end = outcome.off_body    ? DrapeEnd::off_body
                : outcome.on_floor  ? DrapeEnd::on_floor
                : outcome.slid_down ? DrapeEnd::slid_down
                                    : DrapeEnd::on_body;
  return outcome;
}

} // namespace sartor
