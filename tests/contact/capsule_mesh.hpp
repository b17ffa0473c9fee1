#pragma once
// A closed, outward-oriented triangle mesh of the capsule of radius r around
// the z axis from z = 0 to z = length, for tests: `around` vertices per
// ring, `cap_rings` rings in each hemispherical cap (poles excluded),
// `body_rings` ring gaps along the cylinder. Its vertices lie on the capsule,
// so its surface is inside it by at most the chords' sagitta.

#include "contact/body_obj.hpp"

#include <cmath>

namespace sartor::test {

inline BodyMesh capsule_mesh(double radius, double length, int around = 32, int cap_rings = 8,
                             int body_rings = 10) {
  BodyMesh mesh;
  const auto ring = [&](double z, double ring_radius) {
    for (int i = 0; i < around; ++i) {
      const double angle = 2.0 * M_PI * i / around;
      mesh.vertices.emplace_back(ring_radius * std::cos(angle), ring_radius * std::sin(angle), z);
    }
  };
  mesh.vertices.emplace_back(0.0, 0.0, -radius); // south pole
  for (int k = 1; k <= cap_rings; ++k) {         // lower cap, the equator last
    const double polar = 0.5 * M_PI * k / cap_rings;
    ring(-radius * std::cos(polar), radius * std::sin(polar));
  }
  for (int k = 1; k <= body_rings; ++k) // the cylinder up to z = length
    ring(length * k / body_rings, radius);
  for (int k = cap_rings - 1; k >= 1; --k) { // upper cap
    const double polar = 0.5 * M_PI * k / cap_rings;
    ring(length + radius * std::cos(polar), radius * std::sin(polar));
  }
  mesh.vertices.emplace_back(0.0, 0.0, length + radius); // north pole
  const int rings = 2 * cap_rings - 1 + body_rings;
  const auto at = [&](int r, int i) { return 1 + r * around + (i % around); };
  const int north = int(mesh.vertices.size()) - 1;
  for (int i = 0; i < around; ++i) {
    mesh.faces.push_back({0, at(0, i + 1), at(0, i)});
    for (int r = 0; r + 1 < rings; ++r) {
      mesh.faces.push_back({at(r, i), at(r, i + 1), at(r + 1, i + 1)});
      mesh.faces.push_back({at(r, i), at(r + 1, i + 1), at(r + 1, i)});
    }
    mesh.faces.push_back({north, at(rings - 1, i), at(rings - 1, i + 1)});
  }
  return mesh;
}

} // namespace sartor::test
