// sartor drape: a garment from its pattern to its drape on the mannequin.
// TAGCON constructs it (app/garment_construction.hpp), and the case
// pipeline of `sartor run` (app/cloth_case.hpp) sews and drapes it: by
// default statically, minimising the total potential with the seams closing
// in continuation stages (solvers/statics.hpp); on request in implicit dynamics
// with kinetic damping and a final static solve.

#include "app/cloth_case.hpp"
#include "app/commands.hpp"
#include "app/drape_outcome.hpp"
#include "app/edit_case.hpp"
#include "app/garment_construction.hpp"
#include "app/progressive_drape.hpp"
#include "app/start_from.hpp"
#include "app/wear_case.hpp"
#include "app/wear_checkpoint.hpp"
#include "common/checksum.hpp"
#include "common/csv.hpp"
#include "common/error.hpp"
#include "common/output.hpp"
#include "contact/body_obj.hpp"
#include "contact/mannequin.hpp"
#include "contact/mesh_shape.hpp"
#include "fem/petsc_call.hpp"
#include "fem/petsc_options.hpp"
#include "mesh/seams.hpp"

#include <nlohmann/json.hpp>
#include <petscsys.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <optional>

namespace sartor {

namespace {

// What drape changes in the options of `sartor run`: defaults for a garment
// on the mannequin (as cases/seams/tube_on_cylinder.yaml drapes).
const std::map<std::string, std::string>& drape_defaults() {
  static const std::map<std::string, std::string> defaults{
      {"body", "mannequin mu=0.3 name=mannequin"},
      {"density", "0.25"},
      {"bending-stiffness", "1.5e-5"},
      // Tight garments press on the body (~100 N on the skirt): a stiffer
      // penalty keeps the vertices within the contact offset.
      {"contact-stiffness-factor", "5"},
  };
  return defaults;
}

// Without --analysis dynamic: edge contact. The static minimiser starts the
// samples outside the body and keeps them there; a dynamic drape starts
// from the placement, whose chords may cut into the body, and the samples'
// penalty there threw the coarse skirt 0.2 m in its first 0.02 s.
const std::map<std::string, std::string>& drape_static_defaults() {
  static const std::map<std::string, std::string> defaults{{"contact-edge-spacing", "0.015"}};
  return defaults;
}

// With --analysis dynamic (the fall in time, on request): the time grid,
// and the hinges: with the patch model the dynamic sewing of the coarse
// skirt took 10 s CPU for its first 0.02 s against 10 s for 0.3 s
// (docs/finite-elements.md#bending); --bending-model patch asks for it.
const std::map<std::string, std::string>& drape_dynamic_defaults() {
  static const std::map<std::string, std::string> defaults{{"time-step", "0.01"},
                                                           {"time-end", "1.5"},
                                                           {"output-interval", "0.1"},
                                                           {"bending-model", "discrete_shell"}};
  return defaults;
}

// Sewing, for a garment with seams. Statics (the default): the seams close
// in eight continuation stages of their stiffness, from a pull of 10 N/m of
// seam (a 2 N T-shirt's seams, about 3 m, pull with 30 N in all) to their
// own stiffness, without friction until the last (docs/drape.md). Dynamics:
// gradual sewing over the first second (docs/seams.md). Sewn at once, the
// T-shirt's shoulder seams dragged the upper panels into the shoulders;
// sewn like this it hangs on them.
const std::map<std::string, std::string>& drape_sewing_defaults(bool dynamic) {
  static const std::map<std::string, std::string> statics{{"sewing-stages", "8"},
                                                          {"sewing-start-tension", "10"}};
  static const std::map<std::string, std::string> dynamics{{"sewing-tension", "10"},
                                                           {"sewing-time", "1"}};
  return dynamic ? dynamics : statics;
}

// Flags drape turns on (a flag's default is off): `-membrane_psd false`
// turns one off. Dynamics also get kinetic damping and the settle.
const std::vector<std::string>& drape_flags(bool dynamic) {
  static const std::vector<std::string> statics{"membrane-psd", "bending-psd"};
  static const std::vector<std::string> dynamics{"kinetic-damping", "settle", "membrane-psd",
                                                 "bending-psd"};
  return dynamic ? dynamics : statics;
}

// Options that only time stepping reads: giving one asks for --analysis dynamic.
const std::vector<std::string>& time_stepping_options() {
  static const std::vector<std::string> names{
      "time-end",        "time-step", "damping",        "kinetic-damping", "rest-tolerance",
      "output-interval", "settle",    "sewing-tension", "sewing-time",     "dynamic-solver"};
  return names;
}

// Options of `sartor run` that describe the mesh: the pattern does (its
// seams too, which --seams-file overrides by line ids, not vertices).
bool is_mesh_option(const std::string& name) {
  return name.rfind("mesh", 0) == 0 && name != "mesh-refine" && name != "mesh-rotate-x" &&
         name != "mesh-translate";
}

// The garment without the panels that no seam attaches (a pattern's panel
// TAGCON found no seam for): nothing would hold them, and
// a free panel makes the static equilibrium singular. A garment without
// seams keeps its panels. Vertices are renumbered, the seams with them.
struct SewableGarment {
  TriangleMesh mesh; // material_ids = panel index
  std::vector<Seam> seams;
  std::vector<std::string> left_out; // panel ids
};

SewableGarment sewable_garment(const ConstructedGarment& constructed) {
  const garment::GarmentMesh& garment = constructed.garment;
  const std::size_t panels = constructed.pattern.panels.size();
  std::vector<int> panel_of_vertex(garment.mesh.vertex_count(), -1);
  for (std::size_t t = 0; t < garment.mesh.triangle_count(); ++t)
    for (int v : garment.mesh.triangles[t])
      panel_of_vertex[std::size_t(v)] = garment.mesh.material_ids[t];
  std::vector<bool> sewn(panels, garment.seams.empty());
  for (const Seam& seam : garment.seams) {
    for (const auto* line : {&seam.a, &seam.b})
      for (int v : *line)
        sewn[std::size_t(panel_of_vertex[std::size_t(v)])] = true;
  }
  SewableGarment kept;
  std::vector<int> new_index(garment.mesh.vertex_count(), -1);
  for (std::size_t v = 0; v < garment.mesh.vertex_count(); ++v) {
    if (!sewn[std::size_t(panel_of_vertex[v])]) continue;
    new_index[v] = int(kept.mesh.positions.size());
    kept.mesh.positions.push_back(garment.mesh.positions[v]);
  }
  for (std::size_t t = 0; t < garment.mesh.triangle_count(); ++t) {
    if (!sewn[std::size_t(garment.mesh.material_ids[t])]) continue;
    std::array<int, 3> triangle{};
    for (std::size_t c = 0; c < 3; ++c)
      triangle[c] = new_index[std::size_t(garment.mesh.triangles[t][c])];
    kept.mesh.triangles.push_back(triangle);
    kept.mesh.material_uv.push_back(garment.mesh.material_uv[t]);
    kept.mesh.material_ids.push_back(garment.mesh.material_ids[t]);
  }
  for (const CreaseEdge& crease : garment.mesh.creases)
    if (new_index[std::size_t(crease.a)] >= 0)
      kept.mesh.creases.push_back({new_index[std::size_t(crease.a)],
                                   new_index[std::size_t(crease.b)], crease.rest_angle,
                                   crease.stiffness_factor});
  for (Seam seam : garment.seams) {
    for (auto* line : {&seam.a, &seam.b})
      for (int& v : *line)
        v = new_index[std::size_t(v)];
    kept.seams.push_back(seam);
  }
  for (std::size_t p = 0; p < panels; ++p)
    if (!sewn[p]) kept.left_out.push_back(constructed.pattern.panels[p].id);
  return kept;
}

// Seams whose springs cross the body at the start: the straight line from a
// vertex of line a to its partner on line b (by position along the lines)
// runs inside the mannequin. Such a spring pulls its cloth into the body in
// the first time steps (contact acts on vertices only); a shallow crossing
// (a chord of the waist) is pushed back out, a deep one (through an arm) is
// not. Per seam with a crossing: the crossing vertex pairs and the deepest
// point of their lines inside the body, m.
struct BodyCrossing {
  int pairs = 0;
  double depth = 0.0;
};

std::map<std::string, BodyCrossing> seams_crossing_body(const SewableGarment& garment,
                                                        const contact::Shape* body) {
  std::map<std::string, BodyCrossing> crossing;
  for (const Seam& seam : garment.seams) {
    const std::size_t na = seam.a.size(), nb = seam.b.size();
    for (std::size_t i = 0; i < na; ++i) {
      const double along = na > 1 ? double(i) / double(na - 1) : 0.0;
      std::size_t j = std::size_t(std::lround(along * double(nb - 1)));
      if (seam.reverse) j = nb - 1 - j;
      const Eigen::Vector3d& from = garment.mesh.positions[std::size_t(seam.a[i])];
      const Eigen::Vector3d& to = garment.mesh.positions[std::size_t(seam.b[j])];
      double deepest = 0.0;
      for (int k = 1; k < 16; ++k)
        deepest = std::min(deepest, body->query(from + k / 16.0 * (to - from)).distance);
      if (deepest < 0.0) {
        BodyCrossing& entry = crossing[seam.name];
        ++entry.pairs;
        entry.depth = std::max(entry.depth, -deepest);
      }
    }
  }
  return crossing;
}

// How the drape ended (app/drape_outcome.hpp), on the mannequin whose
// feet stand on the floor; classified on rank 0, which has the final
// positions, and broadcast.
DrapeOutcome drape_outcome(const CaseResult& result, const DrapeEndLimits& limits,
                           const contact::GarmentBody& garment_body) {
  std::array<double, 8> packed{};
  if (is_root()) {
    const contact::Shape* body = garment_body.distance.get();
    double floor = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& v : garment_body.mannequin.mesh.vertices)
      floor = std::min(floor, v.z());
    const DrapeOutcome o = classify_drape_end(
        result.mesh.positions, result.positions, floor,
        [&body](const Eigen::Vector3d& p) { return body->query(p).distance; }, limits);
    packed = {double(o.end),
              double(o.slid_down),
              double(o.on_floor),
              double(o.off_body),
              o.centroid_drop,
              o.lowest,
              o.floor,
              o.nearest_body_distance};
  }
  SartorPetscCall(MPI_Bcast(packed.data(), int(packed.size()), MPI_DOUBLE, 0, PETSC_COMM_WORLD));
  DrapeOutcome outcome;
  outcome.end = DrapeEnd(int(packed[0]));
  outcome.slid_down = packed[1] != 0.0;
  outcome.on_floor = packed[2] != 0.0;
  outcome.off_body = packed[3] != 0.0;
  outcome.centroid_drop = packed[4];
  outcome.lowest = packed[5];
  outcome.floor = packed[6];
  outcome.nearest_body_distance = packed[7];
  return outcome;
}

nlohmann::json drape_outcome_json(const DrapeOutcome& outcome, const DrapeEndLimits& limits) {
  return {{"end", name_of(outcome.end)},
          {"description", outcome.description()},
          {"slid_down", outcome.slid_down},
          {"on_floor", outcome.on_floor},
          {"off_body", outcome.off_body},
          {"centroid_drop_m", outcome.centroid_drop},
          {"lowest_point_m", outcome.lowest},
          {"floor_m", outcome.floor},
          {"nearest_body_distance_m", outcome.nearest_body_distance},
          {"drop_tolerance_m", limits.drop_tolerance},
          {"floor_clearance_m", limits.floor_clearance},
          {"touch_distance_m", limits.touch_distance}};
}

} // namespace

const CommandSpec& drape_command() {
  static const CommandSpec spec{
      "drape",
      "construct a garment from its pattern and drape it on the mannequin",
      "sartor drape PATTERN.json [--fabric SPEC] [--output DIR] [--edge-length M] "
      "[--seams-file FILE] [--drop-tolerance M] [--no-plot] [any option of sartor run]",
      "Constructs the garment as `sartor construct` does (TAGCON around the built-in\n"
      "mannequin: docs/tagcon.md), then sews and drapes it as `sartor run` would a\n"
      "case with --mesh obj and --seams-file: by minimising the total potential\n"
      "(the static minimiser, no time stepping), the seams closing in\n"
      "--sewing-stages continuation stages of their stiffness while the garment's\n"
      "weight grows, on the mannequin (friction mu = 0.3 in the last stage).\n"
      "--analysis dynamic (or any time-stepping option, e.g. --time-end) drops it\n"
      "in implicit dynamics with kinetic damping and gradual sewing instead, then\n"
      "settles it (--kinetic-damping and --settle are on then). Each panel\n"
      "gets the pattern's fabric (--fabric gives every panel one). Every option of\n"
      "`sartor run` applies, except those describing the mesh and its seams; drape\n"
      "changes some defaults (shown below) and turns on --membrane-psd and\n"
      "--bending-psd (`-membrane_psd false` turns one off).\n"
      "--seams-file retags panels and overrides or completes TAGCON's seams by line\n"
      "ids (docs/pattern-format.md#user-seams-and-tags). A drape whose garment ends\n"
      "off the body, on the floor, or with its centroid more than --drop-tolerance\n"
      "below its start is reported as such, not as converged (exit status 1).\n"
      "docs/drape.md has the details and measured runs.\n\n"
      "Output in DIR: what `sartor construct` writes (garment.obj = the placed\n"
      "panels, seams.json, construct.json, pattern_seams.svg, placement.svg);\n"
      "drape_seams.json (the seams sewn: a panel that no seam attaches is left out\n"
      "of the drape); what\n"
      "`sartor run` writes (result.h5 + result.xmf, final.obj = the draped\n"
      "garment, petsc_options.txt; dynamics: series.h5 + series.xmf, dynamics.csv);\n"
      "body.obj\n"
      "(the body: the mannequin, sized/posed by --body, or the --body mesh); summary.json (the "
      "run's summary and \"drape\": timings,\n"
      "seam gap, penetration, body reaction against the garment's weight); and\n"
      "drape.png (front, side and back views coloured by strain, with a colour bar,\n"
      "postproc/plot_drape.py; not with --no-plot).\n\n"
      "examples:\n"
      "  sartor drape cases/patterns/skirt.json --output out/drape/skirt\n"
      "  sartor drape cases/patterns/tshirt.json --fabric silk --edge-length 0.05",
      [] {
        std::vector<OptionSpec> options;
        for (OptionSpec option : case_option_specs()) {
          for (const auto* defaults :
               {&drape_defaults(), &drape_dynamic_defaults(), &drape_sewing_defaults(false),
                &drape_sewing_defaults(true)}) {
            for (const auto& [name, value] : *defaults)
              if (option.answers_to(name)) option.fallback = value;
          }
          if (option.answers_to("sewing-time"))
            option.help = "dynamic: the end of the sewing stage, s";
          if (option.answers_to("bending-model")) {
            option.fallback = "patch";
            option.help += "; drape's dynamics: discrete_shell";
          }
          const auto among = [&](const std::vector<std::string>& names) {
            return std::any_of(names.begin(), names.end(),
                               [&](const std::string& name) { return option.answers_to(name); });
          };
          if (among(drape_flags(true)))
            option.help +=
                among(drape_flags(false)) ? " [on in drape]" : " [on in drape's dynamics]";
          if (option.answers_to("fabric")) {
            option.fallback.clear();
            option.help = "the fabric of every panel, a preset, FILE.yaml or measured FILE.json "
                          "[the pattern's]";
          }
          if (option.answers_to("seams-file")) option = seams_file_option_spec();
          if (option.answers_to("body"))
            option.help = "the body, with a skeleton: \"mannequin [measurements=FILE.json] "
                          "[pose=JOINT:DEG,...] mu=...\" or \"mesh file=BODY.obj "
                          "skeleton=SKELETON.json mu=...\" (docs/bodies.md)";
          // The creep options also steer drape's wear, after a static drape.
          if (option.help.rfind("creep: ", 0) == 0) option.help.insert(5, ", wear");
          if (is_mesh_option(option.name)) {
            option.fallback.clear();
            option.help = "sartor run only: the pattern gives the mesh and seams";
          }
          options.push_back(option);
        }
        for (OptionSpec option : panel_mesh_option_specs()) {
          // Coarser than construct's 2 cm: the drape's time steps cost Newton solves.
          if (option.name == "edge-length") option.fallback = "0.04";
          options.push_back(option);
        }
        for (const OptionSpec& option : level_option_specs())
          options.push_back(option);
        options.push_back(
            {"output", "DIR", "out/drape", "output folder (created; files in it are replaced)"});
        options.push_back({"no-plot", "", "", "write data only, no PNG"});
        options.push_back({"checkpoint-interval", "S", "0",
                           "write a checkpoint every S s of simulated time (dynamics), after "
                           "every sewing stage and contact round (statics: any S > 0); on "
                           "several levels, within each level and after every level but the "
                           "last (docs/reliability.md)"});
        options.push_back({"checkpoint", "FILE", "", "the checkpoint file [OUTPUT/checkpoint.h5]"});
        options.push_back(
            {"restart", "FILE", "", "resume from this checkpoint (the same pattern and options)"});
        options.push_back(
            {"start-from", "DRAPE_DIR", "",
             "start where the drape in DRAPE_DIR left the cloth: another version of this pattern "
             "(a dart added, lines moved, another --edge-length), its panels found by id and "
             "their grain lines unchanged; one level (docs/drape.md#starting-from-another-drape)"});
        for (const OptionSpec& option : wear_option_specs())
          options.push_back(option);
        options.push_back({"drop-tolerance", "M", "0.1",
                           "m the garment's centroid may end below its start: a larger drop is "
                           "reported as slid down"});
        return options;
      }(),
      1};
  return spec;
}

int run_drape(const Invocation& invocation) {
  return drape_pattern(invocation, nullptr);
}

namespace {

// Options of `sartor run` that drape makes no sense of, and a body without
// the skeleton that construction needs, are refused before any work.
void check_drape_options(const Options& options) {
  for (const OptionSpec& option : drape_command().options) {
    if (is_mesh_option(option.name) && options.is_set(option.name)) {
      throw InputError("option --" + options.name_given(option.name) +
                       " does not apply to sartor drape: the garment's mesh and seams come from "
                       "the pattern (--edge-length, --min-angle)");
    }
  }
  const std::string body = options.text("body");
  if (body.rfind("mannequin", 0) != 0 &&
      (body.rfind("mesh", 0) != 0 || body.find("skeleton=") == std::string::npos)) {
    throw InputError("option --body: sartor drape constructs the garment around its body, so the "
                     "body must have a skeleton: \"mannequin [measurements=FILE.json] "
                     "[pose=...] mu=...\" or \"mesh file=BODY.obj skeleton=SKELETON.json "
                     "mu=...\", got '" +
                     body + "'");
  }
}

// The body as draped on, body.obj (rank 0 writes it).
void write_drape_body(const std::string& directory, const ConstructedGarment& constructed,
                      const std::string& path) {
  if (is_root()) {
    write_body_obj(directory + "/body.obj", constructed.body->mannequin.mesh,
                   {"Sartor body: " + constructed.body->source,
                    "the body sartor drape draped " + path + " on; metres"});
  }
}

// Warns of the panels left out and of seams whose springs cross the body;
// the crossings for the summary.
nlohmann::json report_sewing(const SewableGarment& sewable, const ConstructedGarment& constructed) {
  for (const std::string& panel : sewable.left_out) {
    SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD,
                                "sartor drape: panel '%s' is left out: no sewn seam attaches it\n",
                                panel.c_str()));
  }
  // A crossing deeper than 1 cm is more than the curvature of the body
  // between two seam vertices: the spring will pull cloth through it.
  const std::map<std::string, BodyCrossing> crossing =
      seams_crossing_body(sewable, constructed.body->distance.get());
  nlohmann::json crossing_json = nlohmann::json::object();
  for (const auto& [seam, entry] : crossing) {
    crossing_json[seam] = {{"pairs", entry.pairs}, {"depth_m", entry.depth}};
    if (entry.depth <= 0.01) continue;
    SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD,
                                "sartor drape: warning: seam '%s': the springs of %d vertex "
                                "pair(s) run through the body (%.0f mm deep) and can pull the "
                                "cloth into it\n",
                                seam.c_str(), entry.pairs, 1e3 * entry.depth));
  }
  return crossing_json;
}

// The cloth: the sewn panels, one material per distinct fabric (or the one
// --fabric names); `labels` gets the panels' names.
CaseCloth drape_cloth(const Options& options, const ConstructedGarment& constructed,
                      const SewableGarment& sewable, ClothOutputLabels* labels) {
  CaseCloth cloth;
  cloth.mesh = sewable.mesh;
  for (const auto& panel : constructed.pattern.panels)
    labels->panels.push_back(panel.id);
  if (options.is_set("fabric")) {
    cloth.fabrics = {options.text("fabric")};
    cloth.mesh.material_ids.clear();
    return cloth;
  }
  assign_panel_fabrics(constructed.pattern.panels, &cloth);
  return cloth;
}

// Drape's defaults over those of `sartor run`, in drape's options (not only
// in the spec: the pipeline asks whether --body is set, and a flag's default
// is off); whether the drape is dynamic.
bool set_drape_defaults(Options& options, bool sewn, bool creased) {
  for (const auto& [name, value] : drape_defaults())
    options.set_default(name, value);
  // --analysis creep: the static drape, then wear (docs/wear.md).
  if (options.text("analysis") == "creep") {
    options.set("analysis", "static");
    options.set_default("wear-time", "28800");
  }
  // A time-stepping option asks for dynamics (drape's default before the
  // static minimiser; such command lines keep their meaning).
  if (!options.is_set("analysis")) {
    for (const std::string& name : time_stepping_options()) {
      if (options.is_set(name)) options.set_default("analysis", "dynamic");
    }
  }
  const bool dynamic = options.text("analysis") == "dynamic";
  for (const auto& [name, value] : dynamic ? drape_dynamic_defaults() : drape_static_defaults())
    options.set_default(name, value);
  // Statics: the bending patches, which converge to plate theory (the hinges
  // are 5 to 31 % too soft; docs/finite-elements.md#bending). A mesh with
  // creases is left to `sartor run`'s rule: the hinges, which carry them.
  if (!dynamic && !creased) options.set_default("bending-model", "patch");
  if (sewn) {
    for (const auto& [name, value] : drape_sewing_defaults(dynamic))
      options.set_default(name, value);
  }
  for (const std::string& flag : drape_flags(dynamic))
    options.set_default(flag, "true");
  return dynamic;
}

struct GarmentWeight {
  double area = 0.0;                                // m^2 of material
  double mass = 0.0;                                // kg
  Eigen::Vector3d weight = Eigen::Vector3d::Zero(); // N
};

GarmentWeight garment_weight(const Options& options, const TriangleMesh& mesh) {
  GarmentWeight garment;
  for (const auto& uv : mesh.material_uv)
    garment.area += 0.5 * std::abs((uv[1] - uv[0]).x() * (uv[2] - uv[0]).y() -
                                   (uv[1] - uv[0]).y() * (uv[2] - uv[0]).x());
  garment.mass = options.nonnegative_real("density") * garment.area;
  const std::vector<double> gravity = option_numbers(options, "gravity", 3);
  garment.weight = garment.mass * Eigen::Vector3d(gravity[0], gravity[1], gravity[2]);
  return garment;
}

// The time steps of the relaxation are solved loosely; the settle solves
// fully: to 1e-6 of the garment's weight (1.4e-6 N for the skirt), above
// the round-off the stiff seam and contact springs leave in the residual
// (1e-7 to 1e-6 N on the skirt, growing as the mesh is refined).
void set_drape_tolerances(bool dynamic, const Eigen::Vector3d& weight) {
  if (dynamic) SartorPetscCall(set_default_option("-snes_rtol", "1e-4"));
  // A stage meant to converge may crawl for a while where the garment
  // slides along a soft direction (the coarse T-shirt's about 150
  // iterations, the hooded top's up to 300), and one cut off passes on an
  // iterate round-off moves: at 300 the hooded top ended 9.5e-6 m apart on
  // 4 ranks, at 1000 3.8e-10 m (docs/drape.md).
  if (!dynamic) SartorPetscCall(set_default_option("-snes_max_it", "1000"));
  if (weight.norm() > 0.0)
    SartorPetscCall(set_default_option("-snes_atol", format_number(1e-6 * weight.norm()).c_str()));
}

// What the drape achieved.
struct DrapeMeasures {
  Eigen::Vector3d reaction = Eigen::Vector3d::Zero();  // N, the body's on the garment
  double penetration = 0.0;                            // m, deepest into the offset layer
  double closest = std::numeric_limits<double>::max(); // m, nearest vertex to the body
  double offset = 0.0;                                 // m, --contact-offset
  Eigen::Vector3d imbalance = Eigen::Vector3d::Zero(); // N
  double seam_gap = 0.0;                               // m
  double residual = -1.0; // N of the final static solve; < 0 when there is none
  bool equilibrium = false;
  DrapeEndLimits end_limits;
  DrapeOutcome outcome;
  bool converged = false;
};

DrapeMeasures measure_drape(const Options& options, const ClothCase& cloth_case,
                            const CaseResult& result, const contact::GarmentBody& body,
                            const Eigen::Vector3d& weight) {
  DrapeMeasures m;
  for (const BodyContact& report : result.contact.reports) {
    m.reaction += report.normal_force + report.friction_force;
    m.penetration = std::max(m.penetration, report.max_penetration);
    m.closest = std::min(m.closest, report.min_distance);
  }
  m.offset = cloth_case.contact.settings.offset;
  // At rest the body's reaction on the garment cancels its weight (pins, when
  // a user adds some, take their share: pin_reaction_N).
  m.imbalance = m.reaction + result.pin_reaction + weight;
  m.seam_gap = result.seams ? result.seams->gap : 0.0;
  // The residual force of the final static solve (the settle, or statics),
  // N; negative when there is none (dynamics without --settle). A solve can
  // stop on a small Newton step (CONVERGED_SNORM_RELATIVE) far from
  // equilibrium: the drape converged only when the residual is below 1e-3
  // of the garment's weight.
  if (result.dynamics && !result.dynamics->settle_reason.empty()) {
    m.residual = result.dynamics->settle_residual_norm;
  } else if (!result.dynamics && !result.creep) {
    m.residual = result.report.final_residual_norm;
  }
  m.equilibrium = m.residual >= 0.0 && m.residual <= 1e-3 * weight.norm();
  m.end_limits.drop_tolerance = options.nonnegative_real("drop-tolerance");
  m.outcome = drape_outcome(result, m.end_limits, body);
  m.converged =
      result.converged && (m.residual < 0.0 || m.equilibrium) && m.outcome.end == DrapeEnd::on_body;
  return m;
}

// summary.json's construction section (its details: construct.json).
nlohmann::json construction_json(const ConstructedGarment& constructed,
                                 const SewableGarment& sewable,
                                 const nlohmann::json& crossing_json) {
  return {{"panels", constructed.pattern.panels.size()},
          {"seams", constructed.construction.seams.size()},
          {"sewn_seams", constructed.garment.seams.size()},
          {"panels_left_out", sewable.left_out},
          {"seams_across_body", crossing_json},
          {"unseamed_lines", constructed.construction.unseamed.size()},
          {"file", "construct.json"}};
}

// summary.json's drape section; `timing` its timing_s.
nlohmann::json drape_json(const DrapeMeasures& m, const GarmentWeight& garment,
                          const CaseResult& result, const std::string& verdict,
                          nlohmann::json timing, const std::vector<LevelRun>& levels) {
  const auto to_json = [](const Eigen::Vector3d& v) { return nlohmann::json{v.x(), v.y(), v.z()}; };
  const Eigen::Vector3d& weight = garment.weight;
  const double residual = m.residual;
  return {
      {"converged", m.converged},
      {"outcome", drape_outcome_json(m.outcome, m.end_limits)},
      {"equilibrium_checked", residual >= 0.0},
      {"residual_force_N", residual >= 0.0 ? nlohmann::json(residual) : nlohmann::json(nullptr)},
      {"material_area_m2", garment.area},
      {"mass_kg", garment.mass},
      {"weight_N", to_json(weight)},
      {"body_reaction_N", to_json(m.reaction)},
      {"relative_imbalance", weight.norm() > 0 ? m.imbalance.norm() / weight.norm() : 0.0},
      {"largest_seam_gap_m", m.seam_gap},
      {"max_penetration_m", m.penetration},
      {"contact_offset_m", m.offset},
      {"residual_relative_to_weight", residual >= 0.0 && weight.norm() > 0.0
                                          ? nlohmann::json(residual / weight.norm())
                                          : nlohmann::json(nullptr)},
      // The deepest vertex in the offset layer as a fraction of the offset
      // (1: on the body's surface), and whether any vertex is inside the body.
      {"deepest_vertex_relative_to_offset", m.penetration / m.offset},
      {"vertex_inside_body", m.closest < 0.0},
      {"method", result.dynamics           ? "dynamics"
                 : result.report.minimised ? "minimise"
                                           : "snes"},
      // The certificate's verdict (its details: summary.json's certificate).
      {"certificate", verdict},
      {"timing_s", std::move(timing)},
      {"levels", levels_json(levels)}};
}

void print_drape(const CaseResult& result, std::size_t seams_sewn, double construction_seconds,
                 const DrapeMeasures& m, const Eigen::Vector3d& weight, const std::string& verdict,
                 const std::string& directory) {
  const double residual = m.residual;
  SartorPetscCall(PetscPrintf(
      PETSC_COMM_WORLD,
      "sartor drape: %zu triangles, %zu seams sewn; construction %.3f s, drape %.1f s (%s, "
      "%s); residual force %s of the weight; seam gap %.2e m, deepest vertex %.2e m into the "
      "%.2g m offset (%s); body reaction %.6g N for a weight of %.6g N; certificate: "
      "%s; wrote %s\n",
      result.mesh.triangle_count(), seams_sewn, construction_seconds, result.solve_seconds,
      result.dynamics ? "dynamics" : "static minimiser",
      m.outcome.end != DrapeEnd::on_body ? ("garment " + m.outcome.description()).c_str()
      : !m.converged                     ? "not converged"
      : residual < 0.0 ? "dynamics completed; equilibrium not checked without --settle"
                       : "converged",
      residual >= 0.0 && weight.norm() > 0.0 ? format_number(residual / weight.norm()).c_str()
                                             : "unknown",
      m.seam_gap, m.penetration, m.offset,
      m.closest < 0.0 ? "a vertex inside the body" : "outside the body", m.reaction.norm(),
      weight.norm(), verdict.c_str(), directory.c_str()));
}

// Throws the drape's failure, if any (the wear's report printed once the
// drape itself succeeded).
void check_drape(const Options& options, const CaseResult& result, const DrapeMeasures& m,
                 const Eigen::Vector3d& weight, const WearRun& wear, const std::string& directory) {
  if (!result.converged) {
    const std::string reason = result.dynamics ? result.dynamics->reason : result.report.reason;
    throw SolveFailure("the drape did not converge (" + reason + "); " + directory +
                       " holds the last state. Try -snes_monitor" +
                       (result.dynamics ? ", a longer --time-end or a smaller --time-step" : ""));
  }
  if (m.outcome.end != DrapeEnd::on_body) {
    throw SolveFailure("the drape did not drape the garment: it ended " + m.outcome.description() +
                       "; " + directory + " holds its state (summary.json: drape.outcome)");
  }
  if (wear.ran) print_wear(wear);
  if (!m.converged) {
    throw SolveFailure("the drape is not in equilibrium: the final static solve stopped with a "
                       "residual force of " +
                       format_number(m.residual) + " N for a weight of " +
                       format_number(weight.norm()) + " N; " + directory +
                       " holds its state. Look for seams across the body (warnings above) or "
                       "penetration (summary.json)");
  }
  if (wear_requested(options) && !(wear.ran && wear.report.wear.completed)) {
    throw SolveFailure("the wear did not complete (" +
                       (wear.ran ? wear.report.wear.reason : std::string("no converged drape")) +
                       "); " + directory + " holds the states reached (wear.csv)");
  }
}

// --start-from drapes the finest level only: a coarser level would start
// afresh. Throws InputError for --levels over 1 and with --restart.
double start_from_level(const Options& options, const std::vector<double>& edge_lengths) {
  if (options.is_set("levels") && options.integer_in("levels", 1, 8) > 1)
    throw InputError("option --start-from: the drape starts on the finest mesh; give --levels 1");
  if (options.is_set("restart"))
    throw InputError("option --start-from: --restart resumes a checkpoint instead; give one");
  return edge_lengths.back();
}

void print_start_from(const StartFromReport& report) {
  SartorPetscCall(PetscPrintf(
      PETSC_COMM_WORLD,
      "sartor drape: started from %s: %ld vertices placed on its drape, %ld beyond its panels "
      "(up to %.3g m, extended), the deepest %.3g m below the offset lifted out\n",
      report.directory.c_str(), report.vertices, report.extrapolated, report.farthest_beyond_m,
      report.lifted_depth_m));
}

// --start-from: the cloth placed where the old drape left it, on the
// finest level alone (`edge_lengths` cut to it); none without the option.
std::optional<StartFromReport> start_from(const Options& options,
                                          const ConstructedGarment& constructed,
                                          const SewableGarment& sewable,
                                          const ClothCase& cloth_case, CaseCloth* cloth,
                                          std::vector<double>* edge_lengths) {
  if (!options.is_set("start-from")) return std::nullopt;
  *edge_lengths = {start_from_level(options, *edge_lengths)};
  const StartFromReport report =
      start_from_drape(options.text("start-from"), constructed.pattern, sewable.mesh.material_ids,
                       cloth_case.contact, &cloth->mesh);
  print_start_from(report);
  return report;
}

} // namespace

int drape_pattern(const Invocation& invocation, const EditRequest* edit) {
  using Clock = std::chrono::steady_clock;
  const auto started = Clock::now();
  const double started_cpu = process_cpu_seconds();
  const std::string command = edit ? "edit" : "drape";
  // Drape's defaults and its own seams file go into its copy of the options.
  Invocation drape = invocation;
  Options& options = drape.options;
  const std::string path = drape.command_line.positionals.at(0);
  const std::string directory = options.text("output");
  check_drape_options(options);
  const std::string body = options.text("body");

  // 1. The garment, constructed and written as `sartor construct` writes it.
  const std::string user_seams = options.is_set("seams-file") ? options.text("seams-file") : "";
  const ConstructedGarment constructed = construct_garment(
      path, panel_mesh_options(options), user_seams, !options.flag("no-prefold"), body);
  print_construction(constructed);
  const auto constructed_at = Clock::now();
  write_construction(directory, constructed,
                     construction_summary(drape, "drape", path, constructed));
  write_drape_body(directory, constructed, path);

  // 2. The cloth: the sewn panels, one material per distinct fabric.
  const SewableGarment sewable = sewable_garment(constructed);
  const nlohmann::json crossing_json = report_sewing(sewable, constructed);
  const std::string seams_file = directory + "/drape_seams.json";
  if (is_root()) write_seams(seams_file, sewable.seams);
  // Every rank reads it in solve_case.
  SartorPetscCall(MPI_Barrier(PETSC_COMM_WORLD));
  ClothOutputLabels labels{{}, {}, sewable.mesh.material_ids};
  CaseCloth cloth = drape_cloth(options, constructed, sewable, &labels);
  name_single_fabric(cloth, &options);

  // 3. Sew and drape: `sartor run`'s options, drape's defaults, drape's seams (the
  // user's --seams-file is what petsc_options.txt echoes, to re-run the job).
  options.set("seams-file", seams_file);
  const bool dynamic =
      set_drape_defaults(options, !sewable.seams.empty(), !sewable.mesh.creases.empty());
  const GarmentWeight garment = garment_weight(options, cloth.mesh);
  const Eigen::Vector3d& weight = garment.weight;
  set_drape_tolerances(dynamic, weight);
  labels.fabrics = cloth.fabrics;
  const auto wear = std::make_shared<WearRun>();
  if (wear_requested(options)) {
    if (dynamic) throw InputError("option --wear-time: wear follows a static drape, not dynamics");
    attach_wear(options, directory, labels, &cloth, wear);
  } else if (options.is_set("restart") && within_wear(options.text("restart"))) {
    throw InputError("option --restart: " + options.text("restart") +
                     " was taken within a wear; resume it with the same --wear-time");
  }
  if (edit) {
    if (dynamic || wear_requested(options))
      throw InputError("sartor edit edits a static drape: --analysis dynamic and --wear-time "
                       "do not apply");
    attach_edit(options, directory,
                {constructed.pattern, sewable.mesh.material_ids, sewable.seams, labels},
                edit->steps, {edit->drape.directory, edit->drape.recorded_cpu, started_cpu}, &cloth,
                edit->run);
  }
  std::vector<LevelRun> levels;
  // The drape's final state, at full precision: `sartor edit DIRECTORY` resumes from it.
  CaseCheckpointing checkpointing = case_checkpointing(options, directory);
  checkpointing.final_state = directory + "/" + drape_state_file;
  const ClothCase cloth_case = read_cloth_case(options, false);
  const FinerLevels finer_levels = read_finer_levels(options, cloth_case);
  std::vector<double> edge_lengths =
      drape_level_edge_lengths(options, constructed.construction, constructed.mesh_options);
  const std::optional<StartFromReport> started_from =
      start_from(options, constructed, sewable, cloth_case, &cloth, &edge_lengths);
  // Progressive refinement (app/progressive_drape.hpp): coarser levels
  // first when --edge-length allows them; one level is the drape above.
  const DrapeLevel finest{constructed.mesh_options.edge_length, cloth, sewable.mesh.material_ids,
                          sewable.seams, seams_file};
  const CaseResult result = drape_progressively(cloth_case, finer_levels, constructed.construction,
                                                constructed.mesh_options, finest, edge_lengths,
                                                directory, labels, &levels, checkpointing);

  // 4. What the drape achieved.
  const DrapeMeasures measures =
      measure_drape(options, cloth_case, result, *constructed.body, weight);
  const double construction_seconds =
      constructed.construction.placement_seconds + constructed.construction.seam_seconds;
  const double total_seconds = std::chrono::duration<double>(Clock::now() - started).count();

  const std::string verdict = certificate_verdict(cloth_case.certificate, result.certified);
  nlohmann::json summary = run_metadata(drape, command);
  summary["pattern"] = path;
  summary["pattern_file"] = std::filesystem::absolute(path).lexically_normal().string();
  summary["pattern_checksum"] = file_checksum(path);
  summary["fabrics"] = cloth.fabrics;
  summary["construction"] = construction_json(constructed, sewable, crossing_json);
  add_case_summary(result, summary);
  summary["drape"] = drape_json(
      measures, garment, result, verdict,
      {{"construction", construction_seconds},
       {"meshing", constructed.mesh_seconds},
       {"construct_total", std::chrono::duration<double>(constructed_at - started).count()},
       {"drape", result.solve_seconds},
       {"drape_setup", result.setup_seconds},
       {"total", total_seconds}},
      levels);
  summary["drape"]["cpu_s"] = result.cpu_at_end - started_cpu;
  if (started_from) summary["drape"]["start_from"] = started_from->json();
  if (edit && edit->run->ran) summary["edit"] = edit->run->summary;
  if (wear->ran) {
    add_wear_summary(*wear, labels, summary);
    write_wear_tables(directory, *wear);
  }
  write_case_results(directory, result, summary, labels);
  write_petsc_options(directory, options);
  if (drape.keep_result) drape.keep_result(result, summary, labels);

  print_drape(result, constructed.garment.seams.size(), construction_seconds, measures, weight,
              verdict, directory);
  // The picture helps most when the drape failed.
  if (!options.flag("no-plot")) make_plot("plot_drape.py", directory);
  check_drape(options, result, measures, weight, *wear, directory);
  return 0;
}

} // namespace sartor
