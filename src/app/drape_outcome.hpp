#pragma once
// How a drape ended, read from where the garment started and where it came
// to rest (docs/drape.md#how-a-drape-ended): on the body, or slid down it,
// on the floor, or off the body. A drape that ends anywhere but on the body
// did not drape the garment, whatever its solver reports.

#include <Eigen/Core>

#include <functional>
#include <string>
#include <vector>

namespace sartor {

struct DrapeEndLimits {
  double drop_tolerance = 0.1;   // m the garment's centroid may sink below its start
  double floor_clearance = 0.01; // m above the floor that counts as on it
  double touch_distance = 0.02;  // m from the body within which a vertex touches it
};

enum class DrapeEnd { on_body, slid_down, on_floor, off_body };
const char* name_of(DrapeEnd end);

struct DrapeOutcome {
  DrapeEnd end = DrapeEnd::on_body; // the first that holds of off_body, on_floor, slid_down
  bool slid_down = false;
  bool on_floor = false;
  bool off_body = false;
  double centroid_drop = 0.0;         // m, > 0 when the garment sank (vertex mean height)
  double lowest = 0.0;                // m, the lowest vertex's height
  double floor = 0.0;                 // m, the floor's height
  double nearest_body_distance = 0.0; // m, of the vertex closest to the body
  std::string description() const;    // e.g. "slid down 0.44 m"
};

// `initial` and `final` are the same vertices before and after the drape;
// `body_distance` the signed distance to the body (> 0 outside), m; `up` is
// +z. Throws std::invalid_argument when the lists differ in size or are empty.
DrapeOutcome classify_drape_end(const std::vector<Eigen::Vector3d>& initial,
                                const std::vector<Eigen::Vector3d>& final, double floor,
                                const std::function<double(const Eigen::Vector3d&)>& body_distance,
                                const DrapeEndLimits& limits = {});

} // namespace sartor
