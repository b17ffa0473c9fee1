#pragma once
// Checkpoints of a time-stepping run, to resume it after a crash or a kill
// exactly where it stood (HDF5, one file, rank 0 writes, every rank reads).
//
// A checkpoint holds what the next step depends on: time, the next step size,
// the step count, the load factor, positions and (for dynamics) velocities of
// every vertex, the creep state of every element, the friction anchors, and
// the rows the run's history file had so far. It is written to FILE.tmp and
// renamed over FILE, so a run killed while writing leaves the previous
// checkpoint intact.
//
// Layout (all in SI units): /time, /next_step, /load_factor (scalars),
// /step (int64), /positions (n x 3), /velocities (n x 3, optional),
// /start_positions (n x 3, optional: the mesh's start where the run did not
// start from its case's placement, a finer drape level's prolonged start),
// /creep (t x 6: eps_v warp, eps_p warp, eps_v weft, eps_p weft, tension
// warp, tension weft), /anchors (k x 10: body, vertex, point, normal, the lagged normal force
// (N; inf where not known) and whether the anchor slid at its last update),
// /history (the history CSV text), /state (optional: JSON text of the
// controller of a dynamic run or a static drape, fem/run_state.hpp),
// /before (optional: a group holding, in this same layout, the checkpoint of
// the phase this run followed: a drape's last, under its wear's checkpoints),
// /checksum (uint64: FNV-1a over all of the above, /before's own checksum
// standing for /before, verified on reading: a corrupted file is refused),
// and the attribute /format = "sartor-checkpoint 3". A file without /state
// sums as one with an empty /state, so checkpoints written before /state
// existed still resume.

#include "fem/cloth_problem.hpp"
#include "fem/creep_coupling.hpp"

#include <Eigen/Core>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace sartor {

struct RunCheckpoint {
  double time = 0.0;      // s
  double next_step = 0.0; // s
  long step = 0;
  double load_factor = 0.0;
  std::vector<Eigen::Vector3d> positions;  // m, mesh numbering
  std::vector<Eigen::Vector3d> velocities; // m/s; empty for quasi-static runs
  // m; the mesh's start when it is not the case's own placement (a finer
  // level of a drape starts from the level before's drape); usually empty
  std::vector<Eigen::Vector3d> start_positions;
  std::vector<ElementCreep> creep; // per mesh triangle
  std::vector<AnchorRow> anchors;
  std::string history; // the run's history file (CSV) up to this state
  std::string state;   // JSON: the step controller and reports so far; "" for creep runs
  // The last checkpoint of the phase this run followed (the drape a wear
  // starts from), which a restart resumes first; null for a run of one phase
  std::shared_ptr<const RunCheckpoint> before;
};

// The checkpoint itself, or the phase it carries in /before: the run it
// resumes first (a wear's checkpoint resumes its drape from /before).
const RunCheckpoint& first_phase(const RunCheckpoint& checkpoint);

// Positions and creep states as a checkpoint's rows, flattened (3 values a
// position; 6 a creep state, in /creep's column order), and back. The way
// back throws std::invalid_argument on a partial row.
std::vector<double> position_rows(const std::vector<Eigen::Vector3d>& positions);
std::vector<Eigen::Vector3d> positions_from_rows(const std::vector<double>& values);
std::vector<double> creep_rows(const std::vector<ElementCreep>& states);
std::vector<ElementCreep> creep_from_rows(const std::vector<double>& values);

// Atomic (temporary file and rename). Throws InputError when it cannot write.
void write_checkpoint(const std::string& path, const RunCheckpoint& checkpoint);
// Throws InputError naming the file and what is missing or malformed.
RunCheckpoint read_checkpoint(const std::string& path);

} // namespace sartor
