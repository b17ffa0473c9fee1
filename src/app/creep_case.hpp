#pragma once
// `--analysis creep` of a cloth case (thesis §5.3, Algorithm 2): its options,
// the elements' creep materials, and the run with its history file
// (creep.csv) and checkpoints (fem/checkpoint.hpp). docs/creep-structure.md.

#include "app/cli.hpp"
#include "app/time_case.hpp"
#include "solvers/creep_analysis.hpp"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace sartor {

// --load-history, --creep-tolerance, --min-time-step, --max-time-step,
// --creep-parameters (the case options of creep runs).
const std::vector<OptionSpec>& creep_option_specs();

// Where a run writes checkpoints and what it resumes from (`sartor run`'s
// --checkpoint, --checkpoint-interval, --restart).
struct CaseCheckpointing {
  std::string file;         // written every `interval` s of simulated time
  double interval = 0.0;    // s; 0: no checkpoints
  std::string restart_file; // resume from this checkpoint; "" starts afresh
  // A static solve within a level of a drape on several levels: the level's
  // record (JSON text) its checkpoints carry in /state, with the mesh's start
  // (app/progressive_drape.cpp); "" for every other run.
  std::string drape_level;
  // Statics: the state the solve ended in (after the certificate's saddle
  // escapes), written here whatever the interval; "" writes none (`sartor
  // drape`'s drape_state.h5, which `sartor edit DRAPE_DIR` resumes from).
  std::string final_state;
};

struct CreepRunResult {
  CreepReport report;
  std::string scheme;      // --creep-scheme
  std::string history_csv; // creep.csv: one row per accepted state, from the run's start
  bool resumed = false;
  double resumed_time = 0.0; // s, when resumed
  long checkpoints_written = 0;
};

// Called collectively with each accepted state.
using CreepStateObserver = std::function<void(Vec x, const CreepStepReport& step)>;

// Collective. Runs the creep analysis of `problem` from x (its mesh's
// placement, or the restart's state) over `time`'s grid; the creep options
// (--creep-scheme, --creep-tolerance, step limits, --load-history) are read
// from `options`. `probe_vertex` (mesh numbering, or -1) adds its
// displacement to the history.
CreepRunResult run_creep_case(const Options& options, const TimeCase& time, ClothProblem& problem,
                              Vec x, const CaseCheckpointing& checkpointing, long probe_vertex,
                              CreepCoupling& creep, const CreepStateObserver& observe);

// The creep materials of the case: the fabric's creep parameters per
// direction, or --creep-parameters for both.
std::vector<CreepMaterial> creep_materials(const Options& options);

} // namespace sartor
