// sartor body: checks and describes a rigid body (the built-in mannequin or a
// closed triangle mesh from an OBJ file), and writes it with its skeleton.

#include "common/error.hpp"
#include "common/output.hpp"
#include "contact/mesh_shape.hpp"
#include "fem/petsc_call.hpp"
#include "mesh/body_obj.hpp"
#include "mesh/mannequin.hpp"
#include "solvers/commands.hpp"

#include <nlohmann/json.hpp>
#include <petscsys.h>

#include <chrono>
#include <cmath>

namespace sartor {

const CommandSpec& body_command() {
  static const CommandSpec spec{
      "body",
      "check and describe a body: the built-in mannequin or a closed OBJ mesh",
      "sartor body [--body default|FILE.obj] [--output DIR]",
      "Loads a rigid body as the contact code does and reports what it is. The\n"
      "default is Sartor's built-in mannequin (1.75 m, standing, arms 27 degrees\n"
      "away from the torso, facing -y, feet on z = 0), generated procedurally with\n"
      "its skeleton. A FILE.obj body must be a closed, 2-manifold, consistently\n"
      "and outward-oriented triangle mesh; anything else is an error naming the\n"
      "file, the line and the problem.\n\n"
      "Output in DIR: body.obj (v and f lines), skeleton.json (mannequin only),\n"
      "summary.json (size, bounding box, area, volume, topology, timings) and\n"
      "body.png (postproc/plot_body.py). Formats: docs/bodies.md.\n\n"
      "examples:\n"
      "  sartor body\n"
      "  sartor body --body scan.obj --output out/scan",
      {
          {"body", "SPEC", "default", "default (the built-in mannequin) or FILE.obj"},
          {"output", "DIR", "out/body", "output folder (created; files in it are replaced)"},
          {"no-plot", "", "", "write data only, no PNG"},
      },
      0};
  return spec;
}

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

nlohmann::json vector_json(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

nlohmann::json skeleton_json(const std::vector<Bone>& bones) {
  nlohmann::json list = nlohmann::json::array();
  for (const Bone& bone : bones) {
    list.push_back(
        {{"name", bone.name},
         {"parent", bone.parent.empty() ? nlohmann::json() : nlohmann::json(bone.parent)},
         {"start", vector_json(bone.start)},
         {"end", vector_json(bone.end)},
         {"start_radius", bone.start_radius},
         {"end_radius", bone.end_radius}});
  }
  return {{"format", "sartor-skeleton"},
          {"version", 1},
          {"units", "m"},
          {"frame", {{"up", "+z"}, {"front", "-y"}, {"left", "+x"}, {"floor_z", 0.0}}},
          {"bones", list}};
}

// Mean time of a signed-distance query at points within 2 cm of the surface
// (near vertices, as cloth in contact is), in microseconds.
double mean_query_microseconds(const contact::Shape& shape, const BodyMesh& mesh) {
  const std::size_t samples = 20000;
  double checksum = 0.0;
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < samples; ++i) {
    const Eigen::Vector3d& v = mesh.vertices[(i * 7919) % mesh.vertices.size()];
    const double phase = static_cast<double>(i);
    const Eigen::Vector3d offset(std::sin(phase), std::cos(1.3 * phase), std::sin(0.7 * phase));
    checksum += shape.query(v + 0.02 * offset).distance;
  }
  const double elapsed = seconds_since(start);
  return std::isfinite(checksum) ? 1e6 * elapsed / static_cast<double>(samples) : NAN;
}

} // namespace

int run_body(const Invocation& invocation) {
  const Options& options = invocation.options;
  const auto started = std::chrono::steady_clock::now();
  const std::string spec = options.text("body");
  const bool is_mannequin = spec == "default";

  BodyMesh mesh;
  std::vector<Bone> skeleton;
  const auto load_started = std::chrono::steady_clock::now();
  if (is_mannequin) {
    const Mannequin& mannequin = default_mannequin();
    mesh = mannequin.mesh;
    skeleton = mannequin.skeleton;
  } else {
    mesh = read_body_obj(spec);
  }
  const double load_seconds = seconds_since(load_started);
  const BodyMeasures measures = measure_body(mesh);

  const auto tree_started = std::chrono::steady_clock::now();
  const std::unique_ptr<contact::Shape> shape =
      contact::make_mesh_shape(mesh.vertices, mesh.faces, is_mannequin ? "mannequin" : spec);
  const double tree_seconds = seconds_since(tree_started);
  const double query_microseconds = mean_query_microseconds(*shape, mesh);

  const std::string directory = options.text("output");
  if (is_root()) make_output_directory(directory);
  const std::string source =
      is_mannequin ? "built-in mannequin, generated procedurally by Sartor" : "file " + spec;
  if (is_root()) {
    write_body_obj(directory + "/body.obj", mesh,
                   {"Sartor body: " + source,
                    std::to_string(measures.used_vertices) + " vertices, " +
                        std::to_string(mesh.faces.size()) +
                        " triangles, metres, faces counter-clockwise seen from outside"});
    if (is_mannequin) write_json(directory + "/skeleton.json", skeleton_json(skeleton));
  }

  nlohmann::json summary = run_metadata(invocation, "body");
  summary["body"] = {
      {"source", source},
      {"kind", is_mannequin ? "mannequin" : "file"},
      {"obj", "body.obj"},
      {"skeleton", is_mannequin ? nlohmann::json("skeleton.json") : nlohmann::json()},
      {"describe", shape->describe()},
      {"vertices", measures.used_vertices},
      {"triangles", mesh.faces.size()},
      {"edges", measures.edges},
      {"height_m", measures.upper.z() - measures.lower.z()},
      {"bounding_box_m",
       {{"lower", vector_json(measures.lower)}, {"upper", vector_json(measures.upper)}}},
      {"area_m2", measures.area},
      {"volume_m3", measures.volume},
      {"closed", true},
      {"manifold", true},
      {"outward_oriented", true},
      {"components", measures.components},
      {"euler_characteristic", measures.euler_characteristic},
      {"genus", measures.components == 1 ? nlohmann::json((2 - measures.euler_characteristic) / 2)
                                         : nlohmann::json()},
      {"shortest_edge_m", measures.shortest_edge},
      {"longest_edge_m", measures.longest_edge},
      {"smallest_angle_deg", measures.smallest_angle_deg},
  };
  summary["timings"] = {{"load_or_generate_s", load_seconds},
                        {"aabb_tree_build_s", tree_seconds},
                        {"query_mean_us", query_microseconds}};
  summary["wall_time_s"] = seconds_since(started);
  if (is_root()) write_json(directory + "/summary.json", summary);
  if (!options.flag("no-plot")) make_plot("plot_body.py", directory);
  SartorPetscCall(PetscPrintf(
      PETSC_COMM_WORLD,
      "sartor body: %s: %zu triangles, height %.4f m, volume %.5f m^3, closed 2-manifold "
      "(%zu component%s, Euler characteristic %ld)\nsartor body: wrote %s\n",
      source.c_str(), mesh.faces.size(), measures.upper.z() - measures.lower.z(), measures.volume,
      measures.components, measures.components == 1 ? "" : "s", measures.euler_characteristic,
      directory.c_str()));
  return 0;
}

} // namespace sartor
