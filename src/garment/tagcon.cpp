#include "garment/tagcon.hpp"

#include "common/error.hpp"
#include "contact/mannequin.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

namespace sartor::garment {

namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

constexpr double pi = 3.14159265358979323846;
constexpr int samples_per_line = 16; // pieces of equal arc length per line

std::string format(double value, int digits = 3) {
  std::ostringstream out;
  out.precision(digits);
  out << value;
  return out.str();
}

bool is_limb(Cylinder c) {
  return c == Cylinder::arm_l || c == Cylinder::arm_r || c == Cylinder::leg_l ||
         c == Cylinder::leg_r;
}

// +1 for the wearer's left (+x), -1 for the right.
double limb_sign(Cylinder c) {
  return (c == Cylinder::arm_l || c == Cylinder::leg_l) ? 1.0 : -1.0;
}

// Bones whose flesh a cylinder encloses (for the radius), beyond the
// side-filtered trunk for the legs.
std::vector<std::string> bones_of(Cylinder c) {
  switch (c) {
  case Cylinder::torso:
    return {"pelvis",  "torso",   "clavicle_l", "clavicle_r", "hip_l", "hip_r",
            "thigh_l", "thigh_r", "shin_l",     "shin_r",     "neck"};
  case Cylinder::arm_l:
    return {"upper_arm_l", "forearm_l", "hand_l"};
  case Cylinder::arm_r:
    return {"upper_arm_r", "forearm_r", "hand_r"};
  case Cylinder::leg_l:
    return {"thigh_l", "shin_l", "foot_l"};
  case Cylinder::leg_r:
    return {"thigh_r", "shin_r", "foot_r"};
  case Cylinder::neck:
    return {"neck"};
  case Cylinder::head:
    return {"head", "neck"};
  }
  return {};
}

double distance_to_segment(const Vector3d& p, const Vector3d& a, const Vector3d& b, double* t) {
  const Vector3d ab = b - a;
  const double s = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  *t = s;
  return (p - (a + s * ab)).norm();
}

// The bone whose flesh a point belongs to: the nearest cone surface.
int nearest_bone(const Mannequin& body, const Vector3d& p) {
  double best = 1e300;
  int owner = 0;
  for (std::size_t b = 0; b < body.skeleton.size(); ++b) {
    const Bone& bone = body.skeleton[b];
    double t = 0;
    const double d = distance_to_segment(p, bone.start, bone.end, &t) -
                     ((1 - t) * bone.start_radius + t * bone.end_radius);
    if (d < best) {
      best = d;
      owner = int(b);
    }
  }
  return owner;
}

std::vector<int> nearest_bones(const Mannequin& body) {
  std::vector<int> owner(body.mesh.vertices.size(), 0);
  for (std::size_t v = 0; v < body.mesh.vertices.size(); ++v)
    owner[v] = nearest_bone(body, body.mesh.vertices[v]);
  return owner;
}

Vector3d normal_part(const Vector3d& v, const Vector3d& axis) {
  return v - v.dot(axis) * axis;
}

// The pack's bounding box (its members as placed, outlines flattened).
void pack_box(const Pattern& pattern, const Pack& pack, Vector2d* low, Vector2d* high) {
  Eigen::AlignedBox2d box;
  const double tolerance = pattern.flattening_tolerance();
  for (const auto& member : pack.members)
    for (const auto& p : pattern.panels[member.panel].outline_polygon(tolerance))
      box.extend(member.placement.apply(p));
  *low = box.min();
  *high = box.max();
}

bool upper_body_garment(const Pattern& pattern) {
  if (pattern.hangs_from_shoulders) return *pattern.hangs_from_shoulders;
  for (std::size_t k = 0; k < pattern.packs.size(); ++k) {
    const Cylinder c = pattern.pack_tag(int(k)).cylinder;
    if (c == Cylinder::arm_l || c == Cylinder::arm_r || c == Cylinder::neck || c == Cylinder::head)
      return true;
  }
  // A torso pack too long to hang from the waist is a dress: it hangs from
  // the shoulders.
  constexpr double longest_waist_garment = 0.8; // m
  for (const auto& pack : pattern.packs) {
    if (pattern.panels[pack.members.front().panel].tag.cylinder != Cylinder::torso) continue;
    Vector2d low, high;
    pack_box(pattern, pack, &low, &high);
    if (high.y() - low.y() > longest_waist_garment) return true;
  }
  return false;
}

// The cylinder's axis, anchor and bones from the skeleton.
FittedCylinder cylinder_axis(Cylinder c, const Mannequin& body, bool upper_body, double clearance,
                             const std::vector<int>& owner) {
  FittedCylinder fitted;
  fitted.cylinder = c;
  fitted.bones = bones_of(c);
  const auto front_normal_to = [](const Vector3d& up) {
    return Vector3d(normal_part(-Vector3d::UnitY(), up).normalized());
  };
  switch (c) {
  case Cylinder::torso: {
    const Bone& trunk = body.bone("torso");
    fitted.up = Vector3d::UnitZ();
    if (upper_body) {
      double shoulder_top = trunk.end.z();
      for (std::size_t v = 0; v < owner.size(); ++v) {
        const std::string& name = body.skeleton[std::size_t(owner[v])].name;
        if (name == "clavicle_l" || name == "clavicle_r")
          shoulder_top = std::max(shoulder_top, body.mesh.vertices[v].z());
      }
      fitted.top = Vector3d(0, trunk.end.y(), shoulder_top + clearance);
      fitted.lid = true;
      fitted.anchor = "shoulder";
    } else {
      fitted.top = Vector3d(0, trunk.start.y(), trunk.start.z());
      fitted.anchor = "waist";
    }
    break;
  }
  case Cylinder::arm_l:
  case Cylinder::arm_r: {
    const std::string side = c == Cylinder::arm_l ? "_l" : "_r";
    const Bone& upper = body.bone("upper_arm" + side);
    const Bone& fore = body.bone("forearm" + side);
    fitted.up = (upper.start - fore.end).normalized();
    fitted.top = upper.start + 0.04 * fitted.up;
    fitted.anchor = "shoulder joint";
    break;
  }
  case Cylinder::leg_l:
  case Cylinder::leg_r: {
    const std::string side = c == Cylinder::leg_l ? "_l" : "_r";
    const Bone& thigh = body.bone("thigh" + side);
    const Bone& shin = body.bone("shin" + side);
    fitted.up = (thigh.start - shin.end).normalized();
    const double waist = body.bone("torso").start.z();
    fitted.top = thigh.start + (waist - thigh.start.z()) / fitted.up.z() * fitted.up;
    fitted.anchor = "waist";
    break;
  }
  case Cylinder::neck: {
    const Bone& neck = body.bone("neck");
    fitted.up = (neck.end - neck.start).normalized();
    fitted.top = neck.start + 0.09 * fitted.up;
    fitted.anchor = "neck base + 9 cm";
    break;
  }
  case Cylinder::head: {
    const Bone& head = body.bone("head");
    fitted.up = (head.end - head.start).normalized();
    fitted.top = head.end + 0.12 * fitted.up;
    fitted.anchor = "crown + 12 cm";
    break;
  }
  }
  fitted.front = front_normal_to(fitted.up);
  return fitted;
}

// Largest distance from the axis of the vertices owned by the cylinder's
// bones within its covered length (a leg also takes the trunk's flesh on
// its side of the body). The torso's section is the trunk's: the shoulder
// girdle reaches out to the arm roots, and a cylinder that wide puts the
// torso panels' side lines through the arms below the armpits; the lid
// covers the girdle from above and the arm cylinders its ends.
double section_radius(const FittedCylinder& c, const Mannequin& body,
                      const std::vector<int>& owner) {
  std::set<std::string> bones(c.bones.begin(), c.bones.end());
  if (c.cylinder == Cylinder::torso) {
    bones.erase("clavicle_l");
    bones.erase("clavicle_r");
  }
  double radius = 0;
  for (std::size_t v = 0; v < owner.size(); ++v) {
    const Vector3d& p = body.mesh.vertices[v];
    const std::string& name = body.skeleton[std::size_t(owner[v])].name;
    bool mine = bones.count(name) > 0;
    if (!mine && (c.cylinder == Cylinder::leg_l || c.cylinder == Cylinder::leg_r)) {
      mine = (name == "pelvis" || name == "torso" || name == "hip_l" || name == "hip_r") &&
             p.x() * limb_sign(c.cylinder) > 0;
    }
    if (!mine) continue;
    const double axial = (p - c.top).dot(c.up);
    if (axial > 0.02 || axial < -c.length - 0.02) continue;
    radius = std::max(radius, normal_part(p - c.top, c.up).norm());
  }
  return radius;
}

// The angle about the axis of unrolled point (arc s, axial a): s / radius,
// on the lid too (folded in to the radius radius - a), kept within the
// pack's half. The lid's circles are shorter than the rim, so a panel
// folded onto it is compressed around the axis (by a / radius; 30 % at the
// neck points of the sample tops), never stretched: keeping the arc length
// along the smaller circles instead shears the fold by s / (radius - a),
// and stretched the T-shirt's shoulders (Green strain up to 0.53).
double wrap_angle(const FittedCylinder& c, double radius, const Vector2d& unrolled) {
  const double angle = unrolled.x() / radius;
  if (!(c.lid && unrolled.y() > 0)) return angle;
  return std::clamp(angle, -0.5 * pi, 0.5 * pi);
}

// Unrolled half-cylinder coordinates (arc s, axial a) to 3D.
Vector3d wrap(const FittedCylinder& c, Side side, double radius, double layer_lift,
              const Vector2d& unrolled) {
  const Vector3d centre_direction = side == Side::front ? c.front : Vector3d(-c.front);
  const Vector3d across = c.up.cross(centre_direction);
  const double angle = wrap_angle(c, radius, unrolled);
  const Vector3d radial = std::cos(angle) * centre_direction + std::sin(angle) * across;
  if (c.lid && unrolled.y() > 0)
    return c.top + layer_lift * c.up + std::max(radius - unrolled.y(), 0.0) * radial;
  return c.top + unrolled.y() * c.up + radius * radial;
}

std::array<Vector3d, 2> wrap_frame(const FittedCylinder& c, Side side, double radius,
                                   const Vector2d& unrolled) {
  const Vector3d centre_direction = side == Side::front ? c.front : Vector3d(-c.front);
  const Vector3d across = c.up.cross(centre_direction);
  const double angle = wrap_angle(c, radius, unrolled);
  const Vector3d radial = std::cos(angle) * centre_direction + std::sin(angle) * across;
  const Vector3d around = -std::sin(angle) * centre_direction + std::cos(angle) * across;
  if (c.lid && unrolled.y() > 0) return {around, -radial};
  return {around, c.up};
}

Vector2d closest_on_polyline(const std::vector<Vector2d>& points, const Vector2d& p) {
  Vector2d best = points.front();
  double best_distance = 1e300;
  for (std::size_t k = 1; k < points.size(); ++k) {
    const Vector2d ab = points[k] - points[k - 1];
    const double t = std::clamp((p - points[k - 1]).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    const Vector2d q = points[k - 1] + t * ab;
    if ((q - p).norm() < best_distance) {
      best_distance = (q - p).norm();
      best = q;
    }
  }
  return best;
}

// The point at normalised arc length t of a sampled line (equal pieces).
Vector3d at_fraction(const std::vector<Vector3d>& samples, double t) {
  const double x = std::clamp(t, 0.0, 1.0) * double(samples.size() - 1);
  const std::size_t k = std::min(std::size_t(x), samples.size() - 2);
  const double f = x - double(k);
  return (1 - f) * samples[k] + f * samples[k + 1];
}

} // namespace

// The orientation whose seam springs (point to point at equal arc length)
// start with the least energy. Comparing only the end points' distances can
// twist a ring's seam: the hood's neck edge, placed round the back of the
// head, ends 1 cm nearer the front neckline's far end the wrong way round.
bool should_reverse(const LineGeometry& a, const LineGeometry& b) {
  double direct = 0.0;
  double crossed = 0.0;
  const double last = double(a.samples.size() - 1);
  for (std::size_t k = 0; k < a.samples.size(); ++k) {
    const double t = double(k) / last;
    direct += (a.samples[k] - at_fraction(b.samples, t)).squaredNorm();
    crossed += (a.samples[k] - at_fraction(b.samples, 1 - t)).squaredNorm();
  }
  return crossed < direct;
}

const char* name_of(SeamKind kind) {
  switch (kind) {
  case SeamKind::intra_pack:
    return "intra_pack";
  case SeamKind::inter_cylinder:
    return "inter_cylinder";
  case SeamKind::inter_half_cylinder:
    return "inter_half_cylinder";
  case SeamKind::t_seam:
    return "t_seam";
  case SeamKind::y_seam:
    return "y_seam";
  case SeamKind::dart:
    return "dart";
  case SeamKind::user:
    return "user";
  }
  return "?";
}

bool cylinders_adjacent(Cylinder a, Cylinder b) {
  if (a == b) return false;
  const auto pair = [&](Cylinder x, Cylinder y) {
    return (a == x && b == y) || (a == y && b == x);
  };
  return pair(Cylinder::torso, Cylinder::arm_l) || pair(Cylinder::torso, Cylinder::arm_r) ||
         pair(Cylinder::torso, Cylinder::neck) || pair(Cylinder::torso, Cylinder::head) ||
         pair(Cylinder::torso, Cylinder::leg_l) || pair(Cylinder::torso, Cylinder::leg_r) ||
         pair(Cylinder::neck, Cylinder::head) || pair(Cylinder::leg_l, Cylinder::leg_r);
}

MatchScore match_score(const LineGeometry& i, const LineGeometry& j, bool seamable,
                       const TagconOptions& options) {
  MatchScore m;
  m.distance = std::max(0.0, (options.d_max - (i.centre - j.centre).norm()) / options.d_max);
  // An interior (T-seam) line has no outward side: its normal is taken
  // facing the other line.
  const double dot = i.normal.dot(j.normal);
  m.orientation = (i.interior || j.interior) ? (1 + std::abs(dot)) / 2 : (1 - dot) / 2;
  m.length =
      std::max(0.0, (options.length_diff - std::abs(i.length - j.length)) / options.length_diff);
  m.curvature = std::max(0.0, (options.curvature_diff - std::abs(i.curvature - j.curvature)) /
                                  options.curvature_diff);
  m.seamable = seamable ? 1 : 0;
  return m;
}

std::vector<std::array<int, 2>> closest_line_pairs(const std::vector<LineGeometry>& lines,
                                                   const std::vector<int>& group,
                                                   const std::vector<int>& panel,
                                                   double fov_half_angle_deg, double max_distance) {
  const double cos_fov = std::cos(fov_half_angle_deg * pi / 180);
  const int n = int(lines.size());
  std::vector<int> choice(std::size_t(n), -1);
  for (int i = 0; i < n; ++i) {
    if (group[std::size_t(i)] < 0) continue;
    const LineGeometry& li = lines[std::size_t(i)];
    const double touching = 1e-9 * std::max(1.0, li.length);
    double best = max_distance;
    for (int j = 0; j < n; ++j) {
      if (j == i || group[std::size_t(j)] != group[std::size_t(i)] ||
          panel[std::size_t(j)] == panel[std::size_t(i)])
        continue;
      const Vector2d nearest = closest_on_polyline(lines[std::size_t(j)].samples_2d, li.centre_2d);
      const Vector2d towards = nearest - li.centre_2d;
      const double distance = towards.norm();
      const bool in_view = distance <= touching || towards.dot(li.normal_2d) >= cos_fov * distance;
      if (in_view && distance <= best) {
        if (distance < best || choice[std::size_t(i)] < 0) choice[std::size_t(i)] = j;
        best = distance;
      }
    }
  }
  std::vector<std::array<int, 2>> pairs;
  for (int i = 0; i < n; ++i) {
    const int j = choice[std::size_t(i)];
    if (j > i && choice[std::size_t(j)] == i) pairs.push_back({i, j});
  }
  return pairs;
}

int best_ring_shift(int size_a, int size_b, const std::function<double(int, int)>& score,
                    int clicks) {
  int individual = 0;
  for (int j = 1; j < size_b; ++j)
    if (score(0, j) > score(0, individual)) individual = j;
  int best_shift = individual;
  double best_sum = -1;
  for (int click = 0; click <= clicks; ++click) {
    for (int direction : {-1, 1}) {
      if (click == 0 && direction == 1) continue;
      const int shift = ((individual + direction * click) % size_b + size_b) % size_b;
      double sum = 0;
      for (int i = 0; i < std::min(size_a, size_b); ++i)
        sum += score(i, (i + shift) % size_b);
      if (sum > best_sum + 1e-12) {
        best_sum = sum;
        best_shift = shift;
      }
    }
  }
  return best_shift;
}

std::vector<FittedCylinder> fit_cylinders(const Pattern& pattern, const Mannequin& body,
                                          const TagconOptions& options) {
  const bool upper_body = upper_body_garment(pattern);
  const std::vector<int> owner = nearest_bones(body);
  std::vector<FittedCylinder> cylinders;
  for (Cylinder c : all_cylinders()) {
    std::vector<int> packs;
    for (std::size_t k = 0; k < pattern.packs.size(); ++k)
      if (pattern.pack_tag(int(k)).cylinder == c) packs.push_back(int(k));
    if (packs.empty()) continue;
    FittedCylinder fitted = cylinder_axis(c, body, upper_body, options.clearance, owner);
    double widest = 0;
    int widest_pack = packs.front();
    for (int k : packs) {
      Vector2d low, high;
      pack_box(pattern, pattern.packs[std::size_t(k)], &low, &high);
      const double height = high.y() - low.y() - (fitted.lid ? options.lid_depth : 0.0);
      fitted.length = std::max(fitted.length, height);
      if (high.x() - low.x() > widest) {
        widest = high.x() - low.x();
        widest_pack = k;
      }
    }
    fitted.body_radius = section_radius(fitted, body, owner);
    if (fitted.body_radius == 0) { // no flesh of its bones in the covered length
      for (const auto& name : fitted.bones)
        fitted.body_radius = std::max(fitted.body_radius, body.bone(name).start_radius);
    }
    const double fitted_radius = fitted.body_radius + options.clearance;
    const double widest_allowed = options.max_widening * pi * fitted_radius;
    if (widest > widest_allowed) {
      // Thesis Fig. 3.9: a panel that spans two cylinders (sleeves cut in one
      // with the bodice) cannot be wrapped onto one half cylinder.
      const Pack& pack = pattern.packs[std::size_t(widest_pack)];
      Vector2d low, high;
      pack_box(pattern, pack, &low, &high);
      const double centre = 0.5 * (low.x() + high.x());
      std::vector<std::string> beyond;
      std::string panels;
      for (const auto& member : pack.members) {
        const Panel& panel = pattern.panels[std::size_t(member.panel)];
        panels += (panels.empty() ? "'" : ", '") + panel.id + "'";
        for (const auto& line : panel.outline) {
          for (const auto& p : line.curve.flatten(pattern.flattening_tolerance())) {
            if (std::abs(member.placement.apply(p).x() - centre) > 0.5 * widest_allowed) {
              beyond.push_back("'" + line.id + "'");
              break;
            }
          }
        }
      }
      std::string lines;
      for (std::size_t k = 0; k < beyond.size(); ++k)
        lines += (k ? ", " : "") + beyond[k];
      throw InputError(pattern.source + ": " + pack.json_path + ": pack '" + pack.id + "' " +
                       to_string(pattern.pack_tag(widest_pack)) + " is " + format(widest) +
                       " m wide, but its half cylinder '" + name_of(c) + "' (radius " +
                       format(fitted_radius) + " m) takes at most " + format(widest_allowed) +
                       " m: lines " + lines + " of panel " + panels +
                       " lie beyond it and cannot be placed or seamed. TAGCON wraps every "
                       "panel onto one cylinder (thesis Fig. 3.9): cut a part that belongs to "
                       "another cylinder (e.g. a sleeve) as its own panel with its own tag");
    }
    fitted.radius = std::max(fitted_radius, widest / pi);
    cylinders.push_back(fitted);
  }
  return cylinders;
}

int Construction::line_index(const std::string& id) const {
  for (std::size_t k = 0; k < lines.size(); ++k)
    if (lines[k].id == id) return int(k);
  return -1;
}

Vector3d Construction::place_in_pack(int pack, const Vector2d& point) const {
  const PackPlacement& placed = packs[std::size_t(pack)];
  const FittedCylinder& c = cylinders[std::size_t(placed.cylinder)];
  Vector3d p = wrap(c, placed.tag.side, placed.radius,
                    std::max(0, placed.tag.layer) * options.layer_gap, point + placed.offset);
  if (body) {
    Vector3d normal;
    const double distance = body(p, &normal);
    const double wanted = 0.5 * options.clearance;
    if (distance < wanted) p += (wanted - distance) * normal.normalized();
  }
  return p;
}

std::array<Vector3d, 2> Construction::wrap_tangents(int pack, const Vector2d& point) const {
  const PackPlacement& placed = packs[std::size_t(pack)];
  return wrap_frame(cylinders[std::size_t(placed.cylinder)], placed.tag.side, placed.radius,
                    point + placed.offset);
}

Vector3d Construction::place(int panel, const Vector2d& point) const {
  const int pack = pattern->pack_of(panel);
  for (const auto& member : pattern->packs[std::size_t(pack)].members)
    if (member.panel == panel) return place_in_pack(pack, member.placement.apply(point));
  return Vector3d::Zero();
}

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

LineGeometry line_geometry(const Construction& construction, int panel_index, int pack,
                           const Placement& member, const Curve& curve, std::string id,
                           bool interior, int index) {
  LineGeometry line;
  line.panel = panel_index;
  line.index = index;
  line.interior = interior;
  line.id = std::move(id);
  line.length = curve.length();
  for (const auto& p : curve.split_equal_arc_length(samples_per_line))
    line.samples_2d.push_back(member.apply(p));
  const std::size_t n = line.samples_2d.size();
  Vector3d normal = Vector3d::Zero();
  Vector2d normal_2d = Vector2d::Zero();
  double turning = 0;
  for (std::size_t k = 0; k < n; ++k) {
    line.samples.push_back(construction.place_in_pack(pack, line.samples_2d[k]));
    const Vector2d tangent =
        (line.samples_2d[std::min(k + 1, n - 1)] - line.samples_2d[k > 0 ? k - 1 : 0]).normalized();
    // Counter-clockwise outlines: the outside is to the right of the tangent.
    const Vector2d outward(tangent.y(), -tangent.x());
    normal_2d += outward;
    const auto frame = construction.wrap_tangents(pack, line.samples_2d[k]);
    normal += outward.x() * frame[0] + outward.y() * frame[1];
    if (k >= 2) {
      const Vector2d d0 = line.samples_2d[k - 1] - line.samples_2d[k - 2];
      const Vector2d d1 = line.samples_2d[k] - line.samples_2d[k - 1];
      turning += std::abs(std::atan2(d0.x() * d1.y() - d0.y() * d1.x(), d0.dot(d1)));
    }
  }
  line.normal = normal.normalized();
  line.normal_2d = normal_2d.normalized();
  line.centre = line.samples[n / 2];
  line.centre_2d = line.samples_2d[n / 2];
  line.curvature = turning / line.length;
  return line;
}

// A limb line's side: +1 lateral, -1 medial (towards the body's midline),
// 0 in between (front or back centre).
int limb_side(const FittedCylinder& c, const LineGeometry& line) {
  const Vector3d lateral = normal_part(Vector3d(limb_sign(c.cylinder), 0, 0), c.up).normalized();
  const double offset = normal_part(line.centre - c.top, c.up).dot(lateral);
  if (offset > 0.4 * c.radius) return 1;
  if (offset < -0.4 * c.radius) return -1;
  return 0;
}

struct Pair {
  int a, b;
  double score;
};

// Best individual match of every line of both sets in the other set, pairs
// sorted by M descending, created greedily (thesis §3.3.2, inter-half).
std::vector<Pair> greedy_sorted_matching(const std::vector<int>& first,
                                         const std::vector<int>& second,
                                         const std::function<double(int, int)>& score,
                                         double min_match) {
  std::vector<Pair> candidates;
  const auto best_of = [&](int i, const std::vector<int>& others, bool i_first) {
    int best = -1;
    double best_score = min_match;
    for (int j : others) {
      const double s = i_first ? score(i, j) : score(j, i);
      if (s > best_score) {
        best_score = s;
        best = j;
      }
    }
    if (best >= 0)
      candidates.push_back(i_first ? Pair{i, best, best_score} : Pair{best, i, best_score});
  };
  for (int i : first)
    best_of(i, second, true);
  for (int j : second)
    best_of(j, first, false);
  std::sort(candidates.begin(), candidates.end(), [](const Pair& x, const Pair& y) {
    if (x.score != y.score) return x.score > y.score;
    return std::make_pair(x.a, x.b) < std::make_pair(y.a, y.b);
  });
  std::set<int> used;
  std::vector<Pair> chosen;
  for (const Pair& p : candidates) {
    if (used.count(p.a) || used.count(p.b)) continue;
    used.insert(p.a);
    used.insert(p.b);
    chosen.push_back(p);
  }
  return chosen;
}

// Positioning (§3.1.2): the cylinder each tag names, by its index in
// Construction::cylinders.
std::map<Cylinder, int> index_of_cylinders(const std::vector<FittedCylinder>& cylinders) {
  std::map<Cylinder, int> index;
  for (std::size_t k = 0; k < cylinders.size(); ++k)
    index[cylinders[k].cylinder] = int(k);
  return index;
}

// Pack k's box centred on its half cylinder, its top at the cylinder's
// anchor (on the lid when the torso has one).
PackPlacement position_pack(const Pattern& pattern, std::size_t k,
                            const std::vector<FittedCylinder>& cylinders,
                            const std::map<Cylinder, int>& cylinder_index,
                            const TagconOptions& options) {
  PackPlacement placed;
  placed.pack = int(k);
  placed.tag = pattern.pack_tag(int(k));
  pack_box(pattern, pattern.packs[k], &placed.box_min, &placed.box_max);
  placed.cylinder = cylinder_index.at(placed.tag.cylinder);
  const FittedCylinder& c = cylinders[std::size_t(placed.cylinder)];
  placed.radius = c.radius + placed.tag.layer * options.layer_gap;
  if (placed.radius <= 0.5 * c.radius) {
    throw InputError(pattern.source + ": " + pattern.packs[k].json_path + ": pack '" +
                     pattern.packs[k].id + "' is on layer " + std::to_string(placed.tag.layer) +
                     ", too far inside its cylinder (radius " + format(c.radius) + " m)");
  }
  placed.offset = Vector2d(-0.5 * (placed.box_min.x() + placed.box_max.x()),
                           (c.lid ? options.lid_depth : 0.0) - placed.box_max.y());
  return placed;
}

// The box of the lines that `wanted` selects in the packs placed on lower
// layers of `placed`'s half cylinder, in unrolled coordinates.
template <class Lines, class Wanted>
Eigen::AlignedBox2d lines_beneath_box(const Pattern& pattern,
                                      const std::vector<PackPlacement>& packs,
                                      const PackPlacement& placed, Lines lines_of, Wanted wanted) {
  Eigen::AlignedBox2d box;
  for (const auto& beneath : packs) {
    if (beneath.tag.layer >= placed.tag.layer || beneath.tag.cylinder != placed.tag.cylinder ||
        beneath.tag.side != placed.tag.side)
      continue;
    for (const auto& member : pattern.packs[std::size_t(beneath.pack)].members)
      for (const auto& line : lines_of(pattern.panels[std::size_t(member.panel)]))
        if (wanted(line))
          for (const auto& p : line.curve.flatten(pattern.flattening_tolerance()))
            box.extend(member.placement.apply(p) + beneath.offset);
  }
  return box;
}

// Outer layers sewn by T-seams sit over the T-seam lines beneath them, so
// that those lines are in their 3D position (§3.3.3); those sewn by
// Y-seams put their Y-seam lines over the Y-seam lines beneath.
void align_outer_layers(const Pattern& pattern, std::vector<PackPlacement>& packs) {
  const auto interior_of = [](const Panel& panel) -> const auto& {
    return panel.interior;
  };
  const auto outline_of = [](const Panel& panel) -> const auto& {
    return panel.outline;
  };
  const auto is_t_seam = [](const InteriorLine& line) {
    return line.kind == InteriorLine::Kind::t_seam;
  };
  const auto is_y_seam = [](const OutlineLine& line) { return line.y_seam; };
  for (auto& placed : packs) {
    if (placed.tag.layer == 0) continue;
    Eigen::AlignedBox2d targets = lines_beneath_box(pattern, packs, placed, interior_of, is_t_seam);
    if (!targets.isEmpty()) {
      placed.offset = targets.center() - 0.5 * (placed.box_min + placed.box_max);
      continue;
    }
    targets = lines_beneath_box(pattern, packs, placed, outline_of, is_y_seam);
    Eigen::AlignedBox2d own;
    for (const auto& member : pattern.packs[std::size_t(placed.pack)].members)
      for (const auto& line : pattern.panels[std::size_t(member.panel)].outline)
        if (line.y_seam)
          for (const auto& p : line.curve.flatten(pattern.flattening_tolerance()))
            own.extend(member.placement.apply(p));
    if (!targets.isEmpty() && !own.isEmpty()) placed.offset = targets.center() - own.center();
  }
}

// Every outline line and T-seam interior line in 3D, in panel order
// (outline, then interior) for stable output.
std::vector<LineGeometry> placed_lines(const Pattern& pattern, const Construction& construction) {
  std::vector<LineGeometry> lines;
  for (std::size_t k = 0; k < pattern.packs.size(); ++k) {
    for (const auto& member : pattern.packs[k].members) {
      const Panel& panel = pattern.panels[std::size_t(member.panel)];
      for (std::size_t l = 0; l < panel.outline.size(); ++l)
        lines.push_back(line_geometry(construction, member.panel, int(k), member.placement,
                                      panel.outline[l].curve, panel.outline[l].id, false, int(l)));
      for (std::size_t l = 0; l < panel.interior.size(); ++l)
        if (panel.interior[l].kind == InteriorLine::Kind::t_seam)
          lines.push_back(line_geometry(construction, member.panel, int(k), member.placement,
                                        panel.interior[l].curve, panel.interior[l].id, true,
                                        int(l)));
    }
  }
  std::stable_sort(lines.begin(), lines.end(),
                   [](const LineGeometry& x, const LineGeometry& y) { return x.panel < y.panel; });
  return lines;
}

// Seam creation (§3.3.4) over the placed lines of `result`, step by step.
// Each step marks the lines it settles as done, with the reason why a line
// stays unseamed.
class SeamFinder {
public:
  SeamFinder(const Pattern& pattern, const Mannequin& body, const BodyDistance& body_distance,
             const TagconOptions& options, const std::map<Cylinder, int>& cylinder_index,
             Construction& result)
      : pattern_(pattern), body_(body), body_distance_(body_distance), options_(options),
        cylinder_index_(cylinder_index), result_(result), n_(int(result.lines.size())),
        done_(std::size_t(n_), false), why_(std::size_t(n_)), role_(std::size_t(n_), Role::along),
        partner_cylinder_(std::size_t(n_), -1), inter_half_(std::size_t(n_), false) {}

  void find_seams() {
    sew_darts();
    sew_layers();
    sew_intra_pack();
    classify_remaining();
    sew_inter_cylinder();
    sew_inter_half_cylinder();
    delete_penetrating_seams();
    list_unseamed();
  }

  // Every pack of a pattern with several has a seam; throws an InputError
  // naming the pack and why each of its lines stayed unseamed.
  void check_every_pack_seamed() const;

private:
  enum class Role { along, top_end, bottom_end };

  PanelTag tag_of(int line) const {
    return pattern_.panels[std::size_t(result_.lines[std::size_t(line)].panel)].tag;
  }
  int pack_of_line(int line) const {
    return pattern_.pack_of(result_.lines[std::size_t(line)].panel);
  }
  const FittedCylinder& cylinder_of(int line) const {
    return result_.cylinders[std::size_t(cylinder_index_.at(tag_of(line).cylinder))];
  }
  const OutlineLine* outline_line(int line) const {
    const LineGeometry& g = result_.lines[std::size_t(line)];
    return g.interior ? nullptr
                      : &pattern_.panels[std::size_t(g.panel)].outline[std::size_t(g.index)];
  }
  bool used(Cylinder c) const { return cylinder_index_.count(c) > 0; }
  // Marks line i done and unseamed for `reason`.
  void give_up(int i, std::string reason) {
    done_[std::size_t(i)] = true;
    why_[std::size_t(i)] = std::move(reason);
  }
  void add_seam(SeamKind kind, int a, int b, const MatchScore& score);
  bool seamable(int i, int j) const;
  double score(int i, int j) const {
    return match_score(result_.lines[std::size_t(i)], result_.lines[std::size_t(j)], seamable(i, j),
                       options_)
        .value();
  }
  void sew_darts();
  void sew_layers();
  void sew_intra_pack();
  Role role_of(int line) const;
  int cylinder_at_end(int line, Role role) const;
  void classify_along(int i);
  void classify_remaining();
  std::array<std::vector<int>, 2> ring_lines(int first, int second) const;
  void sew_ring(int first, int second, std::array<std::vector<int>, 2>& rings);
  void sew_inter_cylinder();
  void sew_inter_half_cylinder();
  std::pair<double, Vector3d> deepest_sweep_point(const FoundSeam& seam) const;
  void delete_penetrating_seams();
  void list_unseamed();

  const Pattern& pattern_;
  const Mannequin& body_;
  const BodyDistance& body_distance_;
  const TagconOptions& options_;
  const std::map<Cylinder, int>& cylinder_index_;
  Construction& result_;
  const int n_; // lines
  std::vector<bool> done_;
  std::vector<std::string> why_;
  std::vector<int> remaining_; // lines left to step 4
  std::vector<Role> role_;
  std::vector<int> partner_cylinder_; // inter-cylinder: the other cylinder
  std::vector<bool> inter_half_;
  std::vector<bool> seamed_;
};

void SeamFinder::add_seam(SeamKind kind, int a, int b, const MatchScore& score) {
  FoundSeam seam;
  seam.kind = kind;
  seam.line_a = a;
  seam.line_b = b;
  seam.score = score;
  seam.certainty = std::clamp(score.value(), 0.01, 1.0);
  seam.reverse = should_reverse(result_.lines[std::size_t(a)], result_.lines[std::size_t(b)]);
  result_.seams.push_back(seam);
}

// M_sa (eq. 3.6) for inter-pack lines: inherently unseamable unless on
// two adjacent cylinders or the two halves of one; conventionally
// unseamable: a limb's medial (inner) line with a lateral (outer) one.
bool SeamFinder::seamable(int i, int j) const {
  const PanelTag a = tag_of(i), b = tag_of(j);
  if (a.cylinder == b.cylinder) {
    if (a.side == b.side) return false;
    if (is_limb(a.cylinder)) {
      const FittedCylinder& c = cylinder_of(i);
      if (limb_side(c, result_.lines[std::size_t(i)]) *
              limb_side(c, result_.lines[std::size_t(j)]) <
          0)
        return false;
    }
    return true;
  }
  if (!cylinders_adjacent(a.cylinder, b.cylinder)) return false;
  // Conventionally unseamable: the two legs join at the crotch only, not
  // along their inseams.
  if (is_limb(a.cylinder) && is_limb(b.cylinder)) {
    const double crotch = body_.bone("thigh_l").start.z() - 0.15;
    return result_.lines[std::size_t(i)].centre.z() > crotch &&
           result_.lines[std::size_t(j)].centre.z() > crotch;
  }
  return true;
}

// Step 1b: every dart's legs are sewn to each other, leg start to leg end
// (apex to apex), before TAGCON matches the other lines, so that no leg is
// left unseamed nor sewn to another panel.
void SeamFinder::sew_darts() {
  for (const Panel& panel : pattern_.panels) {
    for (const Dart& dart : panel.darts) {
      const int a = result_.line_index(dart.first_leg), b = result_.line_index(dart.second_leg);
      MatchScore certain;
      certain.distance = certain.orientation = certain.length = certain.curvature =
          certain.seamable = 1;
      add_seam(SeamKind::dart, a, b, certain);
      result_.seams.back().reverse = true;
      done_[std::size_t(a)] = done_[std::size_t(b)] = true;
    }
  }
}

// Step 2: inter-layer seams. T: an outer layer's outline line to a T-seam
// interior line beneath; Y: an outer layer's Y-seam line to a Y-seam line
// of layer 0 (which keeps its normal seam too). The lines of outer layers
// and the T-seam lines left over join nothing else.
void SeamFinder::sew_layers() {
  for (SeamKind kind : {SeamKind::t_seam, SeamKind::y_seam}) {
    std::vector<int> outer, beneath;
    for (int i = 0; i < n_; ++i) {
      const LineGeometry& g = result_.lines[std::size_t(i)];
      if (g.interior) {
        if (kind == SeamKind::t_seam) beneath.push_back(i);
      } else if (tag_of(i).layer != 0) {
        if (kind == SeamKind::t_seam || outline_line(i)->y_seam) outer.push_back(i);
      } else if (kind == SeamKind::y_seam && outline_line(i)->y_seam) {
        beneath.push_back(i);
      }
    }
    const auto layered_score = [&](int i, int j) {
      const PanelTag a = tag_of(i), b = tag_of(j);
      const bool ok = a.cylinder == b.cylinder && a.side == b.side && b.layer < a.layer;
      return match_score(result_.lines[std::size_t(i)], result_.lines[std::size_t(j)], ok, options_)
          .value();
    };
    std::vector<int> free_outer;
    for (int i : outer)
      if (!done_[std::size_t(i)]) free_outer.push_back(i);
    for (const Pair& p :
         greedy_sorted_matching(free_outer, beneath, layered_score, options_.min_match)) {
      add_seam(kind, p.a, p.b,
               match_score(result_.lines[std::size_t(p.a)], result_.lines[std::size_t(p.b)], true,
                           options_));
      done_[std::size_t(p.a)] = true;
      if (kind == SeamKind::t_seam) done_[std::size_t(p.b)] = true;
    }
  }
  for (int i = 0; i < n_; ++i) {
    if (done_[std::size_t(i)]) continue;
    if (result_.lines[std::size_t(i)].interior)
      give_up(i, "T-seam line: no outer-layer line matches it");
    else if (tag_of(i).layer != 0)
      give_up(i, "a line of layer " + std::to_string(tag_of(i).layer) +
                     " joins only by T- and Y-seams, and none matches it");
  }
}

// Step 3: intra-pack seams (§3.3.1), in each pack's plane.
void SeamFinder::sew_intra_pack() {
  std::vector<int> group(std::size_t(n_), -1), panel(std::size_t(n_), -1);
  for (int i = 0; i < n_; ++i) {
    panel[std::size_t(i)] = result_.lines[std::size_t(i)].panel;
    if (!done_[std::size_t(i)]) group[std::size_t(i)] = pack_of_line(i);
  }
  for (const auto& pair : closest_line_pairs(
           result_.lines, group, panel, options_.fov_half_angle_deg, options_.intra_distance)) {
    const LineGeometry& a = result_.lines[std::size_t(pair[0])];
    const LineGeometry& b = result_.lines[std::size_t(pair[1])];
    MatchScore s = match_score(a, b, true, options_);
    const double gap = (closest_on_polyline(b.samples_2d, a.centre_2d) - a.centre_2d).norm();
    s.distance = 1 - gap / options_.intra_distance;
    s.orientation = 1;
    add_seam(SeamKind::intra_pack, pair[0], pair[1], s);
    done_[std::size_t(pair[0])] = done_[std::size_t(pair[1])] = true;
  }
}

// Where a line faces in its half's unrolled plane (see classify_remaining).
SeamFinder::Role SeamFinder::role_of(int line) const {
  const double cos_end = std::cos(pi / 4);
  const LineGeometry& g = result_.lines[std::size_t(line)];
  if (tag_of(line).cylinder == Cylinder::torso) {
    const PackPlacement& placed = result_.packs[std::size_t(pack_of_line(line))];
    const double centre_line = 0.5 * (placed.box_min.x() + placed.box_max.x());
    double low = 1e300, high = -1e300;
    for (const Vector2d& p : g.samples_2d) {
      low = std::min(low, p.x() - centre_line);
      high = std::max(high, p.x() - centre_line);
    }
    const double reach = 1e-3 * std::max(g.length, 1e-3);
    const bool reaches_centre = low <= reach && high >= -reach;
    const bool faces_centre = g.normal_2d.x() * (g.centre_2d.x() - centre_line) < 0;
    if (g.normal_2d.y() > 0 && (reaches_centre || faces_centre)) return Role::top_end;
    return g.normal_2d.y() <= -cos_end ? Role::bottom_end : Role::along;
  }
  if (g.normal_2d.y() >= cos_end) return Role::top_end;
  if (g.normal_2d.y() <= -cos_end) return Role::bottom_end;
  return Role::along;
}

// The cylinder joined at a line's end of its cylinder; -1 where the
// pattern has none. `up` points to the shoulder on limbs, to the crown on
// the neck and head.
int SeamFinder::cylinder_at_end(int line, Role role) const {
  const Cylinder c = tag_of(line).cylinder;
  const bool top = role == Role::top_end;
  const auto if_used = [&](Cylinder other) { return used(other) ? int(other) : -1; };
  switch (c) {
  case Cylinder::torso: {
    if (top) return used(Cylinder::neck) ? int(Cylinder::neck) : if_used(Cylinder::head);
    const bool left = result_.lines[std::size_t(line)].centre.x() > 0;
    return if_used(left ? Cylinder::leg_l : Cylinder::leg_r);
  }
  case Cylinder::arm_l:
  case Cylinder::arm_r:
  case Cylinder::leg_l:
  case Cylinder::leg_r:
    return top ? if_used(Cylinder::torso) : -1;
  case Cylinder::neck:
    return if_used(top ? Cylinder::head : Cylinder::torso);
  case Cylinder::head:
    if (top) return -1;
    return used(Cylinder::neck) ? int(Cylinder::neck) : if_used(Cylinder::torso);
  }
  return -1;
}

// A line along its cylinder joins the other half, or a cylinder joined on
// this side (an arm's cap on the torso, the other leg), whichever matches
// it best.
void SeamFinder::classify_along(int i) {
  const Cylinder c = tag_of(i).cylinder;
  double best_half = 0, best_side = 0;
  int side_cylinder = -1;
  for (int j : remaining_) {
    const Cylinder d = tag_of(j).cylinder;
    const bool along = role_[std::size_t(j)] == Role::along;
    if (d == c) {
      if (along) best_half = std::max(best_half, score(i, j));
      continue;
    }
    const bool arm_cap = c == Cylinder::torso && (d == Cylinder::arm_l || d == Cylinder::arm_r) &&
                         role_[std::size_t(j)] == Role::top_end;
    const auto is_leg = [](Cylinder x) { return x == Cylinder::leg_l || x == Cylinder::leg_r; };
    const bool other_leg = is_leg(c) && is_leg(d) && along;
    if (!arm_cap && !other_leg) continue;
    const double s = score(i, j);
    if (s > best_side) best_side = s, side_cylinder = int(d);
  }
  if (std::max(best_half, best_side) < options_.min_match) {
    give_up(i, "runs along its cylinder, but no line of the other half or of a "
               "cylinder joined on its side matches it (best M = " +
                   format(std::max(best_half, best_side), 2) + ")");
  } else if (best_side > best_half) {
    partner_cylinder_[std::size_t(i)] = side_cylinder;
  } else {
    inter_half_[std::size_t(i)] = true;
  }
}

// Step 4: classify the rest by the garment construction theory of the
// cylinder abstraction (thesis Fig. 3.2). Cylinders join end to end (a
// sleeve's cap to the torso, a collar's lower edge to the neckline, a
// hood's neck edge to the torso's top opening), the arms on the torso's
// sides and the legs on each other's inner sides at the crotch; the two
// halves of a cylinder join along its length (and across the lid of a
// shoulder-anchored torso: the shoulders). In a half's unrolled plane:
//  * a line whose normal lies within 45 degrees of the axis faces an end
//    of its cylinder: an inter-cylinder line with the cylinder the
//    pattern has there (a non-seam line where there is none, step 5);
//  * on the torso, an upward line that reaches the half's centre line or
//    faces it borders the top opening (neck, or head without a neck),
//    which is centred on the axis; a line facing down faces its bottom end;
//  * every other line runs along its cylinder: an inter-half-cylinder
//    line, except that a torso line may join an arm's cap and a leg line
//    the other leg (above the crotch, M_sa), when its best M there
//    exceeds its best M with the other half's lines along the cylinder.
void SeamFinder::classify_remaining() {
  for (int i = 0; i < n_; ++i)
    if (!done_[std::size_t(i)]) remaining_.push_back(i);
  for (int i : remaining_)
    role_[std::size_t(i)] = role_of(i);
  for (int i : remaining_) {
    const Role role = role_[std::size_t(i)];
    if (role == Role::along) {
      classify_along(i);
      continue;
    }
    const int other = cylinder_at_end(i, role);
    if (other >= 0)
      partner_cylinder_[std::size_t(i)] = other;
    else
      give_up(i, std::string("faces the ") + (role == Role::top_end ? "top" : "bottom") +
                     " end of its cylinder '" + name_of(tag_of(i).cylinder) +
                     "', where the pattern has no adjacent cylinder");
  }
}

// The inter-cylinder lines of the junction of cylinders `first` and
// `second`: those of `first` towards `second`, and those of `second`
// towards `first`.
std::array<std::vector<int>, 2> SeamFinder::ring_lines(int first, int second) const {
  std::array<std::vector<int>, 2> rings;
  for (int side = 0; side < 2; ++side) {
    const int here = side == 0 ? first : second, there = side == 0 ? second : first;
    for (int i : remaining_)
      if (!done_[std::size_t(i)] && int(tag_of(i).cylinder) == here &&
          partner_cylinder_[std::size_t(i)] == there)
        rings[std::size_t(side)].push_back(i);
  }
  return rings;
}

// Sews the two rings of a junction: each sorted by angle around the ring
// axis, the smaller ring's lines to the larger's at the best cyclic shift.
void SeamFinder::sew_ring(int first, int second, std::array<std::vector<int>, 2>& rings) {
  const Cylinder cyl_a = Cylinder(first), cyl_b = Cylinder(second);
  // The ring axis: the distal cylinder's (both legs: the vertical between them).
  Vector3d origin, up, front;
  if ((cyl_a == Cylinder::leg_l || cyl_a == Cylinder::leg_r) &&
      (cyl_b == Cylinder::leg_l || cyl_b == Cylinder::leg_r)) {
    const auto& l = result_.cylinders[std::size_t(cylinder_index_.at(cyl_a))];
    const auto& r = result_.cylinders[std::size_t(cylinder_index_.at(cyl_b))];
    origin = 0.5 * (l.top + r.top);
    up = Vector3d::UnitZ();
    front = -Vector3d::UnitY();
  } else {
    const Cylinder distal = cyl_a == Cylinder::torso ? cyl_b : cyl_a;
    const auto& c = result_.cylinders[std::size_t(cylinder_index_.at(distal))];
    origin = c.top;
    up = c.up;
    front = c.front;
  }
  const Vector3d across = up.cross(front);
  const auto angle = [&](int line) {
    const Vector3d r = result_.lines[std::size_t(line)].centre - origin;
    return std::atan2(r.dot(across), r.dot(front));
  };
  for (auto& ring : rings)
    std::stable_sort(ring.begin(), ring.end(), [&](int x, int y) { return angle(x) < angle(y); });
  const bool swapped = rings[0].size() > rings[1].size();
  const std::vector<int>& small = swapped ? rings[1] : rings[0];
  const std::vector<int>& large = swapped ? rings[0] : rings[1];
  const auto ring_score = [&](int i, int j) {
    return score(small[std::size_t(i)], large[std::size_t(j)]);
  };
  const int shift =
      best_ring_shift(int(small.size()), int(large.size()), ring_score, options_.clicks);
  std::vector<bool> large_used(large.size(), false);
  for (std::size_t i = 0; i < small.size(); ++i) {
    const std::size_t j = (i + std::size_t(shift)) % large.size();
    const int a = small[i], b = large[j];
    const double m = score(a, b);
    done_[std::size_t(a)] = true;
    if (m < options_.min_match) {
      why_[std::size_t(a)] = "the best ring match pairs it with '" +
                             result_.lines[std::size_t(b)].id + "', but M = " + format(m, 2);
      continue;
    }
    done_[std::size_t(b)] = true;
    large_used[j] = true;
    add_seam(SeamKind::inter_cylinder, a, b,
             match_score(result_.lines[std::size_t(a)], result_.lines[std::size_t(b)],
                         seamable(a, b), options_));
  }
  for (std::size_t j = 0; j < large.size(); ++j)
    if (!large_used[j] && !done_[std::size_t(large[j])])
      give_up(large[j], "left over by the ring match (rings of " + std::to_string(small.size()) +
                            " and " + std::to_string(large.size()) + " lines)");
}

// Steps 5-6: inter-cylinder seams, ring by ring.
void SeamFinder::sew_inter_cylinder() {
  std::set<std::pair<int, int>> junctions;
  for (int i : remaining_)
    if (partner_cylinder_[std::size_t(i)] >= 0) {
      const int a = int(tag_of(i).cylinder), b = partner_cylinder_[std::size_t(i)];
      junctions.insert({std::min(a, b), std::max(a, b)});
    }
  for (const auto& [first, second] : junctions) {
    std::array<std::vector<int>, 2> rings = ring_lines(first, second);
    if (rings[0].empty() || rings[1].empty()) {
      for (const auto& ring : rings)
        for (int i : ring)
          give_up(i, std::string("inter-cylinder line with no corresponding line in "
                                 "the adjacent cylinder '") +
                         name_of(int(tag_of(i).cylinder) == first ? Cylinder(second)
                                                                  : Cylinder(first)) +
                         "'");
      continue;
    }
    sew_ring(first, second, rings);
  }
}

// Step 7: inter-half-cylinder seams, cylinder by cylinder.
void SeamFinder::sew_inter_half_cylinder() {
  const auto half_score = [&](int i, int j) { return score(i, j); };
  for (const auto& c : result_.cylinders) {
    std::vector<int> front, back;
    for (int i : remaining_)
      if (!done_[std::size_t(i)] && inter_half_[std::size_t(i)] && tag_of(i).cylinder == c.cylinder)
        (tag_of(i).side == Side::front ? front : back).push_back(i);
    for (const Pair& p : greedy_sorted_matching(front, back, half_score, options_.min_match)) {
      add_seam(SeamKind::inter_half_cylinder, p.a, p.b,
               match_score(result_.lines[std::size_t(p.a)], result_.lines[std::size_t(p.b)], true,
                           options_));
      done_[std::size_t(p.a)] = done_[std::size_t(p.b)] = true;
    }
    for (int i : front)
      if (!done_[std::size_t(i)])
        why_[std::size_t(i)] = "its best match in the other half was taken";
    for (int i : back)
      if (!done_[std::size_t(i)])
        why_[std::size_t(i)] = "its best match in the other half was taken";
  }
}

// The deepest point (signed distance < 0) of the flesh of the seam's two
// cylinders' body parts that the sweep between its lines meets, and where;
// 0 when it meets none (intra-pack seams and darts are not swept).
std::pair<double, Vector3d> SeamFinder::deepest_sweep_point(const FoundSeam& seam) const {
  const LineGeometry& a = result_.lines[std::size_t(seam.line_a)];
  const LineGeometry& b = result_.lines[std::size_t(seam.line_b)];
  double deepest = 0;
  Vector3d where = Vector3d::Zero();
  // Only the flesh of the two cylinders' body parts counts: a torso side
  // seam's sweep may pass behind the hanging arm, as the cloth will.
  std::set<std::string> parts;
  for (int line : {seam.line_a, seam.line_b}) {
    const Cylinder c = tag_of(line).cylinder;
    for (const auto& bone : bones_of(c))
      parts.insert(bone);
    if (c == Cylinder::leg_l || c == Cylinder::leg_r)
      parts.insert({"pelvis", "torso", "hip_l", "hip_r"});
  }
  if (seam.kind != SeamKind::intra_pack && seam.kind != SeamKind::dart && body_distance_) {
    for (int q = 0; q < options_.sweep_pairs; ++q) {
      const double t = (q + 0.5) / options_.sweep_pairs;
      const Vector3d pa = at_fraction(a.samples, t);
      const Vector3d pb = at_fraction(b.samples, seam.reverse ? 1 - t : t);
      for (double s : {0.25, 0.5, 0.75}) {
        const Vector3d x = (1 - s) * pa + s * pb;
        const double d = body_distance_(x, nullptr);
        if (d < deepest && parts.count(body_.skeleton[std::size_t(nearest_bone(body_, x))].name))
          deepest = d, where = x;
      }
    }
  }
  return {deepest, where};
}

// Step 9: delete seams whose sweep penetrates the body.
void SeamFinder::delete_penetrating_seams() {
  std::vector<FoundSeam> kept;
  for (const FoundSeam& seam : result_.seams) {
    const auto [deepest, where] = deepest_sweep_point(seam);
    if (deepest < -options_.penetration) {
      const LineGeometry& a = result_.lines[std::size_t(seam.line_a)];
      const LineGeometry& b = result_.lines[std::size_t(seam.line_b)];
      result_.deleted.push_back(seam);
      const std::string reason = "the sweep of its seam with '" + b.id + "' penetrates the body " +
                                 format(-100 * deepest, 2) + " cm deep at (" + format(where.x()) +
                                 ", " + format(where.y()) + ", " + format(where.z()) + ")";
      why_[std::size_t(seam.line_a)] = reason;
      why_[std::size_t(seam.line_b)] =
          "the sweep of its seam with '" + a.id + "' penetrates the body";
    } else {
      kept.push_back(seam);
    }
  }
  result_.seams = kept;
}

void SeamFinder::list_unseamed() {
  seamed_.assign(std::size_t(n_), false);
  for (const auto& seam : result_.seams)
    seamed_[std::size_t(seam.line_a)] = seamed_[std::size_t(seam.line_b)] = true;
  for (int i = 0; i < n_; ++i)
    if (!seamed_[std::size_t(i)])
      result_.unseamed.push_back(
          {i, why_[std::size_t(i)].empty() ? "not matched" : why_[std::size_t(i)]});
}

void SeamFinder::check_every_pack_seamed() const {
  if (pattern_.packs.size() <= 1) return;
  for (std::size_t k = 0; k < pattern_.packs.size(); ++k) {
    bool any = false;
    std::string reasons;
    for (int i = 0; i < n_; ++i) {
      if (pack_of_line(i) != int(k)) continue;
      any = any || seamed_[std::size_t(i)];
      reasons += "\n  '" + result_.lines[std::size_t(i)].id + "': " + why_[std::size_t(i)];
    }
    if (!any)
      throw InputError(pattern_.source + ": " + pattern_.packs[k].json_path + ": pack '" +
                       pattern_.packs[k].id + "' " + to_string(pattern_.pack_tag(int(k))) +
                       " has no seam: none of its lines could be seamed:" + reasons);
  }
}

} // namespace

Construction construct(const Pattern& pattern, const Mannequin& body,
                       const BodyDistance& body_distance, const TagconOptions& options) {
  Construction result;
  result.pattern = &pattern;
  result.options = options;
  result.body = body_distance;
  const auto placement_start = Clock::now();
  result.cylinders = fit_cylinders(pattern, body, options);
  const std::map<Cylinder, int> cylinder_index = index_of_cylinders(result.cylinders);
  for (std::size_t k = 0; k < pattern.packs.size(); ++k)
    result.packs.push_back(position_pack(pattern, k, result.cylinders, cylinder_index, options));
  align_outer_layers(pattern, result.packs);
  result.lines = placed_lines(pattern, result);
  result.placement_seconds = seconds_since(placement_start);

  const auto seam_start = Clock::now();
  SeamFinder finder(pattern, body, body_distance, options, cylinder_index, result);
  finder.find_seams();
  result.seam_seconds = seconds_since(seam_start);
  finder.check_every_pack_seamed();
  return result;
}

} // namespace sartor::garment
