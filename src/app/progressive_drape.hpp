#pragma once
// Progressive refinement of a drape (Sensitive Couture §7.1, cascadic
// multigrid): the garment is draped on the coarsest meshing of its panels
// as `sartor drape` drapes (sewing, dynamics with kinetic damping, settle),
// the drape is carried to the next finer meshing by barycentric
// interpolation in each panel (src/garment/mesh_levels.hpp), its seams
// closed, the vertices a coarse triangle's chord took into the body lifted
// out, and relaxed there from that start (a short damped dynamics with
// friction, no sewing stage, then the settle); and so on to the
// target edge length. The levels share the construction (TAGCON's
// placement and seam pairing), the panels kept and the fabrics.

#include "app/cli.hpp"
#include "app/cloth_case.hpp"
#include "garment/mesh_levels.hpp"
#include "garment/tagcon.hpp"

#include <nlohmann/json_fwd.hpp>

#include <string>
#include <vector>

namespace sartor {

// --levels and --coarsest-edge.
const std::vector<OptionSpec>& level_option_specs();

// What the levels after the coarsest do differently.
struct FinerLevels {
  double refine_time = 0.0; // s of damped relaxation (dynamic drapes)
  bool sew_last_two = true; // static: only the last two sewing stages
};

// --refine-time (dynamic drapes only) and --level-sewing; InputError names
// the option for a bad value.
FinerLevels read_finer_levels(const Options& options, const ClothCase& cloth_case);
// The levels' edge lengths, coarse to fine, the last --edge-length (one
// entry: a single level). Throws InputError for bad --levels/--coarsest-edge.
std::vector<double> drape_level_edge_lengths(const Options& options,
                                             const garment::Construction& construction,
                                             const PanelMeshOptions& mesh_options);

// The finest level as drape built it: its cloth (mesh, fabrics), each
// triangle's pattern panel, its seams and the seams file solve_case reads
// for it (--seams-file).
struct DrapeLevel {
  double edge_length = 0.0; // m
  CaseCloth cloth;
  std::vector<int> panel_of_triangle;
  std::vector<Seam> seams;
  std::string seams_file;
};

// What each level did.
struct LevelRun {
  double edge_length = 0.0; // m
  std::size_t vertices = 0, triangles = 0;
  std::string analysis; // as solved: dynamic (drape's default) or static
  bool converged = false;
  long newton_iterations = 0;    // all of the level's, dynamics and settle included
  double residual_force = -1.0;  // N, after the level's final static solve
  double seam_gap_prolonged = 0; // m, the start's largest seam gap before closing
  double seam_gap_start = 0;     // m, after closing: the level's start
  double outside_distance = 0;   // m, farthest fine vertex outside its coarse panel
  double deepest_start = 0;      // m, the prolonged start's deepest vertex below the offset
  double solve_seconds = 0.0;    // wall clock of the level's solve
  double cpu_seconds = 0.0;      // this process's CPU time over the level
};

// Collective. Drapes `finest` through `edge_lengths` (coarse to fine, the
// last finest.edge_length): the coarser levels mesh `construction` at their
// edge lengths, keep finest's panels and fabrics, and write their seams
// files beside finest.seams_file. The coarsest level solves `cloth_case`
// (drape's dynamics with its sewing stage); every finer one relaxes for
// `finer.refine_time` s (--refine-time; no sewing stage) and settles, from
// the prolonged drape; in statics it is sewn in stages again, all of them or
// the last two (finer.sew_last_two). The coarsest level's time steps go to
// DIRECTORY/series.h5 (with `labels` for its panels). Returns the finest
// level's result, its solve_seconds summed over the levels; `runs` gets one
// entry per level. A single
// level is solve_case on `finest`, as before, with `checkpointing`. Several
// levels with checkpoints: one at the end of every level before the last
// (its positions and the LevelRuns so far), and in a static drape the level
// solve's own within each level (with the level's record and start); a
// restart goes on with the level after the checkpoint's, or within its level.
CaseResult drape_progressively(const ClothCase& cloth_case, const FinerLevels& finer,
                               const garment::Construction& construction,
                               const PanelMeshOptions& mesh_options, const DrapeLevel& finest,
                               const std::vector<double>& edge_lengths,
                               const std::string& directory, const ClothOutputLabels& labels,
                               std::vector<LevelRun>* runs,
                               const CaseCheckpointing& checkpointing = {});

// Moves the vertices of a prolonged state that lie deeper than half the
// contact offset in one of contact's bodies out to that depth, then the
// points its edge samples query (the coarse chords cut into curved bodies
// between their vertices). Returns the deepest vertex's start, m below the
// offset surface.
double lift_out_of_bodies(const ContactCase& contact, const TriangleMesh& mesh,
                          std::vector<Eigen::Vector3d>* positions);

// summary.json's drape.levels: one object per level.
nlohmann::json levels_json(const std::vector<LevelRun>& runs);

} // namespace sartor
