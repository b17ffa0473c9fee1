#include "app/seam_case.hpp"

#include "common/csv.hpp"
#include "common/error.hpp"
#include "fem/petsc_call.hpp"
#include "fem/petsc_options.hpp"
#include "mesh/merge.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>

namespace sartor {

namespace {

// --sewing-tension and --sewing-time: the sewing stage of a dynamic run.
void set_up_sewing(const SeamCase& seam_case, const TimeCase& time, ClothProblem& problem,
                   SeamReport* report) {
  if (!seam_case.sewing_tension || *seam_case.sewing_tension == 0.0) return;
  if (time.analysis != "dynamic") {
    throw InputError("option --sewing-tension: sewing is a stage of time stepping; give --analysis "
                     "dynamic (or leave --sewing-tension out)");
  }
  const double end = seam_case.sewing_time.value_or(0.5 * time.time_end);
  if (end >= time.time_end) {
    throw InputError("option --sewing-time: the sewing stage must end before --time-end (" +
                     format_number(time.time_end) + " s), got " + format_number(end) + " s");
  }
  problem.sewing_tension = *seam_case.sewing_tension;
  problem.sewing_end_time = end;
  report->sewing_tension = problem.sewing_tension;
  report->sewing_end_time = end;
}

} // namespace

const std::vector<OptionSpec>& seam_option_specs() {
  static const std::vector<OptionSpec> specs = with_module_prefix(
      {
          {"seams-file", "FILE", "", "seams to sew (JSON, docs/formats.md) [tube_panels: its own]"},
          {"seam-stiffness", "N/M2", "", "seam stiffness per unit seam length, N/m^2 [automatic]"},
          {"seam-penalty", "P", "100", "automatic seam stiffness: P x modulus / seam spacing"},
          {"seam-merge", "", "", "sew, then merge matched seam vertices and solve again"},
          {"seam-merge-gap", "M", "1e-4", "--seam-merge: largest seam gap accepted as closed, m"},
          {"sewing-tension", "N/M", "",
           "dynamic: sew gradually: each seam spring starts pulling with this force per metre of "
           "seam and stiffens to its own stiffness by --sewing-time (0 or none: no sewing stage)"},
          {"sewing-time", "S", "", "the end of the sewing stage, s [half of --time-end]"},
      },
      {"seam", "sewing"}, {{"seams-file", "seam-file"}});
  return specs;
}

SeamCase read_seam_case(const Options& options) {
  SeamCase seam_case;
  if (options.is_set("seams-file")) seam_case.seams_file = options.text("seams-file");
  seam_case.penalty = options.positive_real("seam-penalty");
  if (options.is_set("seam-stiffness"))
    seam_case.stiffness = options.positive_real("seam-stiffness");
  seam_case.merge = options.flag("seam-merge");
  seam_case.merge_gap = options.positive_real("seam-merge-gap");
  if (options.is_set("sewing-tension"))
    seam_case.sewing_tension = options.nonnegative_real("sewing-tension");
  if (options.is_set("sewing-time")) seam_case.sewing_time = options.positive_real("sewing-time");
  return seam_case;
}

std::vector<Seam> case_seams(const SeamCase& seam_case, const MeshCase& mesh_case,
                             const TriangleMesh& mesh, int refinements) {
  std::vector<Seam> seams;
  if (!seam_case.seams_file.empty()) {
    seams = read_seams(seam_case.seams_file, mesh);
  } else if (mesh_case.kind == "tube_panels") {
    seams = tube_panels_mesh(mesh_case).seams;
  }
  if (!seams.empty() && refinements > 0) {
    throw InputError("seams and uniform refinement (--mesh-refine " + std::to_string(refinements) +
                     ") cannot be combined: refine the panels before listing their seam lines");
  }
  if (seams.empty() && (seam_case.merge || seam_case.stiffness || seam_case.sewing_tension)) {
    throw InputError("options --seam-merge, --seam-stiffness and --sewing-tension need seams: give "
                     "--seams-file or --mesh tube_panels");
  }
  return seams;
}

SeamStiffness case_seam_stiffness(const SeamCase& seam_case, const ClothMaterial& material) {
  SeamStiffness stiffness;
  stiffness.modulus =
      std::max(material.membrane.warp.initial_modulus(), material.membrane.weft.initial_modulus());
  stiffness.penalty = seam_case.penalty;
  if (seam_case.stiffness) stiffness.per_length = *seam_case.stiffness;
  return stiffness;
}

std::vector<SeamSpring> case_seam_springs(const SeamCase& seam_case, const TriangleMesh& mesh,
                                          const std::vector<Seam>& seams,
                                          const ClothMaterial& material) {
  return seam_springs(mesh, seams, case_seam_stiffness(seam_case, material));
}

void attach_seams(const SeamCase& seam_case, const TimeCase& time, const std::vector<Seam>& seams,
                  const ClothMaterial& material, ClothProblem& problem, SeamReport* report) {
  // Sewing starts with the seam springs stretched across the gap: residuals
  // of ~1e6 N, of which SNES's relative tolerance (1e-10) would accept a
  // final residual of 1e-4 N, a good fraction of the cloth's weight. Sewn
  // cases converge on the absolute tolerance instead (round-off of the
  // membrane forces, IncrementalSystem); -snes_rtol still overrides.
  SartorPetscCall(set_default_option("-snes_rtol", "0"));
  set_up_sewing(seam_case, time, problem, report);
  const std::vector<SeamSpring> springs =
      problem.set_seams(seams, case_seam_stiffness(seam_case, material));
  report->seams = seams.size();
  report->springs = springs.size();
  report->vertex_to_edge_springs = std::size_t(std::count_if(
      springs.begin(), springs.end(), [](const SeamSpring& spring) { return spring.to_edge; }));
  report->cross_rank_springs = problem.seam_coupling()->cross_rank_springs();
}

void sew_and_merge(const SeamCase& seam_case, const TimeCase& time, const ClothMaterial& material,
                   const Eigen::Vector3d& gravity, int load_steps, const std::vector<Seam>& seams,
                   TriangleMesh* mesh, std::vector<int>* pinned, SeamReport* report) {
  // Fails early, before the solve, for seams that cannot be merged.
  matched_vertex_pairs(*mesh, seams);
  std::vector<Eigen::Vector3d> positions;
  {
    ClothProblem sewing(PETSC_COMM_WORLD, *mesh, material, *pinned);
    sewing.loads.gravity = gravity;
    attach_seams(seam_case, time, seams, material, sewing, report);
    StaticOptions solve;
    solve.load_steps = load_steps;
    Vec x = nullptr;
    SartorPetscCall(sewing.create_solution(&x));
    SartorPetscCall(solve_static(sewing, x, solve, &report->sewing));
    SartorPetscCall(sewing.seam_gap(x, &report->gap_before_merge));
    SartorPetscCall(sewing.gather_positions(x, &positions));
    SartorPetscCall(VecDestroy(&x));
  }
  if (!report->sewing.converged) {
    throw SolveFailure("option --seam-merge: the sewing solve did not converge (" +
                       report->sewing.reason + "); try more --load-steps or -snes_monitor");
  }
  const double tolerance = seam_case.merge_gap;
  if (report->gap_before_merge > tolerance) {
    throw SolveFailure("option --seam-merge: the seams did not close (largest gap " +
                       format_number(report->gap_before_merge) + " m > --seam-merge-gap " +
                       format_number(tolerance) + " m); raise --seam-penalty or --seam-stiffness");
  }
  // Every rank holds the whole mesh: share the sewn placement.
  positions.resize(mesh->vertex_count());
  SartorPetscCall(
      MPI_Bcast(positions.data(), int(3 * positions.size()), MPI_DOUBLE, 0, PETSC_COMM_WORLD));
  TriangleMesh sewn = *mesh;
  sewn.positions = positions;
  const MergedMesh merged = merge_vertices(sewn, matched_vertex_pairs(sewn, seams));
  for (int& v : *pinned)
    v = merged.vertex_map[std::size_t(v)];
  std::sort(pinned->begin(), pinned->end());
  pinned->erase(std::unique(pinned->begin(), pinned->end()), pinned->end());
  report->merged = true;
  report->vertices_before_merge = mesh->vertex_count();
  report->vertices_after_merge = merged.mesh.vertex_count();
  *mesh = merged.mesh;
}

void add_seam_summary(const SeamReport& report, nlohmann::json& summary) {
  nlohmann::json seams = {{"seams", report.seams},
                          {"springs", report.springs},
                          {"vertex_to_edge_springs", report.vertex_to_edge_springs},
                          {"cross_rank_springs", report.cross_rank_springs},
                          {"largest_gap_m", report.gap},
                          {"sewing_tension_N_per_m", report.sewing_tension},
                          {"sewing_end_time_s", report.sewing_end_time},
                          {"merged", report.merged}};
  if (report.merged) {
    seams["merge"] = {{"gap_before_m", report.gap_before_merge},
                      {"vertices_before", report.vertices_before_merge},
                      {"vertices_after", report.vertices_after_merge},
                      {"sewing_converged", report.sewing.converged},
                      {"sewing_newton_iterations", report.sewing.newton_iterations},
                      {"sewing_pseudo_steps", report.sewing.pseudo_steps},
                      {"sewing_seconds", report.sewing.solve_seconds}};
  }
  summary["seams"] = seams;
}

} // namespace sartor
