#include "app/mesh_case.hpp"

#include "app/case_checks.hpp"
#include "app/commands.hpp"
#include "app/load_case.hpp"
#include "common/error.hpp"
#include "mesh/obj.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace sartor {

const std::vector<OptionSpec>& mesh_option_specs() {
  static const std::vector<OptionSpec> specs = with_module_prefix(
      {
          {"mesh", "KIND", "rectangle",
           "rectangle, disk, annulus, cylinder_band, sphere_cap, tube_panels or obj"},
          {"mesh-file", "FILE", "", "OBJ file (mesh obj): texture coordinates give the rest shape"},
          {"mesh-width", "M", "1", "rectangle width (along warp), m"},
          {"mesh-height", "M", "1", "rectangle or band height (along weft), m"},
          {"mesh-nx", "N", "10", "rectangle divisions along the width"},
          {"mesh-ny", "N", "10", "rectangle divisions along the height"},
          {"mesh-pattern", "P", "alternating",
           "rectangle (and annulus) diagonals: alternating, right, perturbed"},
          {"mesh-radius", "M", "0.5", "disk, band or sphere radius, annulus outer radius, m"},
          {"mesh-inner-radius", "M", "0.25", "annulus inner radius, m"},
          {"mesh-angles", "A0,A1", "0,360",
           "annulus: from angle A0 to A1, degrees (a full turn stays slit along A0)"},
          {"mesh-lift", "M", "0",
           "annulus: start placement on a helix rising from z = 0 at angle 0 to this at A1, m "
           "(tells the slit's edges apart; the rest shape stays flat)"},
          {"mesh-rings", "N", "8", "disk or cap rings; annulus cells across the radii"},
          {"mesh-segments", "N", "32", "band segments around; annulus cells around"},
          {"mesh-rows", "N", "8", "band rows along the axis"},
          {"mesh-cap-angle", "RAD", "0.5", "sphere cap half angle, rad"},
          {"mesh-nx-front", "N", "", "tube_panels: front panel divisions around [mesh-nx]"},
          {"mesh-ny-front", "N", "",
           "tube_panels: front panel divisions along the height [mesh-ny]"},
          {"mesh-gap", "M", "0.15", "tube_panels: distance the two panels start apart, m"},
          {"mesh-refine", "N", "0", "uniform refinements (each splits triangles in four)"},
          {"mesh-snap-boundary", "", "",
           "disk: put refined boundary vertices back on the circle (position and uv)"},
          {"mesh-waves", "N,A,R0", "",
           "out-of-plane imperfection of the placement: N waves around the z axis, amplitude A (m) "
           "at the rim, growing from radius R0 (m) (docs/contact.md)"},
          {"mesh-rotate-x", "DEG", "0", "rotate the placement about the x axis, degrees"},
          {"mesh-translate", "X,Y,Z", "0,0,0", "then translate it, m"},
      },
      {"mesh"}, {{"mesh", "mesh-kind"}});
  return specs;
}

namespace {

PlacementWaves read_placement_waves(const std::string& text) {
  const auto bad = [&](const std::string& why) {
    return InputError("option --mesh-waves: " + why + " (expected N,AMPLITUDE,RADIUS, e.g. " +
                      "8,0.002,0.09), got '" + text + "'");
  };
  std::vector<double> values;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    std::size_t used = 0;
    try {
      values.push_back(std::stod(item, &used));
    } catch (const std::exception&) {
      throw bad("'" + item + "' is not a number");
    }
    if (item.find_first_not_of(" \t", used) != std::string::npos || !std::isfinite(values.back()))
      throw bad("'" + item + "' is not a number");
  }
  if (values.size() != 3) throw bad("three numbers needed");
  if (values[0] < 1.0 || values[0] != std::floor(values[0]))
    throw bad("N must be a whole number >= 1");
  if (values[2] < 0.0) throw bad("the radius where the waves start must not be negative");
  return {values[0], values[1], values[2], text};
}

// The parameters of the generator --mesh names, and only those.
void read_generator(const Options& options, MeshCase& mesh) {
  const std::string& kind = mesh.kind;
  const auto pattern = [&] { return mesh::rectangle_pattern(options.text("mesh-pattern")); };
  if (kind == "rectangle") {
    mesh.width = options.positive_real("mesh-width");
    mesh.height = options.positive_real("mesh-height");
    mesh.nx = count_option(options, "mesh-nx", 1);
    mesh.ny = count_option(options, "mesh-ny", 1);
    mesh.pattern = pattern();
  } else if (kind == "disk") {
    mesh.radius = options.positive_real("mesh-radius");
    mesh.rings = count_option(options, "mesh-rings", 1);
  } else if (kind == "annulus") {
    const auto angles = option_numbers(options, "mesh-angles", 2);
    mesh.angle_from = angles[0];
    mesh.angle_to = angles[1];
    mesh.inner_radius = options.positive_real("mesh-inner-radius");
    mesh.radius = options.positive_real("mesh-radius");
    mesh.rings = count_option(options, "mesh-rings", 1);
    mesh.segments = count_option(options, "mesh-segments", 1);
    mesh.pattern = pattern();
    mesh.lift = options.real("mesh-lift");
  } else if (kind == "cylinder_band") {
    mesh.radius = options.positive_real("mesh-radius");
    mesh.height = options.positive_real("mesh-height");
    mesh.segments = count_option(options, "mesh-segments", 3);
    mesh.rows = count_option(options, "mesh-rows", 1);
  } else if (kind == "sphere_cap") {
    mesh.radius = options.positive_real("mesh-radius");
    mesh.cap_angle = options.positive_real("mesh-cap-angle");
    mesh.rings = count_option(options, "mesh-rings", 1);
  } else if (kind == "tube_panels") {
    mesh.width = options.positive_real("mesh-width");
    mesh.height = options.positive_real("mesh-height");
    mesh.nx = count_option(options, "mesh-nx", 1);
    mesh.ny = count_option(options, "mesh-ny", 1);
    mesh.nx_front = count_option(options, "mesh-nx-front", 1, "mesh-nx");
    mesh.ny_front = count_option(options, "mesh-ny-front", 1, "mesh-ny");
    mesh.gap = options.nonnegative_real("mesh-gap");
  } else if (kind == "obj") {
    if (!options.is_set("mesh-file")) throw InputError("mesh obj needs --mesh-file FILE.obj");
    mesh.file = options.text("mesh-file");
  } else {
    throw InputError("option --mesh: unknown kind '" + kind +
                     "' (rectangle, disk, annulus, cylinder_band, sphere_cap, tube_panels, obj)");
  }
}

// The triangles the generated mesh will have, before refinement (0 for a
// mesh read from a file or made of panels), computed without building it.
double generated_triangles(const MeshCase& mesh) {
  if (mesh.kind == "rectangle") return 2.0 * mesh.nx * mesh.ny;
  if (mesh.kind == "disk" || mesh.kind == "sphere_cap") return 6.0 * mesh.rings * mesh.rings;
  if (mesh.kind == "cylinder_band") return 2.0 * mesh.segments * mesh.rows;
  if (mesh.kind == "annulus") return 2.0 * mesh.rings * mesh.segments;
  return 0.0;
}

// Moves the boundary vertices of a disk of `radius` centred at the origin
// radially onto its circle, in position and in every corner's uv (disk: uv = x, y).
void snap_to_circle(TriangleMesh& cloth, double radius) {
  std::vector<bool> boundary(cloth.vertex_count(), false);
  for (int v : boundary_vertices(cloth)) {
    boundary[std::size_t(v)] = true;
    Eigen::Vector3d& p = cloth.positions[std::size_t(v)];
    const double r = std::hypot(p.x(), p.y());
    if (r > 0.0) p.head<2>() *= radius / r;
  }
  for (std::size_t t = 0; t < cloth.triangle_count(); ++t) {
    for (std::size_t c = 0; c < 3; ++c) {
      if (!boundary[std::size_t(cloth.triangles[t][c])]) continue;
      Eigen::Vector2d& uv = cloth.material_uv[t][c];
      if (uv.norm() > 0.0) uv *= radius / uv.norm();
    }
  }
}

// The generated (or read) mesh; an annulus comes with its `refinements`
// already made, in its polar parameters, so refined vertices stay on the circles.
TriangleMesh generate(const MeshCase& mesh, int refinements) {
  const std::string& kind = mesh.kind;
  if (kind == "rectangle")
    return mesh::rectangle(mesh.width, mesh.height, mesh.nx, mesh.ny, mesh.pattern);
  if (kind == "disk") return mesh::disk(mesh.radius, mesh.rings);
  if (kind == "annulus") {
    return mesh::annulus(mesh.inner_radius, mesh.radius, mesh.rings, mesh.segments,
                         mesh.angle_from * M_PI / 180.0, mesh.angle_to * M_PI / 180.0, mesh.pattern,
                         refinements, mesh.lift);
  }
  if (kind == "cylinder_band")
    return mesh::cylinder_band(mesh.radius, mesh.height, mesh.segments, mesh.rows);
  if (kind == "sphere_cap") return mesh::sphere_cap(mesh.radius, mesh.cap_angle, mesh.rings);
  if (kind == "tube_panels") return tube_panels_mesh(mesh).mesh;
  return read_obj(mesh.file);
}

} // namespace

MeshCase read_mesh_case(const Options& options, bool generated) {
  MeshCase mesh;
  mesh.kind = generated ? options.text("mesh") : "";
  mesh.refine = count_option(options, "mesh-refine", 0);
  if (generated) read_generator(options, mesh);
  mesh.snap_boundary = options.flag("mesh-snap-boundary");
  if (mesh.snap_boundary && mesh.kind != "disk") {
    throw InputError("option --mesh-snap-boundary applies to --mesh disk only (the mesh is " +
                     mesh.kind + ")");
  }
  if (options.is_set("mesh-waves")) mesh.waves = read_placement_waves(options.text("mesh-waves"));
  mesh.rotate_x = options.real("mesh-rotate-x");
  mesh.translate = option_vector3(options, "mesh-translate");
  return mesh;
}

mesh::PanelMesh tube_panels_mesh(const MeshCase& mesh) {
  return mesh::tube_panels(mesh.width, mesh.height, mesh.nx, mesh.ny, mesh.nx_front, mesh.ny_front,
                           mesh.gap);
}

TriangleMesh build_mesh(const MeshCase& mesh_case, int extra_refinements, int* refinements,
                        const TriangleMesh* given) {
  *refinements = mesh_case.refine + extra_refinements;
  check_mesh_size(generated_triangles(mesh_case), *refinements,
                  "options --mesh-* and --mesh-refine");
  TriangleMesh cloth = given ? *given : generate(mesh_case, *refinements);
  check_mesh_size(double(cloth.triangle_count()), *refinements, "option --mesh-refine");
  const bool refined_by_generator = !given && mesh_case.kind == "annulus";
  for (int level = refined_by_generator ? 0 : *refinements; level > 0; --level) {
    cloth = mesh::refine(cloth);
    if (mesh_case.snap_boundary) snap_to_circle(cloth, mesh_case.radius);
  }
  if (mesh_case.waves) apply_placement_waves(*mesh_case.waves, cloth);
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(mesh_case.rotate_x * M_PI / 180.0, Eigen::Vector3d::UnitX())
          .toRotationMatrix();
  for (auto& p : cloth.positions)
    p = rotation * p + mesh_case.translate;
  return cloth;
}

void apply_placement_waves(const PlacementWaves& waves, TriangleMesh& mesh) {
  double outer = 0.0;
  for (const auto& p : mesh.positions)
    outer = std::max(outer, std::hypot(p.x(), p.y()));
  if (!(outer > waves.start_radius)) {
    throw InputError(
        "option --mesh-waves: the waves start at radius " + std::to_string(waves.start_radius) +
        " m, beyond the mesh's outer radius " + std::to_string(outer) +
        " m (expected N,AMPLITUDE,RADIUS, e.g. 8,0.002,0.09), got '" + waves.text + "'");
  }
  for (auto& p : mesh.positions) {
    const double r = std::hypot(p.x(), p.y());
    if (r <= waves.start_radius) continue;
    const double s = (r - waves.start_radius) / (outer - waves.start_radius);
    p.z() += waves.amplitude * s * s * std::cos(waves.count * std::atan2(p.y(), p.x()));
  }
}

} // namespace sartor
