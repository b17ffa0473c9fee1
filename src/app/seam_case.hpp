#pragma once
// Seams in the case pipeline of `sartor run` (solve_case): the seams of the
// case's mesh (the tube_panels generator's, or a seam file's), their springs
// with the stiffness the options choose, the optional sew-then-merge stage,
// and the "seams" part of summary.json. docs/seams.md describes them.

#include "app/cli.hpp"
#include "app/mesh_case.hpp"
#include "app/time_case.hpp"
#include "fem/cloth_problem.hpp"
#include "mesh/panels.hpp"
#include "mesh/seams.hpp"
#include "solvers/statics.hpp"

#include <nlohmann/json_fwd.hpp>

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace sartor {

// The seams module's options: --seams-file, --seam-stiffness, --seam-penalty,
// --seam-merge, --seam-merge-gap, --sewing-tension, --sewing-time.
const std::vector<OptionSpec>& seam_option_specs();

// Those options, read once and checked for their own values.
struct SeamCase {
  std::string seams_file;               // --seams-file; empty: the mesh generator's, if any
  double penalty = 100.0;               // --seam-penalty
  std::optional<double> stiffness;      // --seam-stiffness, N/m^2; none: automatic
  bool merge = false;                   // --seam-merge
  double merge_gap = 1e-4;              // --seam-merge-gap, m
  std::optional<double> sewing_tension; // --sewing-tension, N/m
  std::optional<double> sewing_time;    // --sewing-time, s
};

// Throws InputError naming the option for a malformed value.
SeamCase read_seam_case(const Options& options);

struct SeamReport {
  std::size_t seams = 0;
  std::size_t springs = 0;
  std::size_t vertex_to_edge_springs = 0;
  PetscInt cross_rank_springs = 0; // springs whose vertices live on different ranks
  double gap = 0.0;                // largest seam gap at the solution, m (0 once merged)
  double sewing_tension = 0.0;     // --sewing-tension: the springs' pull limit, N/m (0: none)
  double sewing_end_time = 0.0;    // the end of the sewing stage, s
  // --seam-merge: the sewing solve, its gap, and the vertices before and after.
  bool merged = false;
  double gap_before_merge = 0.0; // m
  std::size_t vertices_before_merge = 0;
  std::size_t vertices_after_merge = 0;
  StaticReport sewing;
};

// The case's seams: --seams-file's, else the tube_panels generator's, else
// none. Throws InputError when seams meet uniform refinement (the seam lines
// would miss the new vertices).
std::vector<Seam> case_seams(const SeamCase& seam_case, const MeshCase& mesh_case,
                             const TriangleMesh& mesh, int refinements);

// The seams' stiffness settings: --seam-stiffness, or --seam-penalty with the
// material's largest initial modulus.
SeamStiffness case_seam_stiffness(const SeamCase& seam_case, const ClothMaterial& material);
// The springs of `seams` with those settings.
std::vector<SeamSpring> case_seam_springs(const SeamCase& seam_case, const TriangleMesh& mesh,
                                          const std::vector<Seam>& seams,
                                          const ClothMaterial& material);

// Adds the springs to `problem` (from the seam lines, so that they have a
// rest derivative) and records their counts in `report`.
// Throws InputError for a sewing stage outside time stepping or past its end.
void attach_seams(const SeamCase& seam_case, const TimeCase& time, const std::vector<Seam>& seams,
                  const ClothMaterial& material, ClothProblem& problem, SeamReport* report);

// --seam-merge: sews `mesh` with its seams under gravity alone (collective
// statics with continuation), checks that every seam closed to within
// --seam-merge-gap, and replaces `mesh` by the sewn mesh with each matched
// vertex pair merged and `pinned` by the merged pins. Throws InputError when
// the sewing fails, a seam stays open, or a seam is not matched vertex to
// vertex.
void sew_and_merge(const SeamCase& seam_case, const TimeCase& time, const ClothMaterial& material,
                   const Eigen::Vector3d& gravity, int load_steps, const std::vector<Seam>& seams,
                   TriangleMesh* mesh, std::vector<int>* pinned, SeamReport* report);

// summary["seams"].
void add_seam_summary(const SeamReport& report, nlohmann::json& summary);

} // namespace sartor
