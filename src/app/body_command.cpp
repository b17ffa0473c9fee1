// sartor body: checks and describes a rigid body (the built-in mannequin or a
// closed triangle mesh from an OBJ file), and writes it with its skeleton.

#include "app/commands.hpp"
#include "common/error.hpp"
#include "common/output.hpp"
#include "contact/body_files.hpp"
#include "contact/body_obj.hpp"
#include "contact/body_spec.hpp"
#include "contact/mannequin.hpp"
#include "contact/mesh_shape.hpp"
#include "fem/petsc_call.hpp"

#include <nlohmann/json.hpp>
#include <petscsys.h>

#include <chrono>
#include <cmath>
#include <sstream>

namespace sartor {

const CommandSpec& body_command() {
  static const CommandSpec spec{
      "body",
      "check and describe a body: the mannequin (sized, posed) or a closed OBJ mesh",
      "sartor body [--body default|FILE.obj|SPEC] [--measurements FILE.json] [--pose POSE] "
      "[--output DIR]",
      "Loads a rigid body as the contact code does and reports what it is. The\n"
      "default is Sartor's built-in mannequin (1.75 m, standing, arms 45 degrees\n"
      "away from the torso, facing -y, feet on z = 0), generated procedurally with\n"
      "its skeleton; --measurements sizes it to a measurement set (FreeSewing's\n"
      "names, mm) and --pose bends its joints. A FILE.obj body must be a closed,\n"
      "2-manifold, consistently and outward-oriented triangle mesh; anything else\n"
      "is an error naming the file, the line and the problem. A SPEC is a body\n"
      "with a skeleton as construct and drape take it: \"mannequin\n"
      "measurements=FILE.json pose=knee_l:90\" or \"mesh file=BODY.obj\n"
      "skeleton=SKELETON.json\".\n\n"
      "Output in DIR: body.obj (v and f lines), skeleton.json (bodies with one),\n"
      "summary.json (size, bounding box, area, volume, topology, timings; for a\n"
      "sized mannequin the measurements asked for and taken on it) and body.png\n"
      "(postproc/plot_body.py). Formats: docs/bodies.md.\n\n"
      "examples:\n"
      "  sartor body\n"
      "  sartor body --measurements me.json --pose knee_l:90,hip_l:45 --output out/me\n"
      "  sartor body --body scan.obj --output out/scan",
      {
          {"body", "SPEC", "default",
           "default (the built-in mannequin), FILE.obj, or a body with a skeleton "
           "(\"mannequin measurements=FILE.json pose=...\", \"mesh file=BODY.obj "
           "skeleton=SKELETON.json\")"},
          {"measurements", "FILE", "",
           "size the mannequin to this measurement set (JSON, mm, FreeSewing's names)"},
          {"pose", "POSE", "", "bend the mannequin's joints: JOINT:DEG,... (e.g. knee_l:90)"},
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

// What the sized mannequin was asked for and what it measures, with the
// measurements the file left to the default and those it does not use.
nlohmann::json mannequin_summary(const std::string& spec) {
  nlohmann::json result;
  std::istringstream words(spec);
  std::string word;
  while (words >> word) {
    if (word.rfind("pose=", 0) == 0) result["pose"] = word.substr(5);
    if (word.rfind("measurements=", 0) != 0) continue;
    const std::string path = word.substr(13);
    const MeasurementFile file = read_measurement_file(path);
    const MannequinModel model(file.measurements);
    result["measurement_file"] = path;
    result["measurement_set"] = file.name;
    result["defaulted"] = file.defaulted;
    result["unused"] = file.unused;
    for (const MeasurementUse& use : mannequin_measurements()) {
      const double asked = model.requested().at(use.name);
      const double taken = model.achieved().at(use.name);
      result["measurements_mm"][use.name] = {{"requested", asked},
                                             {"achieved", taken},
                                             {"error_percent", 100.0 * (taken / asked - 1.0)}};
    }
    if (!file.defaulted.empty()) {
      std::string names;
      for (const std::string& name : file.defaulted)
        names += (names.empty() ? "" : ", ") + name;
      SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD,
                                  "sartor body: %s lacks %s: the default mannequin's values\n",
                                  path.c_str(), names.c_str()));
    }
  }
  return result;
}

} // namespace

int run_body(const Invocation& invocation) {
  const Options& options = invocation.options;
  const auto started = std::chrono::steady_clock::now();
  std::string spec = options.text("body");
  if (options.is_set("measurements") || options.is_set("pose")) {
    if (spec != "default" && spec.rfind("mannequin", 0) != 0)
      throw InputError("options --measurements and --pose size and pose the mannequin, not '" +
                       spec + "'");
    spec = spec == "default" ? "mannequin" : spec;
    if (options.is_set("measurements")) spec += " measurements=" + options.text("measurements");
    if (options.is_set("pose")) spec += " pose=" + options.text("pose");
  }
  const bool is_file = spec != "default" && spec.find(' ') == std::string::npos &&
                       spec != "mannequin" && spec.rfind("mesh", 0) != 0;
  const bool is_mannequin = spec == "default" || spec.rfind("mannequin", 0) == 0;

  BodyMesh mesh;
  std::vector<Bone> skeleton;
  std::string source = "file " + spec;
  const auto load_started = std::chrono::steady_clock::now();
  if (is_file) {
    mesh = read_body_obj(spec);
  } else {
    contact::GarmentBody body = contact::garment_body(spec, "option --body");
    mesh = std::move(body.mannequin.mesh);
    skeleton = std::move(body.mannequin.skeleton);
    source = body.source;
  }
  const double load_seconds = seconds_since(load_started);
  const BodyMeasures measures = measure_body(mesh);

  const auto tree_started = std::chrono::steady_clock::now();
  const std::unique_ptr<contact::Shape> shape =
      contact::make_mesh_shape(mesh.vertices, mesh.faces, is_mannequin ? "mannequin" : source);
  const double tree_seconds = seconds_since(tree_started);
  const double query_microseconds = mean_query_microseconds(*shape, mesh);

  const std::string directory = options.text("output");
  if (is_root()) make_output_directory(directory);
  if (is_root()) {
    write_body_obj(directory + "/body.obj", mesh,
                   {"Sartor body: " + source,
                    std::to_string(measures.used_vertices) + " vertices, " +
                        std::to_string(mesh.faces.size()) +
                        " triangles, metres, faces counter-clockwise seen from outside"});
    if (!skeleton.empty()) write_json(directory + "/skeleton.json", skeleton_json(skeleton));
  }

  nlohmann::json summary = run_metadata(invocation, "body");
  summary["body"] = {
      {"source", source},
      {"kind", is_mannequin ? "mannequin" : "file"},
      {"obj", "body.obj"},
      {"skeleton", skeleton.empty() ? nlohmann::json() : nlohmann::json("skeleton.json")},
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
  if (options.is_set("measurements") || spec.find("measurements=") != std::string::npos ||
      spec.find("pose=") != std::string::npos)
    summary["mannequin"] = mannequin_summary(spec);
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
