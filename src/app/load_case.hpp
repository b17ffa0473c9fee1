#pragma once
// The loads and pins of a cloth case: gravity, pressure, a point force and an
// edge load; pins by box, boundary and vertex, their motion and release in
// time; and the probe. The options are read once into a typed LoadCase
// (each value checked on its own); what depends on the mesh (which vertices
// a box pins, which edges carry the load) is found against the mesh solved.

#include "app/cli.hpp"
#include "fem/cloth_model.hpp"
#include "fem/pin_motion.hpp"
#include "mesh/triangle_mesh.hpp"

#include <Eigen/Core>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace sartor {

// The load and pin options, declared by this module.
const std::vector<OptionSpec>& load_option_specs();

// Option --NAME as three comma-separated numbers. Throws InputError naming it.
Eigen::Vector3d option_vector3(const Options& options, const std::string& name);

// An axis-aligned box x0,x1,y0,y1,z0,z1, m (closed).
struct CaseBox {
  std::array<double, 6> bounds{};
  bool contains(const Eigen::Vector3d& p) const;
};

struct PointForceCase {
  double vertex = 0.0; // as given (a whole number, checked against the mesh)
  Eigen::Vector3d force = Eigen::Vector3d::Zero(); // N
};

struct EdgeForceCase {
  Eigen::Vector3d force = Eigen::Vector3d::Zero(); // total, N
  CaseBox box; // the boundary edges with both ends inside carry it
};

// --pin-motion: one history per group; each group moves every pin or, with
// --pin-motion-boxes, the pins in its boxes (numbered from 1).
struct PinMotionCase {
  std::vector<PinHistory> histories;
  std::vector<std::vector<std::size_t>> boxes;     // per group; empty: one group moving every pin
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ(); // of the angles (unit)
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
};

struct LoadCase {
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero(); // m/s^2
  double pressure = 0.0;                             // Pa
  std::optional<PointForceCase> point_force;
  std::optional<EdgeForceCase> edge_force;
  std::vector<CaseBox> pin_boxes;   // --pin-box
  bool pin_boundary = false;        // --pin-boundary
  std::vector<double> pin_vertices; // --pin-vertices, as given (checked against the mesh)
  Eigen::Vector3d pin_move = Eigen::Vector3d::Zero(); // statics: ramped with the load, m
  std::optional<PinMotionCase> pin_motion;
  // --pin-release: per pin box, the time its pins let go (infinity: never), s;
  // empty without the option.
  std::vector<double> pin_release;
  std::optional<Eigen::Vector3d> probe; // m
};

// Throws InputError naming the option for a malformed value or a box number
// that --pin-box does not have.
LoadCase read_load_case(const Options& options);

// The pinned vertices, in increasing order. Throws InputError for a
// --pin-vertices entry that is not a vertex of the mesh.
std::vector<int> pinned_vertices(const LoadCase& loads, const TriangleMesh& mesh);

// The --pin-motion groups over `pinned` (indices into it). Throws InputError
// when nothing is pinned or a vertex falls in two groups.
std::vector<PinGroupMotion> pin_groups(const LoadCase& loads, const TriangleMesh& mesh,
                                       const std::vector<int>& pinned);

// Per pinned vertex, the time its pin lets go (infinity: never). A vertex is
// let go only when every --pin-box holding it is, at the last of their
// times; pins of --pin-boundary and --pin-vertices hold throughout.
std::vector<double> pin_release_times(const LoadCase& loads, const TriangleMesh& mesh,
                                      const std::vector<int>& pinned);

// Gravity, pressure, the point force and the edge load (consistent nodal
// forces of a uniform line load per unit material length). Throws
// InputError for a point force off the mesh or an edge box holding no
// boundary edge.
void set_case_loads(const LoadCase& case_loads, const TriangleMesh& mesh, ClothLoads* loads);

} // namespace sartor
