// sartor wrap: a pattern put on a body by marks (Igarashi & Hughes 2002;
// garment/wrap.hpp), written as a placed garment and, with --drape, handed
// to the case pipeline of `sartor run` to drape from there.

#include "app/cloth_case.hpp"
#include "app/commands.hpp"
#include "app/wrap_support.hpp"
#include "common/error.hpp"
#include "common/output.hpp"
#include "contact/body_spec.hpp"
#include "fem/petsc_call.hpp"
#include "fem/petsc_options.hpp"
#include "garment/wrap.hpp"
#include "mesh/obj.hpp"

#include <nlohmann/json.hpp>
#include <petscsys.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <optional>

namespace sartor {

namespace {

// Wrap's own options; --drape also takes every option of `sartor run`.
std::vector<OptionSpec> wrap_option_specs() {
  std::vector<OptionSpec> options{
      {"output", "DIR", "out/wrap", "output folder (created; files in it are replaced)"},
      {"edge-length", "M", "0.03", "m: the longest triangle edge of the panels' meshes"},
      {"min-angle", "DEG", "25", "smallest triangle angle of the panels' meshes, degrees"},
      {"growth-relax-steps", "N", "1", "relaxation steps after each vertex the growth maps"},
      {"relax-steps", "N", "100", "relaxation steps of the whole garment after the growth"},
      {"subdivide", "", "",
       "split the edges that cut into the body during the final relaxation, merge them back "
       "when they no longer do (one level of sqrt(3) subdivision)"},
      {"drape", "", "", "then drape the wrapped garment as `sartor run` would (into DIR/drape)"},
      {"rewrap", "GARMENT.obj", "",
       "rewrap this garment (wrapped from the same pattern, seams and --edge-length): "
       "cloth as far from the marks as the marks file's nearest pin stays"},
      {"no-plot", "", "", "write data only, no PNG"},
  };
  for (const OptionSpec& option : relax_option_specs())
    options.push_back(option);
  return options;
}

// The defaults --drape changes in `sartor run`'s options: the material of
// `sartor drape`, and its static minimiser with edge samples (certified
// from the wrapped sleeve in 411 Newton iterations, although the relaxation
// leaves edges up to 30 % long and a first residual of 635 N for a weight
// of 0.3 N), or with --analysis dynamic its dynamics (a fall with kinetic
// damping, then the static settle; converged, but with 50 edges through
// the arm, no edge samples).
std::map<std::string, std::string> wrap_drape_defaults(bool dynamic) {
  std::map<std::string, std::string> defaults{{"density", "0.25"},
                                              {"bending-stiffness", "1.5e-5"},
                                              {"bending-model", "discrete_shell"},
                                              {"contact-stiffness-factor", "5"},
                                              {"membrane-psd", "true"},
                                              {"bending-psd", "true"}};
  if (dynamic) {
    defaults.insert({{"analysis", "dynamic"},
                     {"time-end", "0.5"},
                     {"time-step", "0.01"},
                     {"output-interval", "0.1"},
                     {"kinetic-damping", "true"},
                     {"settle", "true"}});
  } else {
    defaults.insert({"contact-edge-spacing", "0.015"});
  }
  return defaults;
}

// Options of `sartor run` that wrapping answers itself: the mesh and its
// placement (the wrapped garment), its seams (merged) and the body (the
// marks file's).
bool describes_wrapped_garment(const std::string& name) {
  const bool mesh = name.rfind("mesh", 0) == 0 && name != "mesh-refine";
  return mesh || name == "contact-body" || name == "seam-file";
}

nlohmann::json point_json(const Eigen::Vector3d& p) {
  return {p.x(), p.y(), p.z()};
}

// Drapes the wrapped garment: its panels' fabrics, the marks file's body.
void drape_wrapped(const Invocation& invocation, const garment::WrapResult& wrapped,
                   const garment::Pattern& pattern, const std::string& body,
                   const std::string& directory) {
  Invocation drape = invocation;
  Options& options = drape.options;
  options.set_default("body", body);
  const bool dynamic = options.is_set("analysis") && options.text("analysis") == "dynamic";
  for (const auto& [name, value] : wrap_drape_defaults(dynamic))
    options.set_default(name, value);
  // The drape's cap: a wrapped garment's first stage crawls for a few hundred.
  if (!dynamic) SartorPetscCall(set_default_option("-snes_max_it", "1000"));
  CaseCloth cloth;
  cloth.mesh = wrapped.mesh;
  ClothOutputLabels labels{{}, {}, wrapped.mesh.material_ids};
  for (const garment::Panel& panel : pattern.panels)
    labels.panels.push_back(panel.id);
  assign_panel_fabrics(pattern.panels, &cloth);
  name_single_fabric(cloth, &options);
  labels.fabrics = cloth.fabrics;
  const CaseResult result = solve_case(read_cloth_case(options, false), 0, {}, {}, &cloth);
  const std::string drape_directory = directory + "/drape";
  if (is_root()) make_output_directory(drape_directory);
  nlohmann::json summary = run_metadata(drape, "wrap");
  add_case_summary(result, summary);
  write_case_results(drape_directory, result, summary, labels);
  write_petsc_options(drape_directory, options);
  SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD, "sartor wrap: drape %s in %.1f s (%s); wrote %s\n",
                              result.converged ? "converged" : "did not converge",
                              result.solve_seconds, result.dynamics ? "dynamics" : "statics",
                              drape_directory.c_str()));
  if (!result.converged)
    throw SolveFailure("the drape of the wrapped garment did not converge; " + drape_directory +
                       " holds the last state");
}

nlohmann::json wrap_summary(const Invocation& invocation, const garment::WrapResult& result,
                            const std::vector<garment::MarkPair>& pairs, const contact::Shape& body,
                            double wrap_cpu, double wrap_wall) {
  const Options& options = invocation.options;
  nlohmann::json summary = run_metadata(invocation, "wrap");
  summary["pattern"] = invocation.command_line.positionals.at(0);
  summary["marks"] = invocation.command_line.positionals.at(1);
  summary["body"] = body.describe();
  summary["mesh"] = {{"vertices", result.mesh.vertex_count()},
                     {"triangles", result.mesh.triangle_count()},
                     {"edge_length_m", options.positive_real("edge-length")},
                     {"obj", "wrapped.obj"}};
  summary["root_vertices"] = result.root_vertices;
  summary["split_edges"] = result.split_edges;
  summary["subdivision"] = {{"splits", result.splits}, {"merges", result.merges}};
  summary["mark_mismatch_m"] = {{"max", result.mismatch.max},
                                {"rms", result.mismatch.rms},
                                {"crossings", result.mismatch.crossings}};
  summary["min_body_distance_m"] = result.min_distance;
  summary["offset_m"] = options.nonnegative_real("offset");
  summary["edge_length_ratio"] = {{"min", result.edge_ratios.min},
                                  {"max", result.edge_ratios.max},
                                  {"mean", result.edge_ratios.mean}};
  summary["timing_s"] = {{"wrap_cpu", wrap_cpu}, {"wrap_wall", wrap_wall}};
  // For the picture: the body marks and the cloth's mark points.
  nlohmann::json marks = nlohmann::json::array();
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    nlohmann::json on_body = nlohmann::json::array(), on_cloth = nlohmann::json::array();
    for (const Eigen::Vector3d& p : pairs[k].body)
      on_body.push_back(point_json(p));
    for (const garment::MarkCrossing& crossing : result.crossings) {
      if (crossing.pair != int(k)) continue;
      on_cloth.push_back(
          point_json((1.0 - crossing.along_edge) * result.mesh.positions[std::size_t(crossing.a)] +
                     crossing.along_edge * result.mesh.positions[std::size_t(crossing.b)]));
    }
    marks.push_back({{"id", pairs[k].id}, {"body", on_body}, {"cloth", on_cloth}});
  }
  summary["mark_pairs"] = marks;
  return summary;
}

} // namespace

const CommandSpec& wrap_command() {
  static const CommandSpec spec{
      "wrap",
      "put a pattern on a body by marks on both (Igarashi & Hughes 2002)",
      "sartor wrap PATTERN.json MARKS.json [--output DIR] [--edge-length M] [--offset M] "
      "[--drape [any option of sartor run]] [--no-plot]",
      "Meshes the pattern's panels, sews the lines the marks file pairs (and the\n"
      "pattern's stitches) into one mesh, and puts it on the marks file's body so\n"
      "that each cloth mark lands on its body mark: the edges crossing the marks are\n"
      "pasted first (proportional correspondence along each mark pair), then the\n"
      "mesh grows from them in order of mesh distance, each new vertex placed from\n"
      "its mapped neighbour triangles, with a relaxation step after each (edge\n"
      "lengths towards rest, unflipping, flattening, gravity with friction) and\n"
      "--relax-steps at the end; vertices stay --offset above the body. Cloth marks\n"
      "are polylines in panel coordinates (in the marks file or the pattern's\n"
      "\"marks\"); body marks are 3D polylines taken onto the body surface. The\n"
      "front of a panel (its outline counter-clockwise) faces away from the body.\n"
      "--drape then drapes the wrapped garment with the case pipeline of `sartor\n"
      "run`: its options below apply (only with --drape), except those of the mesh,\n"
      "the seams file and --body (the marks file's body); drape's material and\n"
      "static minimiser (with edge samples) are the defaults, --analysis dynamic\n"
      "falls in time (kinetic damping, settle) instead.\n"
      "--rewrap GARMENT.obj wraps a garment already on the body again by new marks:\n"
      "the marks file's \"pins\" keep every vertex at least as far from the marks\n"
      "as the nearest pin where it is (all of it is rewrapped without pins).\n"
      "docs/wrapping.md has the formats, the algorithm and measured runs.\n\n"
      "Output in DIR: wrapped.obj (the wrapped garment; vt = material (u, v), a\n"
      "group per panel), wrap.json (mark mismatch, smallest body distance, edge\n"
      "length ratios, CPU time), body_points.csv (body surface samples near the\n"
      "garment) and wrap.png (postproc/plot_wrap.py; not with --no-plot); with\n"
      "--drape, DIR/drape holds what `sartor run` writes.\n\n"
      "examples:\n"
      "  sartor wrap cases/wrap/sleeve.json cases/wrap/sleeve_marks.json\n"
      "  sartor wrap cases/wrap/tube.json cases/wrap/tube_marks.json --output out/wrap/tube",
      [] {
        std::vector<OptionSpec> options = wrap_option_specs();
        for (OptionSpec option : case_option_specs()) {
          const bool own = std::any_of(options.begin(), options.end(),
                                       [&](const OptionSpec& o) { return o.name == option.name; });
          // Their help keeps its own scoping ("dynamic: ..."), which the
          // options' checks read; the description says they need --drape.
          if (own) continue;
          // The pipeline reads them, so they stay declared.
          if (describes_wrapped_garment(option.name)) {
            // The placement's defaults are read (as no move); the rest not.
            if (option.name != "mesh-rotate-x" && option.name != "mesh-translate")
              option.fallback.clear();
            option.help = "sartor run only: the wrapped garment and the marks file's body";
          }
          options.push_back(option);
        }
        return options;
      }(),
      2};
  return spec;
}

int run_wrap(const Invocation& invocation) {
  const Options& options = invocation.options;
  const std::string pattern_path = invocation.command_line.positionals.at(0);
  const std::string marks_path = invocation.command_line.positionals.at(1);
  const bool drape = options.flag("drape");
  const std::vector<OptionSpec> own = wrap_option_specs();
  for (const OptionSpec& option : case_option_specs()) {
    const bool is_own = std::any_of(own.begin(), own.end(),
                                    [&](const OptionSpec& o) { return o.name == option.name; });
    const std::vector<std::string> entries = option_entries(option);
    const auto given = std::find_if(entries.begin(), entries.end(),
                                    [&](const std::string& name) { return options.is_set(name); });
    if (is_own || given == entries.end()) continue;
    const std::string given_as = options.name_given(*given);
    if (describes_wrapped_garment(option.name))
      throw InputError("option --" + given_as +
                       " does not apply to sartor wrap: the wrapped garment is the mesh and the "
                       "marks file gives the body");
    if (!drape)
      throw InputError("option --" + given_as + " applies to the drape only: add --drape");
  }
  std::vector<garment::ClothMark> pattern_marks;
  const garment::Pattern pattern = garment::read_pattern_with_marks(pattern_path, pattern_marks);
  garment::WrapMarks marks = garment::read_marks(marks_path, pattern, pattern_marks);
  const contact::Body body = contact::parse_body(marks.body, marks_path + ": body", "body");
  const garment::BodyAtRest shape(body);
  const double edge_length = options.positive_real("edge-length");
  for (garment::MarkPair& pair : marks.pairs)
    pair.body = garment::body_surface_path(shape, pair.body, std::min(0.005, 0.25 * edge_length));
  const TriangleMesh sewn =
      garment::sew_panels(pattern, marks.seams, edge_length, options.positive_real("min-angle"));
  garment::WrapOptions wrap_options;
  wrap_options.relax = relax_parameters(options);
  wrap_options.growth_relax_steps = int(options.integer_in("growth-relax-steps", 0, 1000));
  wrap_options.final_relax_steps = int(options.integer_in("relax-steps", 0, 1000000));
  wrap_options.subdivide = options.flag("subdivide");
  wrap_options.bones = relaxation_bones(options, marks.body, body, marks_path + ": body");

  std::optional<garment::Rewrap> rewrap;
  if (options.is_set("rewrap")) {
    rewrap = garment::Rewrap{read_obj(options.text("rewrap")).positions, {}};
    for (const garment::PinRef& pin : marks.pins)
      rewrap->pins.push_back(garment::pinned_vertex(pin, rewrap->positions));
  } else if (!marks.pins.empty()) {
    throw InputError(marks_path + ": pins: pushpins limit a rewrap only: add --rewrap GARMENT.obj");
  }

  const double cpu_started = process_cpu_seconds();
  const auto wall_started = std::chrono::steady_clock::now();
  const garment::WrapResult result =
      garment::wrap(sewn, pattern, marks.pairs, shape, wrap_options, rewrap ? &*rewrap : nullptr);
  const double wrap_cpu = process_cpu_seconds() - cpu_started;
  const double wrap_wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_started).count();

  const std::string directory = options.text("output");
  if (is_root()) {
    make_output_directory(directory);
    std::vector<std::string> groups;
    for (int panel : result.mesh.material_ids)
      groups.push_back(pattern.panels[std::size_t(panel)].id);
    write_obj(directory + "/wrapped.obj", result.mesh, groups,
              "Sartor wrap: " + pattern_path + " on " + body.describe() + " by " + marks_path);
    nlohmann::json summary =
        wrap_summary(invocation, result, marks.pairs, shape, wrap_cpu, wrap_wall);
    summary["bones"] = bones_summary(wrap_options.bones, result.bone_holds);
    if (rewrap) {
      double pin_motion = 0.0;
      for (int pin : rewrap->pins)
        pin_motion = std::max(
            pin_motion,
            (result.mesh.positions[std::size_t(pin)] - rewrap->positions[std::size_t(pin)]).norm());
      summary["rewrap"] = {{"garment", options.text("rewrap")},
                           {"pins", rewrap->pins},
                           {"kept_vertices", result.kept_vertices},
                           {"pin_motion_max_m", pin_motion}};
    }
    write_json(directory + "/wrap.json", summary);
    write_body_samples(directory + "/body_points.csv", shape, result.mesh.positions,
                       std::max(0.01, 0.5 * edge_length));
  }
  SartorPetscCall(PetscPrintf(
      PETSC_COMM_WORLD,
      "sartor wrap: %zu vertices, %zu triangles, %d root vertices; wrapped in %.3f s CPU; "
      "mark mismatch max %.2e m (rms %.2e m, %d crossings); closest vertex %.2e m above the "
      "body (offset %.2e m); edge length / rest in [%.3f, %.3f], mean %.3f; %zu bones, %ld "
      "moves held back at them; wrote %s\n",
      result.mesh.vertex_count(), result.mesh.triangle_count(), result.root_vertices, wrap_cpu,
      result.mismatch.max, result.mismatch.rms, result.mismatch.crossings, result.min_distance,
      wrap_options.relax.offset, result.edge_ratios.min, result.edge_ratios.max,
      result.edge_ratios.mean, wrap_options.bones.size(), result.bone_holds, directory.c_str()));
  if (!options.flag("no-plot")) make_plot("plot_wrap.py", directory);
  if (drape) drape_wrapped(invocation, result, pattern, marks.body, directory);
  return 0;
}

} // namespace sartor
