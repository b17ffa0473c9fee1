#pragma once
// Checkpoints and restart of `--analysis dynamic` (sartor run, drape): what
// the next step depends on is written at step boundaries (fem/checkpoint.hpp:
// positions, velocities, the friction anchors, and in /state the step
// controller, the step reports and the probe's history so far), and a run
// resumed from one continues as the uninterrupted run would
// (docs/reliability.md#checkpoints-and-restart).

#include "app/creep_case.hpp"
#include "fem/checkpoint.hpp"
#include "solvers/dynamics.hpp"

#include <Eigen/Core>

#include <functional>
#include <string>
#include <vector>

namespace sartor {

// What a dynamic run resumes from: the checkpoint's controller, report and
// probe history, and the state restore() puts into a problem.
struct DynamicResume {
  RunCheckpoint checkpoint;
  DynamicControl control;
  DynamicReport report;
  std::vector<Eigen::Vector3d> probe_history;
  std::string drape_level; // the drape level's record (JSON text); "" if not a level's run
  // The states written to series.h5 before the checkpoint (output steps).
  std::size_t series_states() const;
  // Collective: x, v, problem.time, load factor and friction anchors.
  PetscErrorCode restore(ClothProblem& problem, Vec x, Vec v) const;
};

// Reads and checks a dynamic run's checkpoint against the problem's mesh.
// Throws InputError naming the file when it is not one of this case.
DynamicResume read_dynamic_checkpoint(const std::string& path, const ClothProblem& problem);

// The time of the checkpoint at `path` (any kind), for a resumed series.
double checkpoint_time(const std::string& path);

// Collective. The checkpoint writer for solve_dynamic: the state, the
// report and the probe's history so far (rank 0 writes `checkpointing.file`
// atomically); counts them in *written.
std::function<PetscErrorCode(const DynamicControl&, Vec, Vec)>
dynamic_checkpoint_writer(ClothProblem& problem, const CaseCheckpointing& checkpointing,
                          const DynamicReport& report,
                          const std::vector<Eigen::Vector3d>& probe_history, long* written);

} // namespace sartor
