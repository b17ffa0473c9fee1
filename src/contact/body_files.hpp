#pragma once
// The files a body is described by besides its OBJ mesh (docs/bodies.md):
//   * a measurement set, JSON, the layout agreed with the FreeSewing import:
//       {"name": "...", "units": "mm", "measurements": {"waist": 760, ...}}
//     names are FreeSewing's (contact/mannequin.hpp: is_known_measurement);
//   * a skeleton, JSON, as `sartor body` writes it ("format": "sartor-skeleton").

#include "contact/mannequin.hpp"

#include <string>
#include <vector>

namespace sartor {

struct MeasurementFile {
  std::string name;                   // the set's name ("" when the file has none)
  Measurements measurements;          // those the mannequin is sized to, mm
  std::vector<std::string> defaulted; // the mannequin's names the file lacks
  std::vector<std::string> unused;    // FreeSewing names the mannequin does not use
};

// Throws InputError naming the file and the key: not JSON, units not "mm",
// an unknown name, a value that is not a positive finite number.
MeasurementFile read_measurement_file(const std::string& path);

// Bones with start, end (m) and optional start_radius/end_radius (absent:
// estimated from `mesh`, the mean distance of the nearest vertices).
// Throws InputError naming the file and the bone.
std::vector<Bone> read_skeleton_file(const std::string& path, const BodyMesh& mesh);

} // namespace sartor
