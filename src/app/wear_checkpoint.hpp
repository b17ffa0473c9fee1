#pragma once
// Checkpoints of a drape's wear (`sartor drape --wear-time S` with
// --checkpoint-interval): after every accepted wear step, the worn state
// (positions, creep state, friction anchors, time and next step) with, in
// /state, the wear's report so far (its steps, and its take-offs with the
// recovered garments' positions and creep states) and, in /before, the
// drape's last checkpoint. A restart resumes the drape from /before (it ends
// at once where the drape had ended) and then the wear from the worn state
// (docs/reliability.md#checkpoints-and-restart).

#include "fem/checkpoint.hpp"
#include "solvers/wear.hpp"

#include <memory>
#include <optional>
#include <string>

namespace sartor {

struct WearResume {
  RunCheckpoint checkpoint; // the worn state
  WearReport report;        // the steps and take-offs up to it
  double contact_stiffness_scale = 1.0;
};

// The wear state of the checkpoint at `path`; nullopt when it is a drape's
// own checkpoint (the wear then starts afresh). Read before the drape runs:
// a resumed drape may write its own checkpoints over the file. Throws
// InputError naming the file when it is malformed.
std::optional<WearResume> read_wear_checkpoint(const std::string& path);

// Throws InputError naming `path` when the resumed states are not of `mesh`.
void check_wear_mesh(const WearResume& resume, const std::string& path, const TriangleMesh& mesh);

// Whether the checkpoint at `path` was taken within a wear.
bool within_wear(const std::string& path);

// The writer of WearRestart::write: rank 0 writes `file` atomically with
// `drape` (rank 0's; null elsewhere) as /before; counts them in *written.
// Throws InputError on rank 0 when there is no drape checkpoint to carry.
std::function<PetscErrorCode(ClothProblem&, Vec, const CreepCoupling&, const CreepStepReport&,
                             double, const WearReport&)>
wear_checkpoint_writer(const std::string& file, std::shared_ptr<const RunCheckpoint> drape,
                       long* written);

} // namespace sartor
