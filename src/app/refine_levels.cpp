#include "app/refine_levels.hpp"

#include "app/commands.hpp"
#include "app/log_stage.hpp"
#include "app/progressive_drape.hpp"
#include "common/csv.hpp"
#include "common/error.hpp"
#include "fem/petsc_call.hpp"
#include "mesh/generators.hpp"

#include <nlohmann/json.hpp>
#include <petscsys.h>

namespace sartor {

namespace {

// The mesh a level solves: the case's with `extra` refinements more (fewer
// where negative).
TriangleMesh level_mesh(const ClothCase& cloth_case, int extra) {
  int refinements = 0;
  return build_mesh(cloth_case.mesh, extra, &refinements, nullptr);
}

// The finer level's start: `fine` (the finer mesh as built) placed at the
// refinement of `coarse` at its solved positions, which numbers vertices
// and triangles as `fine` does when `fine` is `coarse` refined.
std::vector<Eigen::Vector3d> prolong(const TriangleMesh& coarse,
                                     std::vector<Eigen::Vector3d> solved, const TriangleMesh& fine,
                                     const std::string& kind) {
  TriangleMesh deformed = coarse;
  deformed.positions = std::move(solved);
  TriangleMesh refined = mesh::refine(deformed);
  if (refined.triangles != fine.triangles) {
    throw InputError("the case's mesh (--mesh-kind " + kind +
                     ") is not the refinement of its coarser mesh by splitting every triangle "
                     "in four, so a level cannot start from the one before: solve it without "
                     "--refine-levels or --prolong");
  }
  return std::move(refined.positions);
}

void record(const CaseResult& result, const CertificateCase& certificate, RefineLevelRun* run) {
  run->refinements = result.mesh_refine;
  run->vertices = result.mesh.vertex_count();
  run->triangles = result.mesh.triangle_count();
  run->longest_edge = result.h;
  run->converged = result.converged;
  run->newton_iterations = long(result.report.newton_iterations);
  run->residual_force = result.report.final_residual_norm;
  if (result.certified) run->certificate = certificate_verdict(certificate, result.certified);
  run->drape = result.contact.drape;
  run->solve_seconds = result.solve_seconds;
}

// `contact`: the case has bodies, which the prolonged start is lifted out of.
void print_level(std::size_t index, std::size_t count, const RefineLevelRun& run, bool contact) {
  std::string start, drape;
  if (index > 0 && contact)
    start = ", started " + format_number(run.deepest_start) + " m below the offset, lifted out";
  if (run.drape) {
    drape = ", drape coefficient " + format_number(run.drape->coefficient) + " (" +
            std::to_string(run.drape->nodes) + " nodes)";
  }
  SartorPetscCall(PetscPrintf(
      PETSC_COMM_WORLD,
      "sartor run: level %zu of %zu: %zu triangles (--mesh-refine %d), %s, %ld Newton "
      "iterations, residual %.3e N, certificate: %s%s, %.1f s (CPU %.1f s)%s\n",
      index + 1, count, run.triangles, run.refinements,
      run.converged ? "converged" : "NOT converged", run.newton_iterations, run.residual_force,
      run.certificate.empty() ? "not taken" : run.certificate.c_str(), drape.c_str(),
      run.solve_seconds, run.cpu_seconds, start.c_str()));
}

} // namespace

OptionSpec refine_levels_option() {
  return {"refine-levels", "N", "1",
          "static: solve on N meshes, coarse to fine: first with N-1 fewer --mesh-refine "
          "refinements, then each finer one from the solution before, its new vertices at the "
          "solved edges' midpoints (docs/drape.md#coarse-to-fine-statics-of-a-run-case)"};
}

void check_refine_levels(const ClothCase& cloth_case, int levels,
                         const CaseCheckpointing& checkpointing) {
  if (levels == 1) return;
  const std::string option = "option --refine-levels " + std::to_string(levels) + ": ";
  if (cloth_case.time.analysis != "static") {
    throw InputError(option + "solves statics level by level; --analysis " +
                     cloth_case.time.analysis + " runs on one mesh");
  }
  if (cloth_case.mesh.refine < levels - 1) {
    throw InputError(option + "the coarsest level has " + std::to_string(levels - 1) +
                     " fewer refinements than the case's mesh, which has --mesh-refine " +
                     std::to_string(cloth_case.mesh.refine) + "; give --mesh-refine " +
                     std::to_string(levels - 1) + " or more (with a coarser base mesh)");
  }
  if (cloth_case.seams.merge)
    throw InputError(option + "--seam-merge changes the mesh; it takes one level");
  if (!checkpointing.restart_file.empty() || checkpointing.interval > 0.0)
    throw InputError(option + "--restart and --checkpoint-interval take one level");
}

CaseResult solve_on_refine_levels(const ClothCase& cloth_case, int levels,
                                  const CaseStepObserver& observe,
                                  const CaseCheckpointing& checkpointing,
                                  std::vector<RefineLevelRun>* runs) {
  check_refine_levels(cloth_case, levels, checkpointing);
  if (levels == 1) return solve_case(cloth_case, 0, observe, checkpointing);
  CaseResult result;
  std::vector<Eigen::Vector3d> start;
  for (int l = 0; l < levels; ++l) {
    const int extra = l - (levels - 1);
    RefineLevelRun run;
    const double cpu_start = process_cpu_seconds();
    const LogStage stage("Refine level " + std::to_string(l));
    if (l > 0) start = prolonged_start(cloth_case, result, extra, &run.deepest_start);
    ClothCase level_case = l == 0 ? cloth_case : finer_level_case(cloth_case);
    level_case.statics.progress_prefix =
        "level " + std::to_string(l + 1) + " of " + std::to_string(levels) + ", ";
    result = solve_case(level_case, extra, l + 1 == levels ? observe : CaseStepObserver{},
                        checkpointing, nullptr, l > 0 ? &start : nullptr);
    record(result, cloth_case.certificate, &run);
    run.cpu_seconds = process_cpu_seconds() - cpu_start;
    print_level(std::size_t(l), std::size_t(levels), run, !cloth_case.contact.bodies.empty());
    runs->push_back(run);
    if (!result.converged) break; // ends here: the caller reports this level's result
  }
  result.solve_seconds = 0.0;
  for (const RefineLevelRun& run : *runs)
    result.solve_seconds += run.solve_seconds;
  return result;
}

ClothCase finer_level_case(ClothCase cloth_case) {
  cloth_case.statics.load_steps = 1;
  cloth_case.statics.sewing_stages = 1;
  cloth_case.statics.converge_stages = false;
  return cloth_case;
}

std::vector<Eigen::Vector3d> prolonged_start(const ClothCase& cloth_case, const CaseResult& coarse,
                                             int extra_refinements, double* deepest_start) {
  const TriangleMesh fine = level_mesh(cloth_case, extra_refinements);
  std::vector<Eigen::Vector3d> start =
      prolong(coarse.mesh, broadcast_positions(coarse.positions, coarse.mesh.vertex_count()), fine,
              cloth_case.mesh.kind);
  *deepest_start = lift_out_of_bodies(cloth_case.contact, fine, &start);
  return start;
}

nlohmann::json refine_levels_json(const std::vector<RefineLevelRun>& runs) {
  nlohmann::json levels = nlohmann::json::array();
  for (const RefineLevelRun& run : runs) {
    levels.push_back(
        {{"mesh_refine", run.refinements},
         {"vertices", run.vertices},
         {"triangles", run.triangles},
         {"longest_edge_m", run.longest_edge},
         {"converged", run.converged},
         {"newton_iterations", run.newton_iterations},
         {"residual_force_N", run.residual_force},
         {"certificate",
          run.certificate.empty() ? nlohmann::json(nullptr) : nlohmann::json(run.certificate)},
         {"start_depth_below_offset_m", run.deepest_start},
         {"drape_coefficient",
          run.drape ? nlohmann::json(run.drape->coefficient) : nlohmann::json(nullptr)},
         {"drape_nodes", run.drape ? nlohmann::json(run.drape->nodes) : nlohmann::json(nullptr)},
         {"solve_s", run.solve_seconds},
         {"cpu_s", run.cpu_seconds}});
  }
  return levels;
}

} // namespace sartor
