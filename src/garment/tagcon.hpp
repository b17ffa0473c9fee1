#pragma once
// TAGCON (thesis ch. 3): automatic garment construction from a tagged and
// packed pattern. Two stages, both deterministic:
//  1. cylindrical positioning (§3.1): cylinders fitted to the body's skeleton
//     (torso, arms, legs, neck, head); each pack's bounding box is wrapped
//     onto its half cylinder, centred on it, at the cylinder's vertical
//     offset, layers (lambda) further out;
//  2. seam creation (§3.2-3.3.4): inter-layer seams (T and Y), intra-pack
//     seams (closest line in the field of view), classification of the rest
//     into inter-cylinder and inter-half-cylinder lines, ring matching with
//     clicks, greedy sorted matching, and deletion of seams whose sweep
//     penetrates the body. Every seam carries its certainty M(i, j).
// Serial, no PETSc. docs/tagcon.md describes the algorithms and choices.

#include "garment/pattern.hpp"

#include <Eigen/Core>

#include <array>
#include <functional>
#include <string>
#include <vector>

namespace sartor {
struct Mannequin;
}

namespace sartor::garment {

struct TagconOptions {
  double clearance = 0.025;       // m between the body section and its cylinder
  double layer_gap = 0.012;       // m further out per layer (lambda)
  double lid_depth = 0.06;        // m of a shoulder-anchored torso pack folded onto the lid
  double max_widening = 1.5;      // a pack may widen its cylinder to this times the fitted radius
  double fov_half_angle_deg = 60; // intra-pack field of view around a line's normal
  double intra_distance = 0.02;   // m: farther intra-pack lines are not matched
  double d_max = 0.6;             // eq. 3.2, m
  double length_diff = 0.3;       // eq. 3.4, m
  double curvature_diff = 25;     // eq. 3.5, 1/m
  double min_match = 0.02;        // M(i, j) below this is no match
  int clicks = 3;                 // ring match: rotations tried each way
  int sweep_pairs = 9;            // point pairs per seam tested against the body
  double penetration = 0.005;     // m: a sweep deeper inside the body than this is deleted
};

// A cylinder of the abstraction, fitted to the body. Points on it:
// top + a up + r (cos t side + sin t (up x side)), side = front or -front,
// t = arc / r; a <= 0 down the body from the top anchor.
struct FittedCylinder {
  Cylinder cylinder = Cylinder::torso;
  Eigen::Vector3d top = Eigen::Vector3d::Zero();     // axis point at the packs' top, m
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();     // unit, distal to proximal
  Eigen::Vector3d front = -Eigen::Vector3d::UnitY(); // unit, normal to up
  double length = 0;                                 // m of axis the packs cover below top
  double body_radius = 0; // largest distance of the covered body section from the axis, m
  double radius = 0;      // body_radius + clearance, widened to hold the widest pack, m
  bool lid = false;       // torso from the shoulders: the top is closed by a lid
  std::string anchor;     // e.g. "shoulder", "waist", "shoulder joint"
  std::vector<std::string> bones;
};

// Where a panel point goes: pack placement, then the wrap.
struct PackPlacement {
  int pack = 0;
  PanelTag tag;
  Eigen::Vector2d box_min = Eigen::Vector2d::Zero(); // pack bounding box, pack coordinates
  Eigen::Vector2d box_max = Eigen::Vector2d::Zero();
  // Unrolled half cylinder coordinates (arc from the half's centre line,
  // axial from the top anchor; > 0 is on the lid) = pack point + offset.
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();
  int cylinder = 0;  // index into Construction::cylinders
  double radius = 0; // the cylinder's radius plus the layers
};

// dart: a dart's legs, sewn before any other seam; user: from a seams file
// (garment/seam_overrides.hpp).
enum class SeamKind { intra_pack, inter_cylinder, inter_half_cylinder, t_seam, y_seam, dart, user };
const char* name_of(SeamKind kind);

// A line as seam creation sees it, in 3D.
struct LineGeometry {
  int panel = 0;
  int index = 0; // in the panel's outline, or its interior list
  bool interior = false;
  std::string id;
  std::vector<Eigen::Vector3d> samples; // equal arc length, start to end
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX(); // planar (in-surface) outward normal
  std::vector<Eigen::Vector2d> samples_2d;           // pack coordinates
  Eigen::Vector2d centre_2d = Eigen::Vector2d::Zero();
  Eigen::Vector2d normal_2d = Eigen::Vector2d::UnitX();
  double length = 0;    // m of fabric
  double curvature = 0; // mean |curvature|: total turning / length, 1/m
};

// The five factors of eq. 3.1 and their product.
struct MatchScore {
  double distance = 0, orientation = 0, length = 0, curvature = 0, seamable = 0;
  double value() const { return distance * orientation * length * curvature * seamable; }
};

struct FoundSeam {
  SeamKind kind = SeamKind::intra_pack;
  int line_a = 0; // indices into Construction::lines
  int line_b = 0;
  bool reverse = false;
  double certainty = 1; // in (0, 1]
  MatchScore score;     // the factors (intra-pack: distance is the FOV proximity)
};

struct UnseamedLine {
  int line = 0;
  std::string reason;
};

// The body as TAGCON queries it: the signed distance at a point (> 0
// outside, m) and, when `gradient` is not null, its gradient (the outward
// normal) there.
using BodyDistance = std::function<double(const Eigen::Vector3d&, Eigen::Vector3d* gradient)>;

struct Construction {
  std::vector<FittedCylinder> cylinders; // those the pattern uses
  std::vector<PackPlacement> packs;      // per pattern pack
  std::vector<LineGeometry> lines;       // outline lines, then interior lines, panel by panel
  std::vector<FoundSeam> seams;
  std::vector<FoundSeam> deleted; // sweep penetrated the body
  std::vector<UnseamedLine> unseamed;
  double placement_seconds = 0;
  double seam_seconds = 0;
  // The 3D position of a point of panel `panel` given in panel coordinates:
  // wrapped onto its half cylinder, then pushed out along the body's normal
  // where the cylinder passes closer than `clearance / 2` to the body (the
  // upper arm's cylinder meets the chest at the armpit).
  Eigen::Vector3d place(int panel, const Eigen::Vector2d& point) const;
  // The same from a point in its pack's coordinates.
  Eigen::Vector3d place_in_pack(int pack, const Eigen::Vector2d& point) const;
  // The unit tangents of the wrap at a pack point: images of the pack's x and y.
  std::array<Eigen::Vector3d, 2> wrap_tangents(int pack, const Eigen::Vector2d& point) const;
  const Pattern* pattern = nullptr;
  TagconOptions options;
  BodyDistance body;
  int line_index(const std::string& id) const; // -1 when absent
};

// Cylinders of the body for this pattern: axes from the skeleton, radii that
// enclose the body section the packs cover (vertices nearest to the
// cylinder's bones), widened for the widest pack. Throws InputError when a
// pack does not fit its half cylinder (thesis Fig. 3.9), naming the lines
// that reach beyond it, or the body lacks a bone a used cylinder needs.
std::vector<FittedCylinder> fit_cylinders(const Pattern& pattern, const Mannequin& body,
                                          const TagconOptions& options);

// The whole construction. Throws InputError for a pattern TAGCON cannot
// construct (see fit_cylinders), or a pack none of whose lines is seamed
// (when the pattern has more than one pack).
Construction construct(const Pattern& pattern, const Mannequin& body,
                       const BodyDistance& body_distance, const TagconOptions& options = {});

// --- building blocks, exposed for tests ---

// Eq. 3.1-3.6 for lines i and j; seamable is M_sa (0 or 1).
MatchScore match_score(const LineGeometry& i, const LineGeometry& j, bool seamable,
                       const TagconOptions& options);
// The orientation of a seam of lines a and b (true: a's start meets b's
// end) whose springs, point to point at equal arc length along the placed
// lines, start with the smaller sum of squared lengths.
bool should_reverse(const LineGeometry& a, const LineGeometry& b);
// M_sa's inherent part: whether two cylinders are ever sewn together.
bool cylinders_adjacent(Cylinder a, Cylinder b);

// Intra-pack matching (§3.3.1) among lines in one plane: for each line, the
// closest line whose nearest point lies within the FOV (or touches the
// line's centre), within max_distance; pairs that choose each other.
// `group[k]` says which lines may pair (same group, other panel): -1 = none.
std::vector<std::array<int, 2>> closest_line_pairs(const std::vector<LineGeometry>& lines,
                                                   const std::vector<int>& group,
                                                   const std::vector<int>& panel,
                                                   double fov_half_angle_deg, double max_distance);

// Ring matching (§3.3.2): rings a and b ordered by angle; pairs a[i] with
// b[(i + k) mod |b|], k within `clicks` of the shift the best individual
// match of a[0] suggests, the k with the largest sum of score(a, b).
// Returns the shift chosen.
int best_ring_shift(int size_a, int size_b, const std::function<double(int, int)>& score,
                    int clicks);

} // namespace sartor::garment
