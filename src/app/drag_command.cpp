// sartor drag: scripted surface drags with pushpins on a garment already on
// a body (Igarashi & Hughes 2002; garment/surface_drag.hpp).

#include "app/commands.hpp"
#include "app/wrap_support.hpp"
#include "common/error.hpp"
#include "common/output.hpp"
#include "contact/body_spec.hpp"
#include "fem/petsc_call.hpp"
#include "garment/surface_drag.hpp"
#include "garment/wrap.hpp"
#include "mesh/obj.hpp"

#include <nlohmann/json.hpp>
#include <petscsys.h>

#include <algorithm>
#include <optional>

namespace sartor {

namespace {

nlohmann::json point_json(const Eigen::Vector3d& p) {
  return {p.x(), p.y(), p.z()};
}

// One scripted drag on the cloth, and what it did.
// With `subdivision`, edges split and merge after every drag step; the
// dependency graph follows the garment's own (base) edges.
nlohmann::json run_drag(garment::ClothOnBody& cloth, const garment::ScriptedDrag& scripted,
                        const garment::DragOptions& options,
                        garment::AdaptiveSubdivision* subdivision) {
  const std::vector<Eigen::Vector3d> start = cloth.positions();
  const garment::RestEdges* base_edges = subdivision ? &subdivision->base_edges() : nullptr;
  garment::SurfaceDrag drag(cloth, scripted.vertex, scripted.pins, options, base_edges);
  Eigen::Vector3d requested = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& step : scripted.steps) {
    requested += step;
    drag.step(step);
    if (subdivision) subdivision->update(cloth);
  }
  drag.release();
  const auto& x = cloth.positions();
  double pin_motion = 0.0, largest_motion = 0.0;
  for (int pin : scripted.pins)
    pin_motion = std::max(pin_motion, (x[std::size_t(pin)] - start[std::size_t(pin)]).norm());
  // Over the garment's own vertices (the first ones when it is subdivided).
  const std::size_t own = base_edges ? base_edges->neighbours.size() : x.size();
  for (std::size_t v = 0; v < own; ++v)
    largest_motion = std::max(largest_motion, (x[v] - start[v]).norm());
  const std::size_t grabbed = std::size_t(scripted.vertex);
  std::size_t attenuated = 0;
  for (double ratio : drag.ratios())
    attenuated += ratio < 1.0 ? 1 : 0;
  return {{"vertex", scripted.vertex},
          {"pins", scripted.pins},
          {"steps", scripted.steps.size()},
          {"requested_displacement_m", point_json(requested)},
          {"start_m", point_json(start[grabbed])},
          {"end_m", point_json(x[grabbed])},
          {"vertex_displacement_m", point_json(x[grabbed] - start[grabbed])},
          {"largest_vertex_motion_m", largest_motion},
          {"pin_motion_max_m", pin_motion},
          {"graph_vertices", drag.graph().order.size()},
          {"attenuated_vertices", attenuated}};
}

} // namespace

const CommandSpec& drag_command() {
  static const CommandSpec spec{
      "drag",
      "drag a garment on a body along its surface, with pushpins (Igarashi & Hughes 2002)",
      "sartor drag GARMENT.obj DRAGS.yaml [--output DIR] [--offset M] [--subdivide] [--no-bones] "
      "[--no-plot]",
      "Reads a garment placed on a body (the wrapped.obj of `sartor wrap`, or the\n"
      "final.obj of a drape: an OBJ with vt = material (u, v)) and a drag script\n"
      "(the body, then drags: a vertex, a list of displacements, pushpins). Each\n"
      "displacement moves the grabbed vertex along the body's tangent plane; the\n"
      "motion spreads over the cloth through the dependency graph of the paper\n"
      "(parents by distance along rest lengths, carried between the vertices'\n"
      "local body frames), attenuated towards each pushpin by the paper's ratio;\n"
      "a relaxation step follows (pins and the grabbed vertex held).\n"
      "docs/wrapping.md has the script format and measured runs.\n\n"
      "Output in DIR: dragged.obj (the garment after the drags), drag.json (per\n"
      "drag: requested and achieved displacement of the grabbed vertex, the pins'\n"
      "motion; edge length ratios, smallest body distance, CPU time),\n"
      "body_points.csv and drag.png (postproc/plot_wrap.py; not with --no-plot).\n\n"
      "examples:\n"
      "  sartor drag out/wrap/wrapped.obj cases/wrap/sleeve_drags.yaml --output out/drag",
      [] {
        std::vector<OptionSpec> options{
            {"output", "DIR", "out/drag", "output folder (created; files in it are replaced)"},
            {"subdivide", "", "",
             "split the edges that cut into the body after every drag step, merge them back "
             "when they no longer do (one level of sqrt(3) subdivision)"},
            {"no-plot", "", "", "write data only, no PNG"}};
        for (const OptionSpec& option : relax_option_specs())
          options.push_back(option);
        return options;
      }(),
      2};
  return spec;
}

int run_drag(const Invocation& invocation) {
  const Options& options = invocation.options;
  const std::string garment_path = invocation.command_line.positionals.at(0);
  const std::string script_path = invocation.command_line.positionals.at(1);
  const TriangleMesh garment = read_obj(garment_path);
  const garment::DragScript script = garment::read_drag_script(script_path, garment.positions);
  const contact::Body body = contact::parse_body(script.body, script_path + ": body", "body");
  const garment::BodyAtRest shape(body);
  garment::ClothOnBody cloth(garment, shape, relax_parameters(options));
  cloth.bones = relaxation_bones(options, script.body, body, script_path + ": body");

  const double cpu_started = process_cpu_seconds();
  nlohmann::json drags = nlohmann::json::array();
  std::optional<garment::AdaptiveSubdivision> subdivision;
  if (options.flag("subdivide")) subdivision.emplace(cloth.mesh());
  for (const garment::ScriptedDrag& scripted : script.drags)
    drags.push_back(
        run_drag(cloth, scripted, script.options, subdivision ? &*subdivision : nullptr));
  const double drag_cpu = process_cpu_seconds() - cpu_started;

  const garment::EdgeRatios ratios = garment::edge_length_ratios(cloth.edges(), cloth.positions());
  const double closest = garment::min_body_distance(shape, cloth.positions());
  const std::string directory = options.text("output");
  if (is_root()) {
    make_output_directory(directory);
    TriangleMesh dragged = cloth.mesh();
    write_obj(directory + "/dragged.obj", dragged, {},
              "Sartor drag: " + garment_path + " by " + script_path);
    nlohmann::json summary = run_metadata(invocation, "drag");
    summary["garment"] = garment_path;
    summary["script"] = script_path;
    summary["body"] = body.describe();
    summary["drags"] = drags;
    summary["bones"] = bones_summary(cloth.bones, cloth.bone_holds());
    if (subdivision)
      summary["subdivision"] = {{"split_edges", subdivision->split_edges()},
                                {"splits", subdivision->splits()},
                                {"merges", subdivision->merges()}};
    summary["min_body_distance_m"] = closest;
    summary["edge_length_ratio"] = {
        {"min", ratios.min}, {"max", ratios.max}, {"mean", ratios.mean}};
    summary["timing_s"] = {{"drag_cpu", drag_cpu}};
    write_json(directory + "/drag.json", summary);
    write_body_samples(directory + "/body_points.csv", shape, dragged.positions, 0.015);
  }
  for (const nlohmann::json& drag : drags) {
    SartorPetscCall(PetscPrintf(
        PETSC_COMM_WORLD,
        "sartor drag: vertex %d: %zu steps, requested %s m, moved %s m; pins moved at most "
        "%.2e m\n",
        drag["vertex"].get<int>(), drag["steps"].get<std::size_t>(),
        drag["requested_displacement_m"].dump().c_str(),
        drag["vertex_displacement_m"].dump().c_str(), drag["pin_motion_max_m"].get<double>()));
  }
  SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD,
                              "sartor drag: %.3f s CPU; closest vertex %.2e m above the body; "
                              "edge length / rest in [%.3f, %.3f]; wrote %s\n",
                              drag_cpu, closest, ratios.min, ratios.max, directory.c_str()));
  if (!options.flag("no-plot")) make_plot("plot_wrap.py", directory);
  return 0;
}

} // namespace sartor
