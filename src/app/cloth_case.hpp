#pragma once
// The pipeline of a cloth case, shared by `sartor run` (one solve) and
// `sartor converge` (the same case on a sequence of refined meshes): build the
// mesh, material, pins and loads that the options describe, solve static
// equilibrium (or, with --analysis dynamic, step through time), and collect
// what the outputs report.

#include "app/certificate_case.hpp"
#include "app/cli.hpp"
#include "app/contact_case.hpp"
#include "app/creep_case.hpp"
#include "app/load_case.hpp"
#include "app/material_case.hpp"
#include "app/mesh_case.hpp"
#include "app/seam_case.hpp"
#include "app/static_case.hpp"
#include "app/time_case.hpp"
#include "element/membrane.hpp"
#include "fem/checkpoint.hpp"
#include "fem/cloth_output.hpp"
#include "fem/cloth_problem.hpp"
#include "garment/pattern.hpp"
#include "mesh/triangle_mesh.hpp"
#include "solvers/dynamics.hpp"
#include "solvers/statics.hpp"

#include <nlohmann/json_fwd.hpp>

#include <Eigen/Core>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace sartor {

// The options of a case (mesh, material, loads, pins, probe, load steps),
// without --output: every command that solves a case declares these.
const std::vector<OptionSpec>& case_option_specs();

// A cloth case as its modules read it from the options, once: what a solve
// takes. A drape copies it per level and changes the copy (its seams, its
// edge samples, a finer level's relaxation), never the options.
struct ClothCase {
  MeshCase mesh;
  TimeCase time;
  MaterialCase material;
  LoadCase loads;
  StaticCase statics;
  SeamCase seams;
  ContactCase contact;
  CertificateCase certificate;
  std::optional<CreepCase> creep; // --analysis creep only
  // An option given that the analysis does not take, as the error to report
  // (empty: none). It is reported after the checks against the mesh (a seam
  // option without seams says that first).
  std::string inapplicable_option;
};

// Reads every module's options (`generated`: the mesh comes from --mesh, not
// in memory) and finds any option the analysis does not take. Throws
// InputError naming the option for a malformed value.
ClothCase read_cloth_case(const Options& options, bool generated = true);

struct CaseProbe {
  std::size_t vertex = 0;           // nearest mesh vertex to the --probe point
  Eigen::Vector3d point;            // the --probe point, m
  Eigen::Vector3d initial_position; // of the vertex, m
  Eigen::Vector3d displacement;     // of the vertex, m
};

struct CaseResult {
  int mesh_refine = 0; // uniform refinements applied (the option's plus the extra ones)
  TriangleMesh mesh;   // as solved: refined and placed
  std::size_t pinned_vertices = 0;
  PetscInt dofs = 0;
  // Characteristic mesh size: the longest triangle edge in material (u, v)
  // coordinates, m.
  double h = 0.0;

  bool converged = false;
  double load_factor = 0.0;              // reached (1 when converged)
  StaticReport report;                   // --analysis static
  std::optional<DynamicReport> dynamics; // --analysis dynamic
  std::optional<CreepRunResult> creep;   // --analysis creep
  ClothEnergy energy;
  Eigen::Vector3d pin_reaction = Eigen::Vector3d::Zero();
  double max_displacement = 0.0;   // m
  std::optional<CaseProbe> probe;  // when --probe is given
  CaseContact contact;             // bodies, reactions, drape (app/contact_case.hpp)
  std::optional<SeamReport> seams; // when the case has seams
  // Contact pressure, friction and seam forces per vertex (rank 0; result.h5).
  std::vector<ClothNodeField> vertex_loads;
  // The final state's certificate (statics, or a settle; not with
  // --no-certificate) and the saddle escapes taken.
  std::optional<CertifiedState> certified;
  // Dynamic runs with --probe: its displacement at every state of
  // dynamics->steps, m.
  std::vector<Eigen::Vector3d> probe_history;
  // Dynamic runs: checkpoints written, and the time resumed from (--restart; -1: none), s.
  long checkpoints_written = 0;
  double resumed_time = -1.0;
  // Statics: the last checkpoint written or resumed from (rank 0; null
  // without checkpoints), which a wear's checkpoints carry as /before.
  std::shared_ptr<const RunCheckpoint> last_checkpoint;

  // Rank 0 only (empty elsewhere): final positions and per-triangle strains.
  std::vector<Eigen::Vector3d> positions;
  std::vector<element::MembraneStrain> strains;

  double setup_seconds = 0.0; // mesh, material, problem
  double solve_seconds = 0.0; // solve_static or solve_dynamic
  double total_seconds = 0.0; // everything up to the gathered results
  // The process's CPU time (s) when the solve and its certificate ended,
  // before any after_statics (an edit's, a wear's).
  double cpu_at_end = 0.0;
};

// Collective. Solves the case, with `extra_refinements` uniform refinements
// on top of --mesh-refine. Throws InputError for a bad input (a fabric, a
// mesh, a setup the analysis cannot solve); a solve that does not converge is reported in the
// result, not thrown. Every field but positions and strains is the same on every rank. With
// --analysis dynamic or creep, `observe` (when given) is called collectively with the initial state
// and after every accepted time step; `checkpointing` says where dynamic and creep runs write
// checkpoints and resume from.
struct CaseState {
  double time = 0.0;                    // s
  bool output = false;                  // an output time
  const CreepCoupling* creep = nullptr; // creep runs: the elements' creep state
};
using CaseStepObserver = std::function<void(ClothProblem& problem, Vec x, const CaseState& state)>;
// A cloth handed to solve_case in memory instead of by --mesh (`sartor
// drape`: the constructed garment). Its mesh's material_ids number `fabrics`
// (each a preset or FILE.yaml), which replace --fabric; the other material
// options (--density, --bending-stiffness, ...) apply to every fabric.
// Several fabrics rule out --seam-merge and --analysis creep (one material).
struct CaseCloth {
  TriangleMesh mesh;
  std::vector<std::string> fabrics;
  // When set, called collectively after a converged static solve, once the
  // results are gathered (drape's wear, app/wear_case.hpp), with the
  // problem, its materials (per mesh material id), its seam springs and the
  // solved positions x, which it may advance.
  // The last argument: CaseResult::last_checkpoint.
  std::function<void(ClothProblem&, const std::vector<ClothMaterial>&,
                     const std::vector<SeamSpring>&, Vec,
                     const std::shared_ptr<const RunCheckpoint>&)>
      after_statics;
};
// The panels' fabrics as the case's materials: cloth->fabrics lists each
// fabric once, in the order the panels first name it, and the mesh's
// material ids (panel indices on entry) become indices into that list.
void assign_panel_fabrics(const std::vector<garment::Panel>& panels, CaseCloth* cloth);

// A cloth of one fabric names it as --fabric, for what reads that option
// (the creep parameters of a wear).
void name_single_fabric(const CaseCloth& cloth, Options* options);

// `start`: the positions the solve starts from (the mesh's placement when
// null; pinned vertices stay at their own).
CaseResult solve_case(const ClothCase& cloth_case, int extra_refinements = 0,
                      const CaseStepObserver& observe = {},
                      const CaseCheckpointing& checkpointing = {}, const CaseCloth* cloth = nullptr,
                      const std::vector<Eigen::Vector3d>* start = nullptr);

// The parts of `sartor run`'s summary.json that describe the solve: "mesh",
// "converged", "solver", "load_steps" (statics) or "dynamics" (time stepping),
// "energy_J", "pin_reaction_N", "max_displacement_m", "probe" (when given),
// "certificate" (when certified: docs/certificate.md) and "timing_s".
void add_case_summary(const CaseResult& result, nlohmann::json& summary);

// Rank 0: result.h5, result.xmf, final.obj and summary.json in `directory`;
// `labels` name the fabric and panel ids there (fem/cloth_output.hpp).
void write_case_results(const std::string& directory, const CaseResult& result,
                        const nlohmann::json& summary, const ClothOutputLabels& labels = {});

// An observer for solve_case that writes the output states of dynamic and
// creep runs (positions, strains; creep strains) to DIRECTORY/series.h5 +
// series.xmf, as `sartor run` does; `labels` as for write_case_results.
// `resumed_from` (a checkpoint file; "": a new run): a resumed run's writer,
// which keeps the states series.h5 has up to the checkpoint's time and
// appends after them.
CaseStepObserver series_writer(const std::string& directory, const ClothOutputLabels& labels = {},
                               const std::string& resumed_from = "");

// --checkpoint, --checkpoint-interval and --restart (the checkpoint file
// defaults to DIRECTORY/checkpoint.h5; DIRECTORY is made when needed).
CaseCheckpointing case_checkpointing(const Options& options, const std::string& directory);

// Collective: every option in effect, to DIRECTORY/petsc_options.txt: the
// options database and the defaults the command gave `options`.
void write_petsc_options(const std::string& directory, const Options& options);

// Collective: rank 0's `positions` (gathered, `count` of them) on every rank.
std::vector<Eigen::Vector3d> broadcast_positions(std::vector<Eigen::Vector3d> positions,
                                                 std::size_t count);

} // namespace sartor
