#pragma once
// Coarse to fine statics of a `sartor run` case (--refine-levels N;
// docs/drape.md#coarse-to-fine-statics-of-a-run-case), Sensitive Couture
// §7.1's cascadic multigrid on uniform refinements: the case is solved first
// on its mesh with N-1 fewer --mesh-refine refinements; each solution is
// carried to the next finer mesh as that mesh's refinement of the solved
// one (every new vertex at the midpoint of its solved edge: the coarse
// solution interpolated exactly), lifted out of the bodies where a chord
// cut into them, and solved again from there. The last level is the case's
// own mesh. `sartor drape --levels` does the same on panel meshings.

#include "app/cloth_case.hpp"

#include <nlohmann/json_fwd.hpp>

#include <optional>

#include <string>
#include <vector>

namespace sartor {

// --refine-levels.
OptionSpec refine_levels_option();

// What each level did.
struct RefineLevelRun {
  int refinements = 0; // --mesh-refine of the level
  std::size_t vertices = 0, triangles = 0;
  double longest_edge = 0.0; // m, material
  bool converged = false;
  long newton_iterations = 0;
  double residual_force = 0.0;       // N
  std::string certificate;           // the verdict; "" when not certified
  double deepest_start = 0.0;        // m, the prolonged start's deepest vertex below the offset
  std::optional<DrapeMeasure> drape; // a Cusick case's coefficient and nodes on this level
  double solve_seconds = 0.0;        // wall clock of the level's solve
  double cpu_seconds = 0.0;          // this process's CPU time over the level
};

// Throws InputError where the case cannot be solved on `levels` levels:
// not statics, fewer --mesh-refine than levels - 1, merged seams (merging
// changes the mesh), a restart or checkpoints.
void check_refine_levels(const ClothCase& cloth_case, int levels,
                         const CaseCheckpointing& checkpointing);

// Collective. One level: solve_case. Several: as above, every level
// certified as solve_case certifies; returns the finest level's result with
// its solve_seconds summed over the levels, and `runs` gets one entry per
// level. Throws InputError when the case's mesh is not the refinement of
// its coarser one (a mesh its generator refines otherwise).
CaseResult solve_on_refine_levels(const ClothCase& cloth_case, int levels,
                                  const CaseStepObserver& observe,
                                  const CaseCheckpointing& checkpointing,
                                  std::vector<RefineLevelRun>* runs);

// The case as a finer level solves it: it starts loaded and sewn (the
// prolonged solution), so in one load step and without sewing stages.
ClothCase finer_level_case(ClothCase cloth_case);

// Collective. The start of the case's mesh with `extra_refinements` (its
// solve_case argument) from `coarse`, solved on the mesh with one
// refinement fewer: that mesh refined at its solved positions, lifted out
// of the bodies; `deepest_start` gets the deepest vertex's depth below the
// offset before lifting (m). Throws InputError when the finer mesh is not
// the coarse one refined.
std::vector<Eigen::Vector3d> prolonged_start(const ClothCase& cloth_case, const CaseResult& coarse,
                                             int extra_refinements, double* deepest_start);

// summary.json's "levels": one object per level.
nlohmann::json refine_levels_json(const std::vector<RefineLevelRun>& runs);

} // namespace sartor
