#include "app/progressive_drape.hpp"

#include "app/case_checks.hpp"
#include "app/commands.hpp"
#include "app/contact_case.hpp"
#include "app/log_stage.hpp"
#include "common/csv.hpp"
#include "common/error.hpp"
#include "contact/body_spec.hpp"
#include "contact/edge_penalty.hpp"
#include "fem/checkpoint.hpp"
#include "fem/petsc_call.hpp"

#include <nlohmann/json.hpp>
#include <petscsys.h>

#include <algorithm>
#include <array>
#include <cstdio>

namespace sartor {

namespace {

// What a finer level changes for its solve: a short damped relaxation (drape's
// dynamics with kinetic damping, --refine-time long) from the prolonged
// drape, then the settle; without the sewing stage (the seams are closed) and
// without the placement options (the start is placed already). A static
// Newton solve straight from the prolonged drape (tried first) stalled on
// the T-shirt: 100 damped Newton steps from a residual of 3.6e3 N, then
// pseudo-transient continuation for minutes (16 to 8 cm; the coarse drape
// held 9 J of potential, the 8 cm one 2 J at rest).
ClothCase finer_level_case(ClothCase level_case, double refine_time) {
  // A static drape (--analysis static) stays static on every level.
  TimeCase& time = level_case.time;
  if (time.dynamic()) {
    check_time_divisions(refine_time, "refine-time", time.time_step, "time-step");
    time.time_end = refine_time;
    time.output_interval = 0.0;
  }
  level_case.seams.sewing_tension.reset();
  level_case.seams.sewing_time.reset();
  level_case.mesh.rotate_x = 0.0;
  level_case.mesh.translate.setZero();
  return level_case;
}

// The edge-sample spacing of a level before the last.
double coarse_edge_spacing(double spacing, double edge_length) {
  return spacing > 0.0 ? std::max(spacing, edge_length / 4.0) : 0.0;
}

// A copy of the level's mesh whose material ids are its panels, as the
// prolongation reads them.
TriangleMesh panel_mesh(const DrapeLevel& level) {
  TriangleMesh mesh = level.cloth.mesh;
  mesh.material_ids = level.panel_of_triangle;
  return mesh;
}

// The level at edge length h: the construction meshed at h, finest's
// panels and fabrics, its seams written to the file `seams_file`.
DrapeLevel coarser_level(const garment::Construction& construction,
                         const PanelMeshOptions& mesh_options, const DrapeLevel& finest, double h,
                         const std::string& seams_file) {
  PanelMeshOptions options = mesh_options;
  options.edge_length = h;
  options.pieces.clear();
  const std::size_t panels = construction.pattern->panels.size();
  std::vector<bool> kept(panels, false);
  std::vector<int> fabric_of_panel(panels, 0);
  for (std::size_t t = 0; t < finest.panel_of_triangle.size(); ++t) {
    const std::size_t panel = std::size_t(finest.panel_of_triangle[t]);
    kept[panel] = true;
    if (!finest.cloth.mesh.material_ids.empty())
      fabric_of_panel[panel] = finest.cloth.mesh.material_ids[t];
  }
  const garment::GarmentMesh garment =
      garment::keep_panels(garment::build_garment_mesh(construction, options), kept);
  DrapeLevel level;
  level.edge_length = h;
  level.cloth.fabrics = finest.cloth.fabrics;
  level.cloth.mesh = garment.mesh;
  level.panel_of_triangle = garment.mesh.material_ids;
  if (finest.cloth.mesh.material_ids.empty()) {
    level.cloth.mesh.material_ids.clear();
  } else {
    for (int& id : level.cloth.mesh.material_ids)
      id = fabric_of_panel[std::size_t(id)];
  }
  level.seams = garment.seams;
  level.seams_file = seams_file;
  if (is_root()) write_seams(seams_file, level.seams);
  SartorPetscCall(MPI_Barrier(PETSC_COMM_WORLD));
  return level;
}

// Moves `x` out to half the contact offset along the body's normal when it
// lies deeper (Newton on the distance: the smooth mannequin's gradient is
// not unit in its fillets, so a few steps reach the level set). Returns the
// depth it had below the offset surface and the displacement.
double lift_point(const contact::Body& body, double offset, Eigen::Vector3d* x,
                  Eigen::Vector3d* displacement) {
  const Eigen::Vector3d start = *x;
  const double depth = offset - body.distance(*x, 0.0);
  for (int k = 0; k < 4; ++k) {
    const contact::SurfaceQuery q = body.query(*x, 0.0);
    if (q.distance >= 0.5 * offset || q.normal.squaredNorm() == 0.0) break;
    *x += (0.5 * offset - q.distance) * q.normal / q.normal.squaredNorm();
  }
  *displacement = *x - start;
  return depth;
}

// Lifts the points of every edge that the contact's edge samples would
// query (contact-edge-spacing apart) out of `body`, moving both ends of the
// edge by the point's displacement; a few sweeps over the edges, since
// lifting one edge moves its neighbours. The edge samples of a finer level
// that start inside a body were stuck there: 22 edges of the skirt held
// 3 mm deep while the adaptive penalty grew 1e7-fold.
void lift_edges_out_of_body(const contact::Body& body, double offset, double spacing,
                            const std::vector<std::array<int, 2>>& edges,
                            std::vector<Eigen::Vector3d>* positions) {
  for (int sweep = 0; sweep < 8; ++sweep) {
    bool lifted = false;
    for (const auto& [a, b] : edges) {
      Eigen::Vector3d& xa = (*positions)[std::size_t(a)];
      Eigen::Vector3d& xb = (*positions)[std::size_t(b)];
      for (double s : contact::edge_sample_parameters((xb - xa).norm(), spacing)) {
        Eigen::Vector3d point = (1.0 - s) * xa + s * xb, displacement;
        if (lift_point(body, offset, &point, &displacement) <= 0.5 * offset) continue;
        xa += displacement;
        xb += displacement;
        lifted = true;
      }
    }
    if (!lifted) return;
  }
}

void record(const CaseResult& result, LevelRun* run) {
  run->converged = result.converged;
  run->solve_seconds = result.solve_seconds;
  if (result.dynamics) {
    run->analysis = "dynamic";
    run->newton_iterations = long(result.dynamics->newton_iterations);
    if (!result.dynamics->settle_reason.empty())
      run->residual_force = result.dynamics->settle_residual_norm;
  } else {
    run->analysis = "static";
    run->newton_iterations = long(result.report.newton_iterations);
    run->residual_force = result.report.final_residual_norm;
  }
}

constexpr const char* level_kind = "drape-level";

// A level's end as a checkpoint: its solved positions, and in /state the
// level reached and what every level so far did.
void write_level_checkpoint(const std::string& path, std::size_t level, std::size_t count,
                            const std::vector<Eigen::Vector3d>& solved,
                            const std::vector<LevelRun>& runs) {
  if (!is_root()) return;
  RunCheckpoint checkpoint;
  checkpoint.next_step = 1.0; // a drape's levels have no clock
  checkpoint.step = long(level);
  checkpoint.positions = solved;
  checkpoint.state =
      nlohmann::json{
          {"kind", level_kind}, {"level", level}, {"levels", count}, {"runs", levels_json(runs)}}
          .dump();
  write_checkpoint(path, checkpoint);
}

LevelRun level_run_from(const nlohmann::json& r) {
  LevelRun run;
  run.edge_length = r.at("edge_length_m").get<double>();
  run.vertices = r.at("vertices").get<std::size_t>();
  run.triangles = r.at("triangles").get<std::size_t>();
  run.analysis = r.at("analysis").get<std::string>();
  run.converged = r.at("converged").get<bool>();
  run.newton_iterations = r.at("newton_iterations").get<long>();
  const nlohmann::json& residual = r.at("residual_force_N");
  run.residual_force = residual.is_null() ? -1.0 : residual.get<double>();
  run.seam_gap_prolonged = r.at("start_seam_gap_prolonged_m").get<double>();
  run.seam_gap_start = r.at("start_seam_gap_closed_m").get<double>();
  run.outside_distance = r.at("largest_outside_distance_m").get<double>();
  run.deepest_start = r.at("start_depth_below_offset_m").get<double>();
  run.solve_seconds = r.at("solve_s").get<double>();
  run.cpu_seconds = r.at("cpu_s").get<double>();
  return run;
}

// Where a drape on several levels resumes from a checkpoint: after a level's
// end (the next level starts from its drape), or within a level's solve
// (which reads the same checkpoint: a static solve's stages and rounds done,
// a dynamic one's time reached).
struct LevelResume {
  std::size_t level = 0; // the level solved next
  bool within = false;
  std::vector<Eigen::Vector3d> solved; // after a level's end: that level's drape
  std::vector<Eigen::Vector3d> start;  // within a finer level: the level's start
  LevelRun run;                        // within a level: its start's record
};

// What a checkpoint within level `level` carries in /state ("drape_level").
std::string level_record(std::size_t level, std::size_t count, const std::vector<LevelRun>& runs,
                         const LevelRun& run) {
  return nlohmann::json{{"level", level},
                        {"levels", count},
                        {"runs", levels_json(runs)},
                        {"run", levels_json({run})[0]}}
      .dump();
}

LevelResume read_level_checkpoint(const std::string& path, const std::vector<DrapeLevel>& levels,
                                  std::vector<LevelRun>* runs) {
  // A wear's checkpoint: the drape's last, which it carries, is the level's.
  const RunCheckpoint read = read_checkpoint(path);
  const RunCheckpoint& checkpoint = first_phase(read);
  LevelResume resume;
  std::size_t level = 0;
  try {
    const nlohmann::json state = nlohmann::json::parse(checkpoint.state);
    resume.within = state.contains("drape_level");
    if (!resume.within && state.at("kind") != level_kind)
      throw std::invalid_argument("neither a level's end nor within a level");
    const nlohmann::json& record = resume.within ? state.at("drape_level") : state;
    level = record.at("level").get<std::size_t>();
    if (record.at("levels").get<std::size_t>() != levels.size() || level >= levels.size() ||
        (!resume.within && level + 1 >= levels.size()))
      throw std::invalid_argument("of a drape with other levels");
    for (const nlohmann::json& r : record.at("runs"))
      runs->push_back(level_run_from(r));
    if (runs->size() != (resume.within ? level : level + 1))
      throw std::invalid_argument("its record of the levels before is not complete");
    if (resume.within) resume.run = level_run_from(record.at("run"));
  } catch (const std::exception& error) {
    throw InputError(path + ": not the checkpoint of a level of this drape's " +
                     std::to_string(levels.size()) + " levels (" + error.what() + ")");
  }
  const std::size_t vertices = levels[level].cloth.mesh.vertex_count();
  const bool start_needed = resume.within && level > 0;
  if (checkpoint.positions.size() != vertices ||
      (start_needed && checkpoint.start_positions.size() != vertices)) {
    throw InputError(path + ": the checkpoint's level " + std::to_string(level + 1) +
                     " has another mesh than this drape's");
  }
  resume.level = resume.within ? level : level + 1;
  if (resume.within) {
    resume.start = checkpoint.start_positions;
  } else {
    resume.solved = checkpoint.positions;
  }
  return resume;
}

void print_level(std::size_t index, std::size_t count, const LevelRun& run) {
  SartorPetscCall(
      PetscPrintf(PETSC_COMM_WORLD,
                  "sartor drape: level %zu of %zu: edge %.3g m, %zu triangles, %s, %s, %ld Newton "
                  "iterations, residual %s N, %.1f s (CPU %.1f s)\n",
                  index + 1, count, run.edge_length, run.triangles, run.analysis.c_str(),
                  run.converged ? "converged" : "NOT converged", run.newton_iterations,
                  run.residual_force >= 0 ? format_number(run.residual_force).c_str()
                                          : "not checked (no settle)",
                  run.solve_seconds, run.cpu_seconds));
  if (index == 0) return;
  SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD,
                              "  from the level before: seam gap %.2e m, closed to %.2e m; "
                              "deepest vertex %.2e m below the contact offset, lifted out\n",
                              run.seam_gap_prolonged, run.seam_gap_start, run.deepest_start));
}

} // namespace

// Moves the vertices of a prolonged drape that lie deeper than half the
// contact offset out to that depth, along the body's normal, and then the
// edges' sample points likewise. A coarse
// triangle's chord cuts into a convex body between its vertices (by
// h^2 / 8R: 2 cm for 16 cm edges on a 15 cm radius), so the finer vertices
// interpolated on it start inside; their penalty forces (1e4 N on the
// T-shirt's 2 N) would throw the static solve far off. Half the offset
// keeps them in contact, so that friction anchors them at the start.
// Returns the deepest vertex's start, m below the offset surface.
double lift_out_of_bodies(const ContactCase& contact, const TriangleMesh& mesh,
                          std::vector<Eigen::Vector3d>* positions) {
  const double offset = contact.settings.offset;
  const double spacing = contact.settings.edge_sample_spacing;
  const std::vector<std::array<int, 2>> edges = mesh_edges(mesh);
  double deepest = 0.0;
  for (const contact::Body& body : contact.bodies) {
    Eigen::Vector3d displacement;
    for (Eigen::Vector3d& x : *positions)
      deepest = std::max(deepest, lift_point(body, offset, &x, &displacement));
    if (spacing > 0.0) lift_edges_out_of_body(body, offset, spacing, edges, positions);
  }
  return deepest;
}

const std::vector<OptionSpec>& level_option_specs() {
  static const std::vector<OptionSpec> specs{
      {"levels", "N", "",
       "progressive refinement: N panel meshings, edge lengths --edge-length x 2^(N-1) .. "
       "--edge-length (1: a single level) [automatic]"},
      {"coarsest-edge", "M", "",
       "progressive refinement: the coarsest level's edge length, m; levels in ratios of at "
       "most 2 down to --edge-length [automatic]"},
      {"refine-time", "S", "0.3",
       "progressive refinement: simulated time of the damped relaxation on each finer level, "
       "s, before its settle"},
      {"level-sewing", "last-two|all", "last-two",
       "progressive refinement, statics: a finer level is sewn again from its prolonged start "
       "only in the last two sewing stages (the one before the last without friction), or in "
       "every one"},
  };
  return specs;
}

FinerLevels read_finer_levels(const Options& options, const ClothCase& cloth_case) {
  FinerLevels finer;
  if (cloth_case.time.dynamic()) finer.refine_time = options.positive_real("refine-time");
  const std::string sewing = options.text("level-sewing");
  if (sewing != "all" && sewing != "last-two")
    throw InputError("option --level-sewing: '" + sewing + "' is neither all nor last-two");
  finer.sew_last_two = sewing == "last-two";
  return finer;
}

std::vector<double> drape_level_edge_lengths(const Options& options,
                                             const garment::Construction& construction,
                                             const PanelMeshOptions& mesh_options) {
  garment::LevelOptions levels;
  levels.target_edge_length = mesh_options.edge_length;
  if (options.is_set("levels")) levels.levels = int(options.integer_in("levels", 1, 8));
  if (options.is_set("coarsest-edge"))
    levels.coarsest_edge_length = options.positive_real("coarsest-edge");
  const std::vector<double> lengths =
      garment::level_edge_lengths(construction, mesh_options, levels);
  if (lengths.size() > 1 && options.is_set("mesh-refine")) {
    throw InputError("option --mesh-refine: refines one mesh uniformly; with progressive "
                     "refinement give --edge-length (the target) or --levels 1");
  }
  return lengths;
}

CaseResult drape_progressively(const ClothCase& cloth_case, const FinerLevels& finer_levels,
                               const garment::Construction& construction,
                               const PanelMeshOptions& mesh_options, const DrapeLevel& finest,
                               const std::vector<double>& edge_lengths,
                               const std::string& directory, const ClothOutputLabels& labels,
                               std::vector<LevelRun>* runs,
                               const CaseCheckpointing& checkpointing) {
  const std::size_t count = edge_lengths.size();
  std::vector<DrapeLevel> levels;
  for (std::size_t l = 0; l + 1 < count; ++l) {
    levels.push_back(coarser_level(construction, mesh_options, finest, edge_lengths[l],
                                   directory + "/drape_seams_level" + std::to_string(l) + ".json"));
  }
  levels.push_back(finest);
  CaseResult result;
  // Several levels: a checkpoint at the end of each level before the last,
  // and within each level as its solve writes them (after every sewing stage
  // and contact round of a static one, every --checkpoint-interval s of
  // simulated time of a dynamic one); one level: solve_case's.
  LevelResume resume;
  if (count > 1 && !checkpointing.restart_file.empty()) {
    resume = read_level_checkpoint(checkpointing.restart_file, levels, runs);
    SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD,
                                "sartor drape: resuming from %s %s level %zu of %zu\n",
                                checkpointing.restart_file.c_str(), resume.within ? "within" : "at",
                                resume.level + 1, count));
  }
  std::vector<Eigen::Vector3d> solved = resume.solved;
  const ClothCase finer = finer_level_case(cloth_case, finer_levels.refine_time);
  // The checkpointing of level l's solve, whose start `run` records.
  const auto level_checkpointing = [&](std::size_t l, const LevelRun& run, bool resumed) {
    if (count == 1) return checkpointing;
    CaseCheckpointing within;
    within.file = checkpointing.file;
    within.interval = checkpointing.interval;
    within.final_state = checkpointing.final_state;
    within.drape_level = level_record(l, count, *runs, run);
    if (resumed) within.restart_file = checkpointing.restart_file;
    return within;
  };
  for (std::size_t l = resume.level; l < count; ++l) {
    DrapeLevel& level = levels[l];
    const bool resumed = resume.within && l == resume.level;
    LevelRun run = resumed ? resume.run : LevelRun{};
    run.edge_length = level.edge_length;
    run.vertices = level.cloth.mesh.vertex_count();
    run.triangles = level.cloth.mesh.triangle_count();
    const double cpu_start = process_cpu_seconds();
    const LogStage stage("Drape level " + std::to_string(l));
    // The levels before the last are starts: at most three edge samples per
    // edge there. With 1.5 cm samples on 16 cm edges the skirt's seams stayed
    // 6 cm open through the sewing stages; with none, the finer level
    // started with chords deep in the body (|F| 1e6 N).
    ClothCase level_case = l == 0 ? cloth_case : finer;
    // --level-sewing last-two (the default): a finer level starts sewn and
    // loaded (the coarser drape prolonged), so it repeats only the last two
    // sewing stages, the one before the last without friction, and the last
    // anchors the cloth afresh where the finer mesh settles
    // (docs/drape.md#sewing-a-finer-level-again: 12 % less CPU over the six
    // samples at 4 cm).
    if (l > 0 && finer_levels.sew_last_two)
      level_case.statics.first_sewing_stage = std::max(0, level_case.statics.sewing_stages - 2);
    level_case.seams.seams_file = level.seams_file;
    if (count > 1) {
      level_case.statics.progress_prefix =
          "level " + std::to_string(l + 1) + " of " + std::to_string(count) + ", ";
    }
    if (l + 1 < count) {
      level_case.contact.settings.edge_sample_spacing =
          coarse_edge_spacing(cloth_case.contact.settings.edge_sample_spacing, level.edge_length);
    }
    if (l == 0) {
      ClothOutputLabels coarsest = labels;
      coarsest.panel_of_triangle = level.panel_of_triangle;
      const CaseCheckpointing in_level = level_checkpointing(l, run, resumed);
      result = solve_case(level_case, 0, series_writer(directory, coarsest, in_level.restart_file),
                          in_level, &level.cloth);
    } else {
      if (resumed) {
        level.cloth.mesh.positions = resume.start;
      } else {
        const garment::Prolongation prolongation(panel_mesh(levels[l - 1]), panel_mesh(level));
        std::vector<Eigen::Vector3d> start = prolongation.vertex_field(solved);
        const garment::SeamClosure closure =
            garment::close_seams(panel_mesh(level), level.seams, &start);
        run.seam_gap_prolonged = closure.gap_before;
        run.seam_gap_start = closure.gap_after;
        run.outside_distance = prolongation.largest_outside_distance();
        run.deepest_start = lift_out_of_bodies(level_case.contact, level.cloth.mesh, &start);
        level.cloth.mesh.positions = start;
      }
      result = solve_case(level_case, 0, {}, level_checkpointing(l, run, resumed), &level.cloth);
    }
    run.cpu_seconds = process_cpu_seconds() - cpu_start;
    record(result, &run);
    if (count > 1) print_level(l, count, run);
    runs->push_back(run);
    if (l + 1 < count) {
      solved = broadcast_positions(result.positions, level.cloth.mesh.vertex_count());
      if (checkpointing.interval > 0.0)
        write_level_checkpoint(checkpointing.file, l, count, solved, *runs);
    }
  }
  // The drape's solve time is all its levels'.
  result.solve_seconds = 0.0;
  for (const LevelRun& run : *runs)
    result.solve_seconds += run.solve_seconds;
  return result;
}

nlohmann::json levels_json(const std::vector<LevelRun>& runs) {
  nlohmann::json levels = nlohmann::json::array();
  for (const LevelRun& run : runs) {
    levels.push_back(
        {{"edge_length_m", run.edge_length},
         {"vertices", run.vertices},
         {"triangles", run.triangles},
         {"analysis", run.analysis},
         {"converged", run.converged},
         {"newton_iterations", run.newton_iterations},
         {"residual_force_N",
          run.residual_force >= 0 ? nlohmann::json(run.residual_force) : nlohmann::json(nullptr)},
         {"start_seam_gap_prolonged_m", run.seam_gap_prolonged},
         {"start_seam_gap_closed_m", run.seam_gap_start},
         {"largest_outside_distance_m", run.outside_distance},
         {"start_depth_below_offset_m", run.deepest_start},
         {"solve_s", run.solve_seconds},
         {"cpu_s", run.cpu_seconds}});
  }
  return levels;
}

} // namespace sartor
