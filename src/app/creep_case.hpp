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

// The creep module's options, read once (creep analyses and wear; other
// analyses leave them unread).
struct CreepCase {
  CreepScheme scheme = CreepScheme::staggered; // --creep-scheme
  double min_step = 1e-6;                      // s, --min-time-step
  double max_step = 0.0;                       // s, --max-time-step (0: no limit)
  double tolerance = 1e-3;                     // --creep-tolerance
  LoadHistory load;                            // --load-history (no knots: 1 always)
  bool dynamic = false;                        // --creep-dynamics
  // --creep-parameters, for both directions of every fabric; none: the fabric's.
  std::optional<CreepMaterial> given;
};

// Throws InputError naming the option for a malformed value.
CreepCase read_creep_case(const Options& options);

// --creep-scheme's name of `scheme` (staggered, monolithic).
std::string creep_scheme_name(CreepScheme scheme);

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

// Collective. Runs the creep analysis `creep_case` of `problem` from x (its
// mesh's placement, or the restart's state) over `time`'s grid, its initial
// equilibrium in `load_steps`. `probe_vertex` (mesh numbering, or -1) adds
// its displacement to the history.
CreepRunResult run_creep_case(const CreepCase& creep_case, const TimeCase& time, int load_steps,
                              ClothProblem& problem, Vec x, const CaseCheckpointing& checkpointing,
                              long probe_vertex, CreepCoupling& creep,
                              const CreepStateObserver& observe);

// The creep material of the case: `creep`'s given parameters, or those of
// the fabric (a name or file, material/fabric.hpp) per direction.
CreepMaterial creep_material(const CreepCase& creep, const std::string& fabric);

} // namespace sartor
