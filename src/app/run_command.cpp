// sartor run: static equilibrium, or implicit dynamics, of a cloth described
// by a YAML case file.
// The case pipeline itself (solve_case) is shared with `sartor converge`.

#include "app/case_checks.hpp"
#include "app/certificate_case.hpp"
#include "app/cloth_case.hpp"
#include "app/commands.hpp"
#include "app/dynamic_case.hpp"
#include "app/load_case.hpp"
#include "app/material_case.hpp"
#include "app/mesh_case.hpp"
#include "app/refine_levels.hpp"
#include "app/seam_case.hpp"
#include "app/static_case.hpp"
#include "app/static_checkpoint.hpp"
#include "app/time_case.hpp"
#include "common/csv.hpp"
#include "common/error.hpp"
#include "common/output.hpp"
#include "fem/cloth_output.hpp"
#include "fem/petsc_call.hpp"
#include "mesh/generators.hpp"
#include "mesh/obj.hpp"
#include "solvers/statics.hpp"

#include <nlohmann/json.hpp>
#include <petscsys.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>

namespace sartor {

const CommandSpec& run_command() {
  static const CommandSpec spec{
      "run",
      "static equilibrium or dynamics of a cloth case (YAML options file)",
      "sartor run CASE.yaml [--option value ...] [-petsc_option ...]",
      "Builds the mesh, material, pins and loads the case describes, solves static\n"
      "equilibrium with Newton's method (PETSc SNES; loads ramped in --load-steps,\n"
      "failed steps cut back), and writes the result. CASE.yaml holds the options\n"
      "below without their dashes (load_steps: 4); options on the command line win.\n\n"
      "Output in DIR: result.h5 + result.xmf (open the .xmf in ParaView: positions,\n"
      "displacement, per-triangle strain and tension in warp and weft), final.obj,\n"
      "summary.json (energies, iterations, residuals, reactions, timings),\n"
      "petsc_options.txt (every option in effect), result.png (the cloth from the\n"
      "front, side and top, coloured by strain: postproc/plot_result.py; not with\n"
      "--no-plot).\n\n"
      "With --analysis dynamic it steps through time instead (backward Euler with\n"
      "lumped masses, from rest at the case's placement, pins following\n"
      "--pin-motion in time), prints progress every 5 % of the simulated time and\n"
      "also writes series.h5 + series.xmf (the states at --output-interval: open\n"
      "series.xmf in ParaView as a time series) and dynamics.csv (time, kinetic and\n"
      "potential energy, residual, iterations, probe displacement per step).\n\n"
      "With --analysis creep it follows the cloth's creep over real time (thesis\n"
      "Algorithm 2: equilibrium, then each element's creep update, with the loads\n"
      "scaled by --load-history and steps sized by --creep-tolerance) and writes\n"
      "series.h5 + series.xmf (with per-triangle creep strains) and creep.csv (one\n"
      "row per step).\n\n"
      "Runs write checkpoints with --checkpoint-interval (statics: after every\n"
      "load step, sewing stage and contact round for any interval > 0), and\n"
      "--restart resumes one where it stood (docs/reliability.md).\n\n"
      "examples:\n"
      "  sartor run cases/fe/hanging_sheet.yaml\n"
      "  sartor run cases/fe/hencky.yaml --mesh-rings 16 -snes_monitor\n"
      "  mpiexec -n 2 sartor run cases/fe/hanging_sheet.yaml\n"
      "  sartor run cases/fe/hanging_sheet_dynamic.yaml --time-end 2 --output-interval 0.05\n"
      "  sartor run cases/fe/cantilever_strip.yaml --pin-motion \"0:0,0,0; 1:0,0,0.1\"\n"
      "  sartor run cases/creep/strip.yaml --checkpoint-interval 600",
      [] {
        std::vector<OptionSpec> options = case_option_specs();
        options.push_back(
            {"output", "DIR", "out/run", "output folder (created; files in it are replaced)"});
        options.push_back({"checkpoint-interval", "S", "0",
                           "write a checkpoint every S seconds of simulated time (dynamic, "
                           "creep); statics: after every load step, stage and round if S > 0"});
        options.push_back({"checkpoint", "FILE", "", "the checkpoint file [OUTPUT/checkpoint.h5]"});
        options.push_back({"restart", "FILE", "", "resume from this checkpoint"});
        options.push_back({"no-plot", "", "", "write data only, no result.png"});
        options.push_back(refine_levels_option());
        return options;
      }(),
      1,
      true};
  return spec;
}

namespace {

nlohmann::json vector_json(const Eigen::Vector3d& v) {
  return {v[0], v[1], v[2]};
}

// The longest triangle edge in material coordinates, m.
double longest_material_edge(const TriangleMesh& mesh) {
  double longest = 0.0;
  for (const auto& uv : mesh.material_uv) {
    for (std::size_t c = 0; c < 3; ++c)
      longest = std::max(longest, (uv[(c + 1) % 3] - uv[c]).norm());
  }
  return longest;
}

void broadcast(double* values, int count) {
  MPI_Bcast(values, count, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
}

// Stages meant to converge that stopped at the iteration limit: the result
// is an equilibrium, but one the stages' round-off may have chosen.
void warn_unconverged_stages(const StaticReport& report) {
  if (report.unconverged_stages.empty()) return;
  std::string stages;
  for (int stage : report.unconverged_stages)
    stages += (stages.empty() ? "" : ", ") + std::to_string(stage);
  print_warnings({"sewing stage(s) " + stages + " of " + std::to_string(report.sewing_stages) +
                  " stopped at -snes_max_it before reaching the tolerance: the stages after "
                  "them started from a state that round-off moves, so the drape may land "
                  "elsewhere on another machine; raise -snes_max_it "
                  "(docs/drape.md#sewing-by-continuation)"});
}

// A checkpoint within a level of a drape on several levels resumes that
// level only, and a level resumes only from such a checkpoint.
void check_drape_level(const CaseCheckpointing& checkpointing, const std::string& drape_level) {
  if (drape_level.empty() == checkpointing.drape_level.empty()) return;
  throw InputError(checkpointing.restart_file +
                   (drape_level.empty()
                        ? ": the checkpoint is of a run on one mesh (sartor run, or a drape "
                          "with --levels 1); resume it as one"
                        : ": the checkpoint is within a level of a drape on several levels; "
                          "resume it with the same --levels"));
}

// --analysis dynamic: from rest, or from --restart's checkpoint, with
// checkpoints as `checkpointing` says.
void solve_dynamic_case(const TimeCase& time, ClothProblem& problem, Vec x,
                        const CaseStepObserver& observe, const CaseCheckpointing& checkpointing,
                        CaseResult* result) {
  // Starts at rest (or where a checkpoint left it); the probe is followed
  // step by step for dynamics.csv.
  Vec v = nullptr;
  SartorPetscCall(VecDuplicate(x, &v));
  SartorPetscCall(VecSet(v, 0.0));
  DynamicReport report;
  std::optional<DynamicResume> resume;
  if (!checkpointing.restart_file.empty()) {
    resume = read_dynamic_checkpoint(checkpointing.restart_file, problem);
    check_drape_level(checkpointing, resume->drape_level);
    if (time.time_end < resume->control.time) {
      throw InputError("option --time-end: " + format_number(time.time_end) + " s is before " +
                       checkpointing.restart_file + "'s time, " +
                       format_number(resume->control.time) + " s");
    }
    SartorPetscCall(resume->restore(problem, x, v));
    report = resume->report;
    result->probe_history = resume->probe_history;
    result->resumed_time = resume->control.time;
    SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD, "sartor: resuming from %s at t = %g s\n",
                                checkpointing.restart_file.c_str(), resume->control.time));
  }
  const DynamicObserver follow = [&](const DynamicStepReport& step, Vec state,
                                     Vec) -> PetscErrorCode {
    if (result->probe) {
      std::vector<Eigen::Vector3d> positions;
      SartorPetscCall(problem.gather_positions(state, &positions));
      double d[3] = {0.0, 0.0, 0.0};
      if (is_root()) {
        const std::size_t p = result->probe->vertex;
        for (int k = 0; k < 3; ++k)
          d[k] = positions[p][k] - result->mesh.positions[p][k];
      }
      broadcast(d, 3);
      result->probe_history.emplace_back(d[0], d[1], d[2]);
    }
    if (observe) observe(problem, state, {step.time, step.output, nullptr});
    return 0;
  };
  DynamicCheckpoints checkpoints;
  checkpoints.resume = resume ? &resume->control : nullptr;
  checkpoints.interval = checkpointing.interval;
  check_time_divisions(time.time_end, "time-end", checkpointing.interval, "checkpoint-interval");
  if (checkpointing.interval > 0.0) {
    checkpoints.write = dynamic_checkpoint_writer(
        problem, checkpointing, report, result->probe_history, &result->checkpoints_written);
  }
  SartorPetscCall(
      solve_dynamic(problem, x, v, dynamic_options(time), &report, follow, checkpoints));
  SartorPetscCall(VecDestroy(&v));
  result->converged = report.completed;
  result->solve_seconds = report.solve_seconds;
  result->dynamics = std::move(report);
}

// Statics: solve_static, from --restart's checkpoint when given, with a
// checkpoint after every sewing stage and contact round when asked.
void solve_static_case(ClothProblem& problem, Vec x, const StaticOptions& solve,
                       const CaseCheckpointing& checkpointing, CaseResult* result) {
  StaticOptions checkpointed = solve;
  std::optional<StaticResume> resume;
  if (!checkpointing.restart_file.empty()) {
    resume = read_static_checkpoint(checkpointing.restart_file, problem);
    check_drape_level(checkpointing, resume->drape_level);
    SartorPetscCall(resume->restore(problem, x));
    checkpointed.resume = &resume->report;
    if (is_root())
      result->last_checkpoint = std::make_shared<const RunCheckpoint>(resume->checkpoint);
    result->resumed_time = 0.0;
    SartorPetscCall(PetscPrintf(
        PETSC_COMM_WORLD,
        "sartor: resuming from %s after %zu load step(s) (load factor %g), %d contact round(s)\n",
        checkpointing.restart_file.c_str(), resume->report.steps.size(),
        resume->checkpoint.load_factor, resume->report.contact_rounds));
  }
  if (checkpointing.interval > 0.0)
    checkpointed.checkpoint = static_checkpoint_writer(
        problem, checkpointing, &result->checkpoints_written, &result->last_checkpoint);
  SartorPetscCall(solve_static(problem, x, checkpointed, &result->report));
  reject_unmet_residual(problem.force_scale(), &result->report);
  warn_unconverged_stages(result->report);
}

// --analysis, checked with the options that only some analyses take, and
// what the analysis needs of the built cloth: stiffness out of a flat
// membrane's plane in statics, a positive areal density in dynamics.
// Self-contact keeps each vertex on its side of the cloth by the
// minimiser's step bound: SNES's steps have none.
void check_self_contact(const ClothCase& cloth_case) {
  if (!cloth_case.contact.self_contact.enabled) return;
  const TimeCase& time = cloth_case.time;
  if (time.creep())
    throw InputError("option --self-contact: --analysis creep has no self-contact yet");
  if (time.dynamic() && !time.minimise)
    throw InputError("option --self-contact needs --dynamic-solver minimise with --analysis "
                     "dynamic (SNES's steps have no bound that keeps cloth from passing through "
                     "itself)");
  if (!time.dynamic() && !cloth_case.statics.minimise)
    throw InputError("option --self-contact needs --static-solver minimise (SNES's steps have no "
                     "bound that keeps cloth from passing through itself)");
}

void check_analysis(const ClothCase& cloth_case, const TriangleMesh& mesh,
                    const std::vector<ClothMaterial>& materials, const std::vector<int>& pinned,
                    const ClothMaterial& material) {
  const TimeCase& time = cloth_case.time;
  if (!cloth_case.inapplicable_option.empty()) throw InputError(cloth_case.inapplicable_option);
  const bool quasi_static = !time.dynamic() && !(cloth_case.creep && cloth_case.creep->dynamic);
  reject_flat_membrane_without_bending(quasi_static, cloth_case.loads.pressure != 0.0, mesh,
                                       materials, pinned);
  if ((time.dynamic() || time.creep()) && cloth_case.loads.pin_move != Eigen::Vector3d::Zero()) {
    throw InputError("option --pin-move ramps the pins with the load in statics; with --analysis " +
                     time.analysis +
                     " give a history in time: --pin-motion \"0:0,0,0; T:DX,DY,DZ\"");
  }
  if (time.dynamic() && material.areal_density <= 0.0) {
    throw InputError("option --density: --analysis dynamic needs a positive areal density, got " +
                     format_number(material.areal_density));
  }
  check_self_contact(cloth_case);
}

// The mesh vertex nearest the --probe point.
CaseProbe case_probe(const Eigen::Vector3d& point, const TriangleMesh& mesh) {
  CaseProbe probe;
  probe.point = point;
  for (std::size_t v = 1; v < mesh.vertex_count(); ++v) {
    if ((mesh.positions[v] - probe.point).norm() <
        (mesh.positions[probe.vertex] - probe.point).norm())
      probe.vertex = v;
  }
  probe.initial_position = mesh.positions[probe.vertex];
  probe.displacement.setZero();
  return probe;
}

// Creep: run_creep_case, the observer seeing the coupling's state.
void solve_creep_case(const CreepCase& creep, const TimeCase& time, int load_steps,
                      const std::string& fabric, ClothProblem& problem, Vec x,
                      const CaseStepObserver& observe, const CaseCheckpointing& checkpointing,
                      CaseResult* result) {
  CreepCoupling coupling(problem, {creep_material(creep, fabric)});
  const CreepStateObserver follow = [&](Vec state, const CreepStepReport& step) {
    if (observe) observe(problem, state, {step.time, step.output, &coupling});
  };
  CreepRunResult run =
      run_creep_case(creep, time, load_steps, problem, x, checkpointing,
                     result->probe ? long(result->probe->vertex) : -1L, coupling, follow);
  result->converged = run.report.completed;
  result->solve_seconds = run.report.solve_seconds;
  result->creep = std::move(run);
}

// The largest displacement and the probe's, from the positions rank 0
// holds: it measures, everybody learns.
void measure_displacements(const TriangleMesh& mesh, CaseResult* result) {
  double measured[4] = {0.0, 0.0, 0.0, 0.0};
  if (is_root()) {
    for (std::size_t v = 0; v < result->positions.size(); ++v) {
      measured[0] = std::max(measured[0], (result->positions[v] - mesh.positions[v]).norm());
    }
    if (result->probe) {
      const Eigen::Vector3d d =
          result->positions[result->probe->vertex] - mesh.positions[result->probe->vertex];
      measured[1] = d.x();
      measured[2] = d.y();
      measured[3] = d.z();
    }
  }
  broadcast(measured, 4);
  result->max_displacement = measured[0];
  if (result->probe) result->probe->displacement = {measured[1], measured[2], measured[3]};
}

} // namespace

void assign_panel_fabrics(const std::vector<garment::Panel>& panels, CaseCloth* cloth) {
  std::vector<int> fabric_of_panel;
  for (const garment::Panel& panel : panels) {
    auto found = std::find(cloth->fabrics.begin(), cloth->fabrics.end(), panel.fabric);
    if (found == cloth->fabrics.end()) found = cloth->fabrics.insert(found, panel.fabric);
    fabric_of_panel.push_back(int(found - cloth->fabrics.begin()));
  }
  for (int& id : cloth->mesh.material_ids)
    id = fabric_of_panel[std::size_t(id)];
}

void name_single_fabric(const CaseCloth& cloth, Options* options) {
  if (cloth.fabrics.size() == 1) options->set("fabric", cloth.fabrics.front());
}

CaseResult solve_case(const ClothCase& cloth_case, int extra_refinements,
                      const CaseStepObserver& observe, const CaseCheckpointing& checkpointing,
                      const CaseCloth* cloth, const std::vector<Eigen::Vector3d>* start) {
  const auto started = std::chrono::steady_clock::now();
  CaseResult result;
  const MeshCase& mesh_case = cloth_case.mesh;
  const TimeCase& time = cloth_case.time;
  result.mesh =
      build_mesh(mesh_case, extra_refinements, &result.mesh_refine, cloth ? &cloth->mesh : nullptr);
  const TriangleMesh& mesh = result.mesh;
  // One material per fabric: the cloth's, or --fabric's.
  const MaterialCase& material_case = cloth_case.material;
  const std::vector<ClothMaterial> materials = case_materials(
      material_case, cloth ? cloth->fabrics : std::vector<std::string>{material_case.fabric},
      mesh.creases.size());
  const SeamCase& seam_case = cloth_case.seams;
  if (materials.size() > 1 && (seam_case.merge || time.creep())) {
    throw InputError("the cloth has " + std::to_string(materials.size()) +
                     " fabrics; --seam-merge and --analysis creep need one: give --fabric");
  }
  const ClothMaterial& material = stiffest_material(materials);
  const LoadCase& load_case = cloth_case.loads;
  const StaticCase& statics = cloth_case.statics;
  std::vector<int> pinned = pinned_vertices(load_case, mesh);
  // Seams (app/seam_case.hpp): sewn by springs, or sewn first and merged.
  const std::vector<Seam> seams = case_seams(seam_case, mesh_case, mesh, result.mesh_refine);
  if (!seams.empty()) result.seams = SeamReport{};
  if (!seams.empty() && seam_case.merge) {
    if (load_case.point_force) {
      throw InputError("option --point-force names a vertex of the unmerged mesh; it cannot be "
                       "combined with --seam-merge");
    }
    sew_and_merge(seam_case, time, material, load_case.gravity, statics.load_steps, seams,
                  &result.mesh, &pinned, &*result.seams);
  }
  result.pinned_vertices = pinned.size();
  result.h = longest_material_edge(mesh);

  const std::vector<double> release_times = pin_release_times(load_case, mesh, pinned);
  ClothProblem problem(PETSC_COMM_WORLD, mesh, materials, pinned, release_times);
  set_case_loads(load_case, mesh, &problem.loads);
  problem.pin_motion = load_case.pin_move;
  problem.pin_groups = pin_groups(load_case, mesh, pinned);
  const ContactCase& contact_case = cloth_case.contact;
  set_up_contact(contact_case, problem);
  problem.contact.project_hessian = material_case.project_membrane;
  if (result.seams && !result.seams->merged) {
    // Static sewing stages start from this pull (before the springs are made).
    if (time.analysis == "static" && statics.sewing_stages > 1)
      problem.sewing_tension = statics.sewing_start_tension;
    attach_seams(seam_case, time, seams, material, problem, &*result.seams);
  }
  set_up_self_contact(contact_case, problem);
  check_analysis(cloth_case, mesh, materials, pinned, material);
  const bool dynamic = time.dynamic();
  const bool creep = time.creep();
  const StaticOptions solve = static_options(statics, problem.seam_coupling());
  if (load_case.probe) result.probe = case_probe(*load_case.probe, mesh);
  result.dofs = problem.global_dof_count();
  const auto set_up = std::chrono::steady_clock::now();

  Vec x = nullptr;
  SartorPetscCall(problem.create_solution(&x));
  if (start) SartorPetscCall(problem.set_solution(*start, x));
  if (dynamic) {
    solve_dynamic_case(time, problem, x, observe, checkpointing, &result);
  } else if (creep) {
    solve_creep_case(*cloth_case.creep, time, statics.load_steps, material_case.fabric, problem, x,
                     observe, checkpointing, &result);
  } else {
    solve_static_case(problem, x, solve, checkpointing, &result);
  }
  // The final state of statics, or of a settle, is certified (a saddle is not converged).
  const bool settled = result.dynamics && result.dynamics->settled;
  const CertificateCase& certificate = cloth_case.certificate;
  if (!creep && (!dynamic || settled) && certificate.certify) {
    result.certified =
        certify_case(certificate, problem, x, dynamic ? nullptr : &solve, &result.report);
  }
  if (!dynamic && !creep) {
    reject_unmet_residual(problem.force_scale(), &result.report);
    result.converged =
        result.report.converged && !(result.certified && result.certified->certificate.saddle());
    result.solve_seconds = result.report.solve_seconds;
    if (!checkpointing.final_state.empty())
      SartorPetscCall(write_final_static_state(problem, x, checkpointing, result.report));
  }
  result.cpu_at_end = process_cpu_seconds();
  result.load_factor = problem.load_factor;

  SartorPetscCall(problem.energy(x, &result.energy));
  if (result.seams) SartorPetscCall(problem.seam_gap(x, &result.seams->gap));
  SartorPetscCall(problem.pin_reaction(x, &result.pin_reaction));
  SartorPetscCall(problem.gather_positions(x, &result.positions));
  SartorPetscCall(problem.gather_strains(x, &result.strains));
  SartorPetscCall(problem.gather_vertex_loads(x, &result.vertex_loads));
  result.contact = measure_contact(contact_case, problem, x, result.positions);
  if (cloth && cloth->after_statics && !dynamic && !creep && result.converged) {
    const bool springs = !seams.empty() && !(result.seams && result.seams->merged);
    cloth->after_statics(problem, materials,
                         springs ? case_seam_springs(seam_case, mesh, seams, material)
                                 : std::vector<SeamSpring>{},
                         x, result.last_checkpoint);
  }
  SartorPetscCall(VecDestroy(&x));

  measure_displacements(mesh, &result);
  const auto finished = std::chrono::steady_clock::now();
  result.setup_seconds = std::chrono::duration<double>(set_up - started).count();
  result.total_seconds = std::chrono::duration<double>(finished - started).count();
  return result;
}

namespace {

void add_statics_summary(const StaticReport& report, nlohmann::json& summary) {
  summary["solver"] = {{"reason", report.reason},
                       {"load_steps", report.steps.size()},
                       {"newton_iterations", report.newton_iterations},
                       {"linear_iterations", report.linear_iterations},
                       {"initial_residual_norm", report.initial_residual_norm},
                       {"final_residual_norm", report.final_residual_norm},
                       {"method", report.minimised ? "minimise" : "snes"}};
  if (report.minimised) {
    summary["solver"]["minimiser"] = {
        {"step_bound_cuts", report.minimiser.step_bound_cuts},
        {"regularised_steps", report.minimiser.regularised_steps},
        {"residual_rule_trials", report.minimiser.residual_rule_trials},
        {"failed_factorisations", report.minimiser.failed_factorisations},
        {"exact_steps", report.minimiser.exact_steps},
        {"extended_steps", report.minimiser.extended_steps},
        {"sewing_stages", report.sewing_stages},
        {"unconverged_stages", report.unconverged_stages},
        {"stalled_stage_resolves", report.stalled_stage_resolves},
        {"contact_rounds", report.contact_rounds},
        {"contact_round_failed", report.contact_round_failed},
        {"contact_stiffness_scale", report.contact_stiffness_scale},
        {"sliding_vertices", report.sliding_vertices},
        {"friction_consistent", report.friction_consistent},
        {"anchored_residual_N", report.anchored_residual_norm},
        {"consistency_tolerance_N", report.consistency_tolerance}};
    nlohmann::json rounds = nlohmann::json::array();
    for (const ContactRound& round : report.rounds) {
      rounds.push_back({{"newton_iterations", round.newton_iterations},
                        {"anchored_residual_N", round.residual_norm},
                        {"sliding_vertices", round.sliding_vertices},
                        {"contact_stiffness_scale", round.contact_stiffness_scale}});
    }
    summary["solver"]["minimiser"]["rounds"] = rounds;
  }
  summary["load_steps"] = nlohmann::json::array();
  for (const auto& step : report.steps) {
    summary["load_steps"].push_back({{"load_factor", step.load_factor},
                                     {"converged", step.converged},
                                     {"reason", step.reason},
                                     {"newton_iterations", step.newton_iterations},
                                     {"linear_iterations", step.linear_iterations},
                                     {"residual_norm", step.residual_norm}});
  }
}

void add_dynamics_summary(const CaseResult& result, nlohmann::json& summary) {
  const DynamicReport& report = *result.dynamics;
  const std::size_t accepted = report.steps.empty() ? 0 : report.steps.size() - 1;
  nlohmann::json history = nlohmann::json::array();
  for (const auto& step : report.steps) {
    history.push_back({{"step", step.step},
                       {"time_s", step.time},
                       {"dt_s", step.dt},
                       {"newton_iterations", step.newton_iterations},
                       {"linear_iterations", step.linear_iterations},
                       {"rejected", step.rejected},
                       {"kinetic_energy_J", step.kinetic_energy},
                       {"potential_energy_J", step.potential_energy},
                       {"static_residual_norm", step.static_residual_norm},
                       {"velocities_reset", step.velocities_reset},
                       {"output", step.output}});
  }
  summary["dynamics"] = {
      {"completed", report.completed},
      {"at_rest", report.at_rest},
      {"reason",
       report.completed ? (report.at_rest ? "at rest" : "reached the end time") : report.reason},
      {"final_time_s", report.final_time},
      {"steps", accepted},
      {"rejected_steps", report.rejected_steps},
      {"newton_iterations", report.newton_iterations},
      {"linear_iterations", report.linear_iterations},
      {"newton_iterations_per_step",
       accepted ? double(report.newton_iterations) / double(accepted) : 0.0},
      {"velocity_resets", report.velocity_resets},
      {"settle", report.settle_reason.empty()
                     ? nlohmann::json(nullptr)
                     : nlohmann::json{{"converged", report.settled},
                                      {"reason", report.settle_reason},
                                      {"newton_iterations", report.settle_newton_iterations},
                                      {"contact_rounds", report.settle_contact_rounds},
                                      {"contact_round_failed", report.settle_contact_round_failed},
                                      {"residual_norm", report.settle_residual_norm}}},
      {"steps_per_second",
       report.solve_seconds > 0 ? double(accepted) / report.solve_seconds : 0.0},
      {"history", history},
      {"checkpoints_written", result.checkpoints_written},
      {"resumed", result.resumed_time >= 0.0}};
  if (result.resumed_time >= 0.0) summary["dynamics"]["resumed_from_time_s"] = result.resumed_time;
}

void add_creep_summary(const CreepRunResult& run, nlohmann::json& summary) {
  const CreepReport& report = run.report;
  long accepted = 0;
  for (const auto& step : report.steps)
    accepted += step.step > 0 ? 1 : 0;
  summary["creep"] = {{"scheme", run.scheme},
                      {"completed", report.completed},
                      {"reason", report.completed ? "reached the end time" : report.reason},
                      {"final_time_s", report.final_time},
                      {"steps", accepted},
                      {"rejected_steps", report.rejected_steps},
                      {"newton_iterations", report.newton_iterations},
                      {"checkpoints_written", run.checkpoints_written},
                      {"resumed", run.resumed}};
  if (run.resumed) summary["creep"]["resumed_from_time_s"] = run.resumed_time;
}

// dynamics.csv: one row per state (the initial one first).
std::string dynamics_csv(const CaseResult& result) {
  std::ostringstream csv;
  csv << "time_s,dt_s,kinetic_energy_J,potential_energy_J,total_energy_J,static_residual_N,"
         "newton_iterations,rejected";
  if (result.probe) csv << ",probe_dx_m,probe_dy_m,probe_dz_m";
  csv << "\n";
  const auto& steps = result.dynamics->steps;
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const DynamicStepReport& s = steps[k];
    csv << format_number(s.time) << ',' << format_number(s.dt) << ','
        << format_number(s.kinetic_energy) << ',' << format_number(s.potential_energy) << ','
        << format_number(s.kinetic_energy + s.potential_energy) << ','
        << format_number(s.static_residual_norm) << ',' << s.newton_iterations << ',' << s.rejected;
    if (result.probe && k < result.probe_history.size()) {
      for (int d = 0; d < 3; ++d)
        csv << ',' << format_number(result.probe_history[k][d]);
    }
    csv << "\n";
  }
  return csv.str();
}

} // namespace

void add_case_summary(const CaseResult& result, nlohmann::json& summary) {
  summary["mesh"] = {{"vertices", result.mesh.vertex_count()},
                     {"triangles", result.mesh.triangle_count()},
                     {"pinned_vertices", result.pinned_vertices},
                     {"dofs", result.dofs}};
  summary["converged"] = result.converged;
  if (result.dynamics) {
    add_dynamics_summary(result, summary);
  } else if (result.creep) {
    add_creep_summary(*result.creep, summary);
  } else {
    add_statics_summary(result.report, summary);
  }
  summary["energy_J"] = {{"membrane", result.energy.membrane},
                         {"bending", result.energy.bending},
                         {"external", result.energy.external},
                         {"total", result.energy.total()}};
  if (result.seams) {
    summary["energy_J"]["seam"] = result.energy.seam;
    add_seam_summary(*result.seams, summary);
  }
  summary["pin_reaction_N"] = vector_json(result.pin_reaction);
  summary["max_displacement_m"] = result.max_displacement;
  if (result.probe) {
    summary["probe"] = {{"vertex", result.probe->vertex},
                        {"initial_position_m", vector_json(result.probe->initial_position)},
                        {"displacement_m", vector_json(result.probe->displacement)}};
  }
  if (!result.contact.bodies.empty() || result.contact.self_contact)
    summary["contact"] = contact_summary(result.contact);
  if (result.certified) {
    summary["certificate"] = certificate_json(result.certified->certificate);
    summary["certificate"]["saddle_escapes"] = result.certified->escapes;
    summary["certificate"]["saddle_push_m"] = result.certified->push_size;
  }
  summary["timing_s"] = {{"setup", result.setup_seconds},
                         {"solve", result.solve_seconds},
                         {"total", result.total_seconds}};
}

void write_case_results(const std::string& directory, const CaseResult& result,
                        const nlohmann::json& summary, const ClothOutputLabels& labels) {
  if (!is_root()) return;
  write_cloth_results(directory, result.mesh, result.positions, result.strains, labels,
                      result.vertex_loads);
  if (result.dynamics) write_file_atomically(directory + "/dynamics.csv", dynamics_csv(result));
  if (result.creep) write_file_atomically(directory + "/creep.csv", result.creep->history_csv);
  write_json(directory + "/summary.json", summary);
}

// Whether the option of database key `key` was given by its other name as
// well, and that one counts (the command line's): re-read, both would clash.
bool superseded(const std::string& key, const std::vector<std::string>& table,
                const Options& options) {
  if (key.size() < 2 || key[0] != '-') return false;
  std::string name = key.substr(1);
  std::replace(name.begin(), name.end(), '_', '-');
  const std::string other = options.other_name(name);
  if (other.empty()) return false;
  const std::string other_key = database_key(other);
  const bool both = std::any_of(table.begin(), table.end(), [&](const std::string& line) {
    return line == other_key || line.rfind(other_key + " ", 0) == 0;
  });
  return both && options.name_given(name) != name;
}

// PETSc lists one option a line, `-name value`, but reads a file back word by
// word: a value with spaces (--body "mannequin mu=0.3") is quoted so that
// `-options_file petsc_options.txt` re-runs the job. The command's own
// defaults go in before the table's last line; -output names the directory
// written (which a command may have chosen in place of the database's:
// `sartor edit DRAPE_DIR` does not write into the drape's).
std::string echoed_options(const std::string& path, const std::string& directory,
                           const Options& options) {
  std::ifstream lines(path);
  std::vector<std::string> table;
  for (std::string line; std::getline(lines, line);)
    table.push_back(line);
  const bool closed = !table.empty() && table.back().rfind("#End", 0) == 0;
  auto end = closed ? table.end() - 1 : table.end();
  for (const auto& [key, value] : options.command_defaults())
    end = table.insert(end, key + " " + value) + 1;
  std::string quoted;
  for (std::string line : table) {
    if (line.rfind("-output ", 0) == 0) line = "-output " + directory;
    const std::size_t space = line.find(' ');
    if (superseded(line.substr(0, space), table, options)) continue;
    if (line.rfind('-', 0) == 0 && space != std::string::npos &&
        line.find_first_of(" \t", space + 1) != std::string::npos) {
      line = line.substr(0, space) + " \"" + line.substr(space + 1) + "\"";
    }
    quoted += line + "\n";
  }
  return quoted;
}

std::vector<Eigen::Vector3d> broadcast_positions(std::vector<Eigen::Vector3d> positions,
                                                 std::size_t count) {
  positions.resize(count);
  static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double), "packed vectors");
  SartorPetscCall(
      MPI_Bcast(positions.data()->data(), int(3 * count), MPI_DOUBLE, 0, PETSC_COMM_WORLD));
  return positions;
}

void write_petsc_options(const std::string& directory, const Options& options) {
  const std::string path = directory + "/petsc_options.txt";
  PetscViewer viewer = nullptr;
  SartorPetscCall(PetscViewerASCIIOpen(PETSC_COMM_WORLD, path.c_str(), &viewer));
  SartorPetscCall(PetscOptionsView(nullptr, viewer));
  SartorPetscCall(PetscViewerDestroy(&viewer));
  if (is_root()) write_file_atomically(path, echoed_options(path, directory, options));
}

CaseStepObserver series_writer(const std::string& directory, const ClothOutputLabels& labels,
                               const std::string& resumed_from) {
  auto series = std::make_shared<std::unique_ptr<ClothTimeSeries>>();
  return [directory, series, labels, resumed_from](ClothProblem& problem, Vec x,
                                                   const CaseState& state) {
    if (!state.output) return;
    std::vector<Eigen::Vector3d> positions;
    std::vector<element::MembraneStrain> strains;
    std::vector<ElementCreep> creep;
    SartorPetscCall(problem.gather_positions(x, &positions));
    SartorPetscCall(problem.gather_strains(x, &strains));
    if (state.creep) SartorPetscCall(state.creep->gather(&creep));
    if (!is_root()) return;
    std::vector<ClothTimeSeries::CellField> fields;
    if (state.creep) {
      fields = {{"viscoelastic_warp", {}},
                {"permanent_warp", {}},
                {"viscoelastic_weft", {}},
                {"permanent_weft", {}}};
      for (const ElementCreep& c : creep) {
        fields[0].values.push_back(c.warp.viscoelastic);
        fields[1].values.push_back(c.warp.permanent);
        fields[2].values.push_back(c.weft.viscoelastic);
        fields[3].values.push_back(c.weft.permanent);
      }
    }
    if (!*series && !resumed_from.empty()) {
      *series = std::make_unique<ClothTimeSeries>(directory, problem.mesh(), labels,
                                                  checkpoint_time(resumed_from));
    }
    if (!*series) *series = std::make_unique<ClothTimeSeries>(directory, problem.mesh(), labels);
    (*series)->write(state.time, positions, strains, fields);
  };
}

CaseCheckpointing case_checkpointing(const Options& options, const std::string& directory) {
  CaseCheckpointing checkpointing;
  checkpointing.interval = options.nonnegative_real("checkpoint-interval");
  checkpointing.file =
      options.is_set("checkpoint") ? options.text("checkpoint") : directory + "/checkpoint.h5";
  if (options.is_set("restart")) checkpointing.restart_file = options.text("restart");
  if (checkpointing.interval > 0.0 || !checkpointing.restart_file.empty()) {
    if (is_root()) make_output_directory(directory);
  }
  return checkpointing;
}

int run_run(const Invocation& invocation) {
  const Options& options = invocation.options;
  const std::string directory = options.text("output");
  // Dynamic runs write their states at output times into series.h5/.xmf.
  const ClothOutputLabels labels{{options.text("fabric")}, {}, {}};
  const CaseCheckpointing checkpointing = case_checkpointing(options, directory);
  const CaseStepObserver write_state = series_writer(directory, labels, checkpointing.restart_file);
  const ClothCase cloth_case = read_cloth_case(options);
  std::vector<RefineLevelRun> levels;
  const CaseResult result =
      solve_on_refine_levels(cloth_case, int(options.integer_in("refine-levels", 1, 8)),
                             write_state, checkpointing, &levels);

  nlohmann::json summary = run_metadata(invocation, "run");
  summary["case"] = invocation.command_line.positionals.at(0);
  add_case_summary(result, summary);
  if (!levels.empty()) summary["levels"] = refine_levels_json(levels);
  write_case_results(directory, result, summary, labels);
  write_petsc_options(directory, options);
  if (invocation.keep_result) invocation.keep_result(result, summary, labels);
  if (!options.flag("no-plot")) make_plot("plot_result.py", directory);

  if (result.creep) {
    const CreepReport& report = result.creep->report;
    SartorPetscCall(PetscPrintf(
        PETSC_COMM_WORLD,
        "sartor run: %zu triangles, creep to t = %g s in %zu steps (%ld rejected), %d Newton "
        "iterations; wrote %s\n",
        result.mesh.triangle_count(), report.final_time, report.steps.size(), report.rejected_steps,
        int(report.newton_iterations), directory.c_str()));
    if (!report.completed) {
      throw SolveFailure("the creep run stopped at t = " + format_number(report.final_time) +
                         " s: " + report.reason + "; " + directory +
                         " holds the last accepted state. Try a smaller --creep-tolerance or "
                         "-snes_monitor");
    }
    return 0;
  }
  if (result.dynamics) {
    const DynamicReport& report = *result.dynamics;
    SartorPetscCall(PetscPrintf(
        PETSC_COMM_WORLD,
        "sartor run: %zu triangles, dynamic to t = %g s in %zu steps (%d rejected), %d Newton "
        "iterations%s%s%s; wrote %s\n",
        result.mesh.triangle_count(), report.final_time, report.steps.size() - 1,
        int(report.rejected_steps), int(report.newton_iterations),
        report.at_rest ? ", at rest" : "", result.certified ? "; certificate of the settle: " : "",
        result.certified ? result.certified->certificate.verdict().c_str() : "",
        directory.c_str()));
    if (!report.completed) {
      throw SolveFailure(report.reason + "; " + directory +
                         " holds the last accepted state. Try a smaller --time-step, --damping, "
                         "or -snes_monitor");
    }
    return 0;
  }
  const std::string verdict = certificate_verdict(cloth_case.certificate, result.certified);
  SartorPetscCall(
      PetscPrintf(PETSC_COMM_WORLD,
                  "sartor run: %zu triangles, %s after %d Newton iterations in %zu load "
                  "step(s), residual %.3e; certificate: %s; wrote %s\n",
                  result.mesh.triangle_count(), result.report.reason.c_str(),
                  int(result.report.newton_iterations), result.report.steps.size(),
                  result.report.final_residual_norm, verdict.c_str(), directory.c_str()));
  if (result.report.converged && result.certified && result.certified->certificate.saddle()) {
    throw SolveFailure("the static solve ended on a saddle, not a minimum: the true Hessian has " +
                       std::to_string(result.certified->certificate.stability.negative) +
                       " direction(s) of descent (summary.json: certificate); " + directory +
                       " holds it. Try --escape-saddles N or another start");
  }
  if (!result.converged) {
    // The minimiser is globalised: smaller load steps rarely help it, a
    // larger iteration budget does (a flat start far from equilibrium).
    const std::string hint = result.report.minimised
                                 ? "Try a larger -snes_max_it (Newton iterations per load step) "
                                   "or -snes_monitor"
                                 : "Try more --load-steps or -snes_monitor";
    throw SolveFailure("the static solve did not converge (" + result.report.reason +
                       " at load factor " + format_number(result.load_factor) + "); " + directory +
                       " holds the last converged state. " + hint);
  }
  return 0;
}

} // namespace sartor
