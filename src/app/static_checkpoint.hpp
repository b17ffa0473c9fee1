#pragma once
// Checkpoints and restart of static solves (`sartor drape`'s minimiser): the
// state after every sewing stage and contact round (solvers/statics.hpp,
// StaticOptions::checkpoint): positions, the friction anchors, and in
// /state the report so far with the adaptive contact penalty
// (docs/reliability.md#checkpoints-and-restart).

#include "app/creep_case.hpp"
#include "fem/checkpoint.hpp"
#include "solvers/statics.hpp"

#include <functional>
#include <string>

namespace sartor {

struct StaticResume {
  RunCheckpoint checkpoint;
  StaticReport report;     // the stages and rounds done
  std::string drape_level; // the drape level's record (JSON text); "" if not a level's solve
  // Collective: x, the friction anchors and the contact stiffness scale.
  PetscErrorCode restore(ClothProblem& problem, Vec x) const;
};

// Reads and checks a static solve's checkpoint against the problem's mesh:
// the file's, or the /before of a later phase's (a wear's, which resumes
// after the drape). Throws InputError naming the file when it is not one of
// this case.
StaticResume read_static_checkpoint(const std::string& path, const ClothProblem& problem);

// Collective. The checkpoint writer for StaticOptions::checkpoint (rank 0
// writes `checkpointing.file` atomically and keeps it in *last); counts
// them in *written.
std::function<PetscErrorCode(Vec, const StaticReport&)>
static_checkpoint_writer(ClothProblem& problem, const CaseCheckpointing& checkpointing,
                         long* written, std::shared_ptr<const RunCheckpoint>* last);

// Collective. Writes the state x a static solve ended in, with its report,
// to checkpointing.final_state (a checkpoint a restart resumes from at the
// end of the solve).
PetscErrorCode write_final_static_state(ClothProblem& problem, Vec x,
                                        const CaseCheckpointing& checkpointing,
                                        const StaticReport& report);

} // namespace sartor
