#include "contact/mannequin.hpp"

#include "common/error.hpp"
#include "contact/self_intersections.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <utility>

namespace sartor {

namespace {

// --- primitives: signed distances with, as `level` asks, their gradients and
// their Hessians (exact for the capsule, first-order for the ellipsoid),
// negative inside. Polygonising the body needs no Hessians, and computing
// them made its generation three times as long. ------------------------------

using FieldValue = MannequinFieldValue;

// What a field evaluation computes besides the value. The value comes out of
// the same arithmetic at every level, and so does the gradient where asked.
enum class Derivatives { none, gradient, hessian };

Eigen::Matrix3d across_projector(const Eigen::Vector3d& unit) {
  return Eigen::Matrix3d::Identity() - unit * unit.transpose();
}

// The convex hull of two spheres (centres a, b; radii ra, rb with
// |ra - rb| < |b - a|). In the plane of the axis and p, with y along the
// axis from a and x the distance from it, the side is the line tangent to
// both circles; its outward normal (s, c) has s = (ra - rb)/L. Points whose
// foot on that line falls before a's tangent point (or after b's) are
// nearest to the sphere there.
struct TaperedCapsule {
  Eigen::Vector3d a;
  Eigen::Vector3d b;
  double ra;
  double rb;
  double length;
  Eigen::Vector3d unit; // along a -> b
  double s;
  double c;

  TaperedCapsule(const Eigen::Vector3d& start, const Eigen::Vector3d& end, double start_radius,
                 double end_radius)
      : a(start), b(end), ra(start_radius), rb(end_radius), length((b - a).norm()),
        unit((b - a) / length), s((ra - rb) / length), c(std::sqrt(1.0 - s * s)) {}

  template <Derivatives level>
  FieldValue distance(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d pa = p - a;
    const double y = pa.dot(unit);
    const Eigen::Vector3d radial = pa - y * unit;
    const double x = radial.norm();
    const double along_side = c * y - s * x;
    const auto sphere = [&p](const Eigen::Vector3d& centre, double r) {
      const Eigen::Vector3d d = p - centre;
      const double norm = d.norm();
      if constexpr (level == Derivatives::none)
        return FieldValue{norm - r, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero()};
      if (norm == 0.0) return FieldValue{-r, Eigen::Vector3d::UnitZ(), Eigen::Matrix3d::Zero()};
      const Eigen::Vector3d n = d / norm;
      if constexpr (level != Derivatives::hessian)
        return FieldValue{norm - r, n, Eigen::Matrix3d::Zero()};
      return FieldValue{norm - r, n, across_projector(n) / norm};
    };
    if (along_side < 0.0) return sphere(a, ra);
    if (along_side > c * length) return sphere(b, rb);
    if constexpr (level == Derivatives::none)
      return {s * y + c * x - ra, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero()};
    const Eigen::Vector3d across = x > 0.0 ? Eigen::Vector3d(radial / x) : unit.unitOrthogonal();
    const Eigen::Matrix3d curvature =
        level == Derivatives::hessian && x > 0.0
            ? Eigen::Matrix3d(c * (across_projector(unit) - across * across.transpose()) / x)
            : Eigen::Matrix3d::Zero();
    return {s * y + c * x - ra, s * unit + c * across, curvature};
  }
};

// Axes are the rows of `frame` (orthonormal). The distance k0 (k0 - 1) / k1,
// k0 = |q / r|, k1 = |q / r^2| (q in the ellipsoid's axes) is exact on the
// surface to first order, which is all a smooth union needs.
struct Ellipsoid {
  Eigen::Vector3d centre;
  Eigen::Vector3d radii;
  Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();

  template <Derivatives level>
  FieldValue distance(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d q = frame * (p - centre);
    const Eigen::Vector3d r2 = radii.cwiseProduct(radii);
    const Eigen::Vector3d q_r2 = q.cwiseQuotient(r2);
    const Eigen::Vector3d q_r4 = q_r2.cwiseQuotient(r2);
    const double k0 = std::sqrt(q.dot(q_r2));
    const double k1 = q_r2.norm();
    if (k1 == 0.0) return {-radii.minCoeff(), Eigen::Vector3d::UnitZ(), Eigen::Matrix3d::Zero()};
    if constexpr (level == Derivatives::none)
      return {k0 * (k0 - 1.0) / k1, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero()};
    const Eigen::Vector3d dk0 = q_r2 / k0;
    const Eigen::Vector3d dk1 = q_r4 / k1;
    // value g(k0) / k1 with g = k0 (k0 - 1)
    const double g = k0 * (k0 - 1.0);
    const double dg = 2.0 * k0 - 1.0;
    const Eigen::Vector3d local = (dg * k1 * dk0 - g * dk1) / (k1 * k1);
    if constexpr (level != Derivatives::hessian)
      return {g / k1, frame.transpose() * local, Eigen::Matrix3d::Zero()};
    const Eigen::Matrix3d ddk0 =
        (Eigen::Matrix3d(r2.cwiseInverse().asDiagonal()) - dk0 * dk0.transpose()) / k0;
    const Eigen::Matrix3d ddk1 =
        (Eigen::Matrix3d(r2.cwiseProduct(r2).cwiseInverse().asDiagonal()) - dk1 * dk1.transpose()) /
        k1;
    const Eigen::Matrix3d cross = dk0 * dk1.transpose();
    const Eigen::Matrix3d local_hessian = (2.0 * dk0 * dk0.transpose() + dg * ddk0) / k1 -
                                          dg * (cross + cross.transpose()) / (k1 * k1) +
                                          2.0 * g * dk1 * dk1.transpose() / (k1 * k1 * k1) -
                                          g * ddk1 / (k1 * k1);
    return {g / k1, frame.transpose() * local, frame.transpose() * local_hessian * frame};
  }
};

// Quadratic smooth minimum: equal to min(a, b) where |a - b| >= k, filling
// the crease between two surfaces with a fillet of size about k otherwise.
// The blend's weights change across the fillet, which bends it by
// -(grad a - grad b)(grad a - grad b)^T / (2k) on top of the weighted curvatures.
template <Derivatives level>
FieldValue smooth_min(const FieldValue& a, const FieldValue& b, double k) {
  const double h = std::max(k - std::abs(a.value - b.value), 0.0) / k;
  const double weight_a = a.value < b.value ? 1.0 - 0.5 * h : 0.5 * h;
  if constexpr (level == Derivatives::none)
    return {std::min(a.value, b.value) - 0.25 * k * h * h, Eigen::Vector3d::Zero(),
            Eigen::Matrix3d::Zero()};
  FieldValue blend{std::min(a.value, b.value) - 0.25 * k * h * h,
                   weight_a * a.gradient + (1.0 - weight_a) * b.gradient, Eigen::Matrix3d::Zero()};
  if constexpr (level == Derivatives::hessian) {
    const Eigen::Vector3d difference = a.gradient - b.gradient;
    blend.hessian = weight_a * a.hessian + (1.0 - weight_a) * b.hessian;
    if (h > 0.0) blend.hessian -= difference * difference.transpose() / (2.0 * k);
  }
  return blend;
}

FieldValue max(const FieldValue& a, const FieldValue& b) {
  return a.value >= b.value ? a : b;
}

constexpr double pi = 3.14159265358979323846;
// Arms away from the torso, in the A-pose of garment construction: hanging
// closer (27 degrees was tried), the upper arm's root reaches past the
// chest's side just below the armpit, where a torso garment's side seams
// end, so a seam sweep from the front panel to the back one would pass
// through the arm (thesis step 5 of 3.2 deletes such seams).
constexpr double arm_abduction = 45.0 * pi / 180.0;

// --- the body's design: joints and flesh, left side (x > 0) -----------------

struct Joints {
  Eigen::Vector3d pelvis{0.0, 0.0, 0.93};
  Eigen::Vector3d lumbar{0.0, 0.0, 1.08};
  Eigen::Vector3d neck_base{0.0, 0.005, 1.43};
  Eigen::Vector3d skull_base{0.0, 0.005, 1.57};
  Eigen::Vector3d crown{0.0, -0.005, 1.70};
  Eigen::Vector3d shoulder{0.185, 0.005, 1.40};
  Eigen::Vector3d elbow;
  Eigen::Vector3d wrist;
  Eigen::Vector3d fingers;
  Eigen::Vector3d hip{0.09, 0.0, 0.91};
  Eigen::Vector3d knee{0.105, -0.005, 0.50};
  Eigen::Vector3d ankle{0.115, 0.01, 0.085};
  Eigen::Vector3d toes{0.12, -0.13, 0.03};

  Joints() { place_arm(1.0); }

  // The arm from the shoulder, its segments `scale` times the default's.
  void place_arm(double scale) {
    const Eigen::Vector3d down_arm(std::sin(arm_abduction), 0.0, -std::cos(arm_abduction));
    elbow = shoulder + scale * 0.29 * down_arm;
    wrist = elbow + scale * 0.25 * down_arm;
    // Short of the fingertips (wrist + 0.165): the hand is thin there, and
    // at 45 degrees the 2 cm grid leaves less of it than the joint needs.
    fingers = wrist + 0.12 * down_arm;
  }
};

Eigen::Vector3d mirrored(Eigen::Vector3d p) {
  p.x() = -p.x();
  return p;
}

// The floor a foot stands on: the half-space normal . p > offset is cut
// away (standing: z < 0). It turns with the foot when the leg is posed.
struct Sole {
  Eigen::Vector3d normal{0.0, 0.0, -1.0};
  double offset = 0.0;
  FieldValue distance(const Eigen::Vector3d& p) const {
    return {normal.dot(p) - offset, normal, Eigen::Matrix3d::Zero()};
  }
};

struct Limbs {
  TaperedCapsule upper_arm;
  TaperedCapsule forearm;
  Ellipsoid hand;
  TaperedCapsule thigh;
  TaperedCapsule shin;
  Ellipsoid calf;
  Ellipsoid foot;
  Ellipsoid buttock;
  Sole sole;
  Eigen::Vector3d fingers; // where the hand's bone ends
  Eigen::Vector3d toes;
};

Limbs left_limbs(const Joints& j) {
  // The hand hangs along the forearm, palm towards the thigh.
  const Eigen::Vector3d along = (j.wrist - j.elbow).normalized();
  const Eigen::Vector3d width = Eigen::Vector3d::UnitY();
  Eigen::Matrix3d hand_frame;
  hand_frame.row(0) = along;
  hand_frame.row(1) = width;
  hand_frame.row(2) = along.cross(width);
  return {{j.shoulder, j.elbow, 0.05, 0.037},
          {j.elbow, j.wrist, 0.04, 0.026},
          {j.wrist + 0.08 * along, {0.085, 0.043, 0.019}, hand_frame},
          {j.hip, j.knee, 0.085, 0.053},
          {j.knee, j.ankle, 0.05, 0.033},
          {{j.knee.x() + 0.002, j.knee.y() + 0.022, 0.36}, {0.047, 0.05, 0.1}},
          {{j.ankle.x() + 0.005, -0.045, 0.025}, {0.045, 0.13, 0.05}},
          {{0.065, 0.045, 0.9}, {0.085, 0.075, 0.1}},
          {},
          j.fingers,
          j.toes};
}

Limbs mirrored(const Limbs& left) {
  Limbs right = left;
  for (TaperedCapsule* c : {&right.upper_arm, &right.forearm, &right.thigh, &right.shin})
    *c = TaperedCapsule(mirrored(c->a), mirrored(c->b), c->ra, c->rb);
  for (Ellipsoid* e : {&right.hand, &right.calf, &right.foot, &right.buttock}) {
    e->centre = mirrored(e->centre);
    e->frame.col(0) = -e->frame.col(0);
  }
  right.sole.normal = mirrored(right.sole.normal);
  right.fingers = mirrored(right.fingers);
  right.toes = mirrored(right.toes);
  return right;
}

// x -> rotation x + shift.
struct RigidMotion {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d shift = Eigen::Vector3d::Zero();
  Eigen::Vector3d operator()(const Eigen::Vector3d& p) const { return rotation * p + shift; }
  // This motion after `inner`.
  RigidMotion after(const RigidMotion& inner) const {
    return {rotation * inner.rotation, rotation * inner.shift + shift};
  }
};

struct Design {
  Joints joints;
  Ellipsoid head{{0.0, -0.005, 1.64}, {0.077, 0.098, 0.11}};
  Ellipsoid jaw{{0.0, -0.03, 1.575}, {0.058, 0.06, 0.05}};
  Ellipsoid nose{{0.0, -0.1, 1.625}, {0.013, 0.022, 0.028}};
  TaperedCapsule neck{{0.0, 0.01, 1.40}, {0.0, 0.005, 1.59}, 0.058, 0.05};
  TaperedCapsule shoulders{{-0.175, 0.01, 1.39}, {0.175, 0.01, 1.39}, 0.055, 0.055};
  Ellipsoid chest{{0.0, 0.005, 1.27}, {0.16, 0.11, 0.18}};
  Ellipsoid waist{{0.0, 0.005, 1.08}, {0.13, 0.095, 0.13}};
  Ellipsoid hips{{0.0, 0.01, 0.94}, {0.165, 0.11, 0.12}};
  Limbs left = left_limbs(joints);
  Limbs right = mirrored(left);
  // The default body is polygonised in a fixed box; others in their bounds.
  bool is_default = true;
  // Posed: each moved bone's motion from the unposed body (skeleton() names).
  std::map<std::string, RigidMotion> bone_motions;
};

const Design& default_design() {
  static const Design d;
  return d;
}

template <Derivatives level>
FieldValue arm_field(const Limbs& l, const Eigen::Vector3d& p) {
  const FieldValue arm =
      smooth_min<level>(l.upper_arm.distance<level>(p), l.forearm.distance<level>(p), 0.02);
  return smooth_min<level>(arm, l.hand.distance<level>(p), 0.02);
}

// Flat soles: the foot is cut by the floor z = 0.
template <Derivatives level>
FieldValue leg_field(const Limbs& l, const Eigen::Vector3d& p) {
  const FieldValue leg =
      smooth_min<level>(l.thigh.distance<level>(p), l.shin.distance<level>(p), 0.03);
  const FieldValue calf = smooth_min<level>(leg, l.calf.distance<level>(p), 0.03);
  return smooth_min<level>(calf, max(l.foot.distance<level>(p), l.sole.distance(p)), 0.03);
}

template <Derivatives level>
FieldValue body_field(const Design& d, const Eigen::Vector3d& p) {
  FieldValue trunk = smooth_min<level>(d.chest.distance<level>(p), d.waist.distance<level>(p), 0.1);
  trunk = smooth_min<level>(trunk, d.hips.distance<level>(p), 0.1);
  trunk = smooth_min<level>(trunk, d.shoulders.distance<level>(p), 0.06);
  trunk = smooth_min<level>(trunk, d.left.buttock.distance<level>(p), 0.04);
  trunk = smooth_min<level>(trunk, d.right.buttock.distance<level>(p), 0.04);
  FieldValue head = smooth_min<level>(d.head.distance<level>(p), d.jaw.distance<level>(p), 0.04);
  head = smooth_min<level>(head, d.nose.distance<level>(p), 0.015);
  FieldValue body = smooth_min<level>(trunk, d.neck.distance<level>(p), 0.04);
  body = smooth_min<level>(body, head, 0.03);
  body = smooth_min<level>(body, arm_field<level>(d.left, p), 0.03);
  body = smooth_min<level>(body, arm_field<level>(d.right, p), 0.03);
  body = smooth_min<level>(body, leg_field<level>(d.left, p), 0.04);
  return smooth_min<level>(body, leg_field<level>(d.right, p), 0.04);
}

// Newton steps along the gradient onto the zero level set.
Eigen::Vector3d project_to_surface(const Design& d, Eigen::Vector3d p) {
  for (int iteration = 0; iteration < 3; ++iteration) {
    const FieldValue f = body_field<Derivatives::gradient>(d, p);
    const double g2 = f.gradient.squaredNorm();
    if (std::abs(f.value) < 1e-10 || g2 < 1e-12) break;
    p -= (f.value / g2) * f.gradient;
  }
  return p;
}

// --- marching tetrahedra -----------------------------------------------------

constexpr double grid_spacing = 0.02; // m; sets the triangle count (about 36k)
// Near a fold (see `generate`), node values are kept this far from zero (m
// of field): where the surface passes closer to a node, the crossings on the
// node's 14 edges crowd within a fraction of a millimetre of it, slivers
// that smoothing spreads out and, on the thin hands, folds over one another.
// The zero set moves by about this much there, and smoothing projects every
// vertex back onto the true surface.
constexpr double near_node = 0.1 * grid_spacing;
constexpr double fold_radius = 2.0 * grid_spacing; // m: the nodes kept from zero around a fold

// The zero set of the piecewise-linear interpolant of the field on the
// Freudenthal subdivision of a regular grid (six tetrahedra per cube around
// its main diagonal; neighbouring cubes split their shared faces alike). With
// no node value exactly zero and the field positive on the grid's boundary,
// that set is a closed 2-manifold; each crossing vertex is shared by all the
// tetrahedra around its grid edge. Triangles are wound so that their normal
// points from the negative (inside) corners to the positive ones.
BodyMesh marching_tetrahedra(const Design& design, const Eigen::Vector3d& lower,
                             const Eigen::Vector3d& upper,
                             const std::vector<Eigen::Vector3d>& folds) {
  const auto near_fold = [&folds](const Eigen::Vector3d& p) {
    return std::any_of(folds.begin(), folds.end(), [&p](const Eigen::Vector3d& fold) {
      return (p - fold).norm() < fold_radius;
    });
  };
  // Shifted off round numbers so that no node lies on the sole plane z = 0.
  const Eigen::Vector3d origin = lower - Eigen::Vector3d::Constant(0.37 * grid_spacing);
  std::array<long, 3> n;
  for (int k = 0; k < 3; ++k)
    n[k] = static_cast<long>(std::ceil((upper[k] - origin[k]) / grid_spacing)) + 1;
  const auto node = [&](long i, long j, long k) { return (k * n[1] + j) * n[0] + i; };
  const auto position = [&](long i, long j, long k) {
    return Eigen::Vector3d(origin.x() + static_cast<double>(i) * grid_spacing,
                           origin.y() + static_cast<double>(j) * grid_spacing,
                           origin.z() + static_cast<double>(k) * grid_spacing);
  };
  std::vector<double> value(static_cast<std::size_t>(n[0] * n[1] * n[2]));
  for (long k = 0; k < n[2]; ++k)
    for (long j = 0; j < n[1]; ++j)
      for (long i = 0; i < n[0]; ++i) {
        const double f = body_field<Derivatives::none>(design, position(i, j, k)).value;
        const bool kept = std::abs(f) < near_node && near_fold(position(i, j, k));
        value[static_cast<std::size_t>(node(i, j, k))] = kept       ? std::copysign(near_node, f)
                                                         : f == 0.0 ? 1e-12
                                                                    : f;
      }

  BodyMesh mesh;
  std::unordered_map<std::int64_t, int> crossing; // (node * 8 + offset code) -> vertex
  struct Corner {
    std::array<long, 3> ijk;
    double f;
  };
  const auto crossing_vertex = [&](const Corner& a, const Corner& b) {
    const Corner& low = a.ijk <= b.ijk ? a : b;
    const Corner& high = a.ijk <= b.ijk ? b : a;
    const long code = (high.ijk[0] - low.ijk[0]) + 2 * (high.ijk[1] - low.ijk[1]) +
                      4 * (high.ijk[2] - low.ijk[2]);
    const std::int64_t key = node(low.ijk[0], low.ijk[1], low.ijk[2]) * 8 + code;
    const auto [it, inserted] = crossing.try_emplace(key, static_cast<int>(mesh.vertices.size()));
    if (inserted) {
      // Kept off the nodes so that no triangle collapses; relaxed later.
      const double t = std::clamp(low.f / (low.f - high.f), 0.01, 0.99);
      mesh.vertices.push_back((1.0 - t) * position(low.ijk[0], low.ijk[1], low.ijk[2]) +
                              t * position(high.ijk[0], high.ijk[1], high.ijk[2]));
    }
    return it->second;
  };
  const auto add_triangle = [&](int a, int b, int c, const Eigen::Vector3d& outward) {
    const Eigen::Vector3d& pa = mesh.vertices[static_cast<std::size_t>(a)];
    const Eigen::Vector3d normal = (mesh.vertices[static_cast<std::size_t>(b)] - pa)
                                       .cross(mesh.vertices[static_cast<std::size_t>(c)] - pa);
    if (normal.dot(outward) >= 0.0) {
      mesh.faces.push_back({a, b, c});
    } else {
      mesh.faces.push_back({a, c, b});
    }
  };
  static constexpr std::array<std::array<int, 3>, 6> axis_orders = {
      {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  for (long k = 0; k + 1 < n[2]; ++k)
    for (long j = 0; j + 1 < n[1]; ++j)
      for (long i = 0; i + 1 < n[0]; ++i) {
        for (const auto& order : axis_orders) {
          std::array<Corner, 4> tet;
          std::array<long, 3> ijk = {i, j, k};
          for (int c = 0; c < 4; ++c) {
            if (c > 0) ++ijk[order[c - 1]];
            tet[c] = {ijk, value[static_cast<std::size_t>(node(ijk[0], ijk[1], ijk[2]))]};
          }
          std::array<const Corner*, 4> inside{};
          std::array<const Corner*, 4> outside{};
          int n_in = 0;
          int n_out = 0;
          for (const Corner& c : tet)
            (c.f < 0.0 ? inside[n_in++] : outside[n_out++]) = &c;
          if (n_in == 0 || n_out == 0) continue;
          Eigen::Vector3d outward = Eigen::Vector3d::Zero();
          for (int c = 0; c < n_out; ++c)
            outward += position(outside[c]->ijk[0], outside[c]->ijk[1], outside[c]->ijk[2]) / n_out;
          for (int c = 0; c < n_in; ++c)
            outward -= position(inside[c]->ijk[0], inside[c]->ijk[1], inside[c]->ijk[2]) / n_in;
          if (n_in == 1 || n_out == 1) {
            const Corner* lone = n_in == 1 ? inside[0] : outside[0];
            const auto& others = n_in == 1 ? outside : inside;
            add_triangle(crossing_vertex(*lone, *others[0]), crossing_vertex(*lone, *others[1]),
                         crossing_vertex(*lone, *others[2]), outward);
          } else {
            // Crossings on the four edges between the two pairs form a cycle.
            const int ac = crossing_vertex(*inside[0], *outside[0]);
            const int ad = crossing_vertex(*inside[0], *outside[1]);
            const int bd = crossing_vertex(*inside[1], *outside[1]);
            const int bc = crossing_vertex(*inside[1], *outside[0]);
            add_triangle(ac, ad, bd, outward);
            add_triangle(ac, bd, bc, outward);
          }
        }
      }
  return mesh;
}

// Tangential Laplacian smoothing with re-projection onto the level set:
// marching tetrahedra leaves slivers where the surface passes near a node.
void relax(const Design& design, BodyMesh& mesh, int sweeps) {
  std::vector<std::vector<int>> neighbours(mesh.vertices.size());
  for (const auto& face : mesh.faces) {
    for (int c = 0; c < 3; ++c) {
      neighbours[static_cast<std::size_t>(face[c])].push_back(face[(c + 1) % 3]);
      neighbours[static_cast<std::size_t>(face[c])].push_back(face[(c + 2) % 3]);
    }
  }
  for (auto& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  std::vector<Eigen::Vector3d> next(mesh.vertices.size());
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
      const Eigen::Vector3d& p = mesh.vertices[v];
      Eigen::Vector3d centre = Eigen::Vector3d::Zero();
      for (int w : neighbours[v])
        centre += mesh.vertices[static_cast<std::size_t>(w)];
      centre /= static_cast<double>(neighbours[v].size());
      const Eigen::Vector3d normal =
          body_field<Derivatives::gradient>(design, p).gradient.normalized();
      Eigen::Vector3d move = 0.5 * (centre - p);
      move -= move.dot(normal) * normal;
      next[v] = project_to_surface(design, p + move);
    }
    mesh.vertices.swap(next);
  }
}

Bone bone(std::string name, std::string parent, const Eigen::Vector3d& start,
          const Eigen::Vector3d& end, double start_radius, double end_radius) {
  return {std::move(name), std::move(parent), start, end, start_radius, end_radius};
}

std::vector<Bone> skeleton(const Design& d) {
  const Joints& j = d.joints;
  std::vector<Bone> bones = {
      bone("pelvis", "", j.pelvis, j.lumbar, d.hips.radii.x(), d.waist.radii.x()),
      bone("torso", "pelvis", j.lumbar, j.neck_base, d.waist.radii.x(), d.chest.radii.x()),
      bone("neck", "torso", j.neck_base, j.skull_base, d.neck.ra, d.neck.rb),
      bone("head", "neck", j.skull_base, j.crown, d.head.radii.y(), d.head.radii.y()),
  };
  for (const auto& [side, limbs] :
       {std::pair{std::string("_l"), &d.left}, std::pair{std::string("_r"), &d.right}}) {
    const Limbs& l = *limbs;
    bones.push_back(bone("clavicle" + side, "torso", j.neck_base, l.upper_arm.a, d.shoulders.ra,
                         d.shoulders.rb));
    bones.push_back(bone("upper_arm" + side, "clavicle" + side, l.upper_arm.a, l.upper_arm.b,
                         l.upper_arm.ra, l.upper_arm.rb));
    bones.push_back(bone("forearm" + side, "upper_arm" + side, l.forearm.a, l.forearm.b,
                         l.forearm.ra, l.forearm.rb));
    bones.push_back(bone("hand" + side, "forearm" + side, l.forearm.b, l.fingers, l.hand.radii.y(),
                         l.hand.radii.y()));
    bones.push_back(bone("hip" + side, "pelvis", j.pelvis, l.thigh.a, l.thigh.ra, l.thigh.ra));
    bones.push_back(
        bone("thigh" + side, "hip" + side, l.thigh.a, l.thigh.b, l.thigh.ra, l.thigh.rb));
    bones.push_back(bone("shin" + side, "thigh" + side, l.shin.a, l.shin.b, l.shin.ra, l.shin.rb));
    bones.push_back(
        bone("foot" + side, "shin" + side, l.shin.b, l.toes, l.foot.radii.x(), l.foot.radii.x()));
  }
  return bones;
}

// --- sizing ------------------------------------------------------------------

// Heights of the default body the vertical map moves (m).
constexpr double default_crown = 1.75;
constexpr double default_hps = 1.43; // the neck's base, where the shoulder line meets it
constexpr double default_waist = 1.08;
constexpr double default_knee = 0.50;
constexpr double default_chest_level = 1.27;
constexpr double default_neck_level = 1.49;
constexpr double default_shoulder_width = 0.37; // between the shoulder joints
constexpr double default_arm_length = 0.54;     // shoulder joint to wrist joint

// A continuous piecewise-linear map of heights through (from, to) knots,
// extended beyond them with the end segments' slopes.
class VerticalMap {
public:
  void add(double from, double to) { knots_.emplace_back(from, to); }
  double operator()(double z) const {
    const std::size_t k = segment(z);
    return knots_[k].second + slope_of(k) * (z - knots_[k].first);
  }
  double slope(double z) const { return slope_of(segment(z)); }

private:
  std::size_t segment(double z) const {
    std::size_t k = 0;
    while (k + 2 < knots_.size() && z > knots_[k + 1].first)
      ++k;
    return k;
  }
  double slope_of(std::size_t k) const {
    return (knots_[k + 1].second - knots_[k].second) / (knots_[k + 1].first - knots_[k].first);
  }
  std::vector<std::pair<double, double>> knots_;
};

void map_heights(const VerticalMap& map, Eigen::Vector3d& p) {
  p.z() = map(p.z());
}

void map_heights(const VerticalMap& map, Ellipsoid& e) {
  e.radii.z() *= map.slope(e.centre.z());
  map_heights(map, e.centre);
}

void map_heights(const VerticalMap& map, TaperedCapsule& c) {
  Eigen::Vector3d a = c.a, b = c.b;
  map_heights(map, a);
  map_heights(map, b);
  c = TaperedCapsule(a, b, c.ra, c.rb);
}

// Radii across a capsule's axis and an ellipsoid's horizontal radii.
void widen(TaperedCapsule& c, double start_factor, double end_factor) {
  c = TaperedCapsule(c.a, c.b, start_factor * c.ra, end_factor * c.rb);
}

void widen(Ellipsoid& e, double factor) {
  e.radii.x() *= factor;
  e.radii.y() *= factor;
}

// The first surface crossing from `centre` along `direction` (centre inside).
double ray_to_surface(const Design& d, const Eigen::Vector3d& centre,
                      const Eigen::Vector3d& direction) {
  double inside = 0.0, outside = 0.004;
  while (body_field<Derivatives::none>(d, centre + outside * direction).value < 0.0) {
    inside = outside;
    outside += 0.004;
    if (outside > 1.0) return inside;
  }
  for (int i = 0; i < 22; ++i) {
    const double middle = 0.5 * (inside + outside);
    (body_field<Derivatives::none>(d, centre + middle * direction).value < 0.0 ? inside : outside) =
        middle;
  }
  return 0.5 * (inside + outside);
}

// A tape measure's girth: the perimeter of the convex hull of the section of
// the body by the plane through `centre` spanned by the unit vectors u, v
// (the part of the section seen from `centre`), m.
double girth(const Design& d, const Eigen::Vector3d& centre, const Eigen::Vector3d& u,
             const Eigen::Vector3d& v) {
  constexpr int rays = 160;
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < rays; ++i) {
    const double angle = 2.0 * pi * i / rays;
    const Eigen::Vector2d along(std::cos(angle), std::sin(angle));
    points.push_back(along * ray_to_surface(d, centre, along.x() * u + along.y() * v));
  }
  // Andrew's monotone chain.
  std::sort(points.begin(), points.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  const auto turns_left = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a,
                             const Eigen::Vector2d& b) {
    const Eigen::Vector2d oa = a - o, ob = b - o;
    return oa.x() * ob.y() - oa.y() * ob.x() > 0.0;
  };
  std::vector<Eigen::Vector2d> hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && !turns_left(hull[k - 2], hull[k - 1], points[i]))
      --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && !turns_left(hull[k - 2], hull[k - 1], points[i]))
      --k;
    hull[k++] = points[i];
  }
  double perimeter = 0.0;
  for (std::size_t i = 0; i + 1 < k; ++i)
    perimeter += (hull[i + 1] - hull[i]).norm();
  return perimeter;
}

double horizontal_girth(const Design& d, const Eigen::Vector3d& centre) {
  return girth(d, centre, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());
}

// Across a limb's capsule at `fraction` of its length from its start.
double limb_girth(const Design& d, const TaperedCapsule& c, double fraction) {
  const Eigen::Vector3d u = c.unit.cross(Eigen::Vector3d::UnitY()).normalized();
  return girth(d, c.a + fraction * c.length * c.unit, u, c.unit.cross(u));
}

// The point of a capsule's axis at height z.
Eigen::Vector3d axis_at_height(const TaperedCapsule& c, double z) {
  return c.a + (z - c.a.z()) / (c.b.z() - c.a.z()) * (c.b - c.a);
}

// The crotch: the lowest point of the body between the legs (x = 0).
double crotch_height(const Design& d) {
  double outside = 0.2, inside = d.joints.pelvis.z();
  const Eigen::Vector3d at(0.0, d.hips.centre.y(), 0.0);
  for (int i = 0; i < 40; ++i) {
    const double middle = 0.5 * (inside + outside);
    (body_field<Derivatives::none>(d, at + middle * Eigen::Vector3d::UnitZ()).value < 0.0
         ? inside
         : outside) = middle;
  }
  return 0.5 * (inside + outside);
}

// Heights of girths below the waist from the measurements, m.
double below_waist(const Measurements& m, const std::string& name) {
  return 1e-3 * (m.at("waistToFloor") - m.at(name));
}

// The girths the fit adjusts, as sizing measures them, mm.
Measurements measure_girths(const Design& d, const Measurements& m, const VerticalMap& map) {
  const Limbs& l = d.left;
  const double knee = below_waist(m, "waistToKnee");
  const TaperedCapsule& knee_piece = knee > l.thigh.b.z() ? l.thigh : l.shin;
  const Eigen::Vector3d neck = axis_at_height(d.neck, map(default_neck_level));
  return {
      {"chest", 1e3 * horizontal_girth(d, {0.0, d.chest.centre.y(), map(default_chest_level)})},
      {"waist", 1e3 * horizontal_girth(d, {0.0, d.waist.centre.y(), 1e-3 * m.at("waistToFloor")})},
      {"hips", 1e3 * horizontal_girth(d, {0.0, d.hips.centre.y(), below_waist(m, "waistToHips")})},
      {"seat", 1e3 * horizontal_girth(d, {0.0, d.hips.centre.y(), below_waist(m, "waistToSeat")})},
      {"neck", 1e3 * horizontal_girth(d, neck)},
      {"biceps", 1e3 * limb_girth(d, l.upper_arm, 0.45)},
      {"wrist", 1e3 * limb_girth(d, l.forearm, 1.0 - 0.02 / l.forearm.length)},
      {"knee", 1e3 * horizontal_girth(d, axis_at_height(knee_piece, knee))},
  };
}

// The vertical map from the default's heights to the requested ones: floor,
// knee (when asked for), crotch, waist, neck base (hps) and crown.
VerticalMap vertical_map(const Measurements& m, double default_crotch) {
  VerticalMap map;
  map.add(0.0, 0.0);
  map.add(default_knee, 1e-3 * (m.at("waistToFloor") - m.at("waistToKnee")));
  map.add(default_crotch, 1e-3 * m.at("inseam"));
  map.add(default_waist, 1e-3 * m.at("waistToFloor"));
  map.add(default_hps, 1e-3 * (m.at("waistToFloor") + m.at("hpsToWaistBack")));
  map.add(default_crown, 1e-3 * m.at("height"));
  return map;
}

// The girth factors' pieces: each factor widens the pieces that carry its girth.
using GirthFactors = std::map<std::string, double>;

void widen_left(Limbs& l, const GirthFactors& f) {
  widen(l.upper_arm, f.at("biceps"), f.at("biceps"));
  widen(l.forearm, f.at("wrist"), f.at("wrist"));
  // The thigh's top, a sphere at the hip joint, carries the hips too: the
  // hips' factor scales it and the legs' spacing.
  const Eigen::Vector3d out((f.at("hips") - 1.0) * l.thigh.a.x(), 0.0, 0.0);
  for (TaperedCapsule* c : {&l.thigh, &l.shin})
    *c = TaperedCapsule(c->a + out, c->b + out, c->ra, c->rb);
  for (Ellipsoid* e : {&l.calf, &l.foot})
    e->centre += out;
  l.toes += out;
  widen(l.thigh, f.at("hips"), f.at("knee"));
  widen(l.shin, f.at("knee"), 1.0);
  widen(l.calf, f.at("knee"));
  widen(l.buttock, f.at("seat"));
  l.buttock.centre.x() *= f.at("seat");
  l.buttock.centre.y() *= f.at("seat");
}

// The default design moved to the requested heights, shoulder width and arm
// length, before any girth is fitted.
Design stretched_design(const Measurements& m, const VerticalMap& map) {
  Design d = default_design();
  d.is_default = false;
  Joints& j = d.joints;
  for (Eigen::Vector3d* p : {&j.pelvis, &j.lumbar, &j.neck_base, &j.skull_base, &j.crown,
                             &j.shoulder, &j.hip, &j.knee, &j.ankle, &j.toes})
    map_heights(map, *p);
  j.shoulder.x() *= 1e-3 * m.at("shoulderToShoulder") / default_shoulder_width;
  j.place_arm(1e-3 * m.at("shoulderToWrist") / default_arm_length);
  for (Ellipsoid* e : {&d.head, &d.jaw, &d.nose, &d.chest, &d.waist, &d.hips})
    map_heights(map, *e);
  map_heights(map, d.neck);
  const double shoulder_half_width = j.shoulder.x() - (0.185 - 0.175);
  d.shoulders = TaperedCapsule({-shoulder_half_width, d.shoulders.a.y(), map(d.shoulders.a.z())},
                               {shoulder_half_width, d.shoulders.b.y(), map(d.shoulders.b.z())},
                               d.shoulders.ra, d.shoulders.rb);
  d.left = left_limbs(j);
  // left_limbs places these at the default's heights.
  for (Ellipsoid* e : {&d.left.calf, &d.left.foot, &d.left.buttock})
    map_heights(map, *e);
  // The pieces that carry the hips and the seat follow their levels (the
  // default's are 2 cm from them), or the fit would widen one to mend the other.
  d.hips.centre.z() = below_waist(m, "waistToHips") - 0.02;
  d.left.buttock.centre.z() = below_waist(m, "waistToSeat") + 0.02;
  return d;
}

Design widened_design(const Design& stretched, const GirthFactors& f) {
  Design d = stretched;
  widen(d.chest, f.at("chest"));
  widen(d.waist, f.at("waist"));
  widen(d.hips, f.at("hips"));
  widen(d.neck, f.at("neck"), f.at("neck"));
  widen_left(d.left, f);
  d.right = mirrored(d.left);
  return d;
}

// Fixed-point iteration on the girth factors: each is multiplied by the
// ratio of the requested girth to the measured one until every girth is
// within 0.2 % (the pieces interact through their fillets, weakly).
Design sized_design(const Measurements& m) {
  const double default_crotch = crotch_height(default_design());
  // The crotch knot is corrected as well: wider hips and seat fill the crotch.
  Measurements knots = m;
  GirthFactors factors;
  for (const MeasurementUse& use : mannequin_measurements())
    if (use.girth) factors[use.name] = 1.0;
  double worst = 0.0;
  std::string worst_name;
  for (int iteration = 0; iteration < 30; ++iteration) {
    const VerticalMap map = vertical_map(knots, default_crotch);
    const Design d = widened_design(stretched_design(knots, map), factors);
    worst = std::abs(1e3 * crotch_height(d) - m.at("inseam")) / m.at("inseam");
    worst_name = "inseam";
    knots["inseam"] += m.at("inseam") - 1e3 * crotch_height(d);
    for (const auto& [name, measured] : measure_girths(d, m, map)) {
      const double error = std::abs(m.at(name) / measured - 1.0);
      if (error > worst) {
        worst = error;
        worst_name = name;
      }
      factors[name] *= std::clamp(m.at(name) / measured, 0.85, 1.15);
    }
    if (worst < 2e-3) return d;
  }
  throw InputError("cannot size the mannequin to these measurements: its " + worst_name +
                   " stays " + std::to_string(100.0 * worst) +
                   " % away from the request (implausible proportions?)");
}

// --- posing ------------------------------------------------------------------

// A turn by `degrees` about the axis through `joint` that swings `segment`
// (a direction) towards `towards`.
RigidMotion flexion(const Eigen::Vector3d& joint, const Eigen::Vector3d& segment,
                    const Eigen::Vector3d& towards, double degrees) {
  const Eigen::Vector3d axis = segment.cross(towards).normalized();
  RigidMotion motion;
  motion.rotation = Eigen::AngleAxisd(degrees * pi / 180.0, axis).toRotationMatrix();
  motion.shift = joint - motion.rotation * joint;
  return motion;
}

void move(const RigidMotion& m, TaperedCapsule& c) {
  c = TaperedCapsule(m(c.a), m(c.b), c.ra, c.rb);
}

void move(const RigidMotion& m, Ellipsoid& e) {
  e.centre = m(e.centre);
  e.frame = e.frame * m.rotation.transpose();
}

void move(const RigidMotion& m, Sole& s) {
  const Eigen::Vector3d on_plane = s.offset * s.normal;
  s.normal = m.rotation * s.normal;
  s.offset = s.normal.dot(m(on_plane));
}

const Eigen::Vector3d forward(0.0, -1.0, 0.0);

void pose_limbs(Limbs& l, const Pose& pose, const std::string& side,
                std::map<std::string, RigidMotion>& motions) {
  const RigidMotion shoulder =
      flexion(l.upper_arm.a, l.upper_arm.unit, forward, pose.angle("shoulder" + side));
  const RigidMotion elbow =
      shoulder.after(flexion(l.forearm.a, l.forearm.unit, forward, pose.angle("elbow" + side)));
  move(shoulder, l.upper_arm);
  move(elbow, l.forearm);
  move(elbow, l.hand);
  l.fingers = elbow(l.fingers);
  const RigidMotion hip = flexion(l.thigh.a, l.thigh.unit, forward, pose.angle("hip" + side));
  const RigidMotion knee =
      hip.after(flexion(l.shin.a, l.shin.unit, -forward, pose.angle("knee" + side)));
  for (const auto& [bone, motion] :
       {std::pair{"upper_arm", shoulder}, std::pair{"forearm", elbow}, std::pair{"hand", elbow},
        std::pair{"thigh", hip}, std::pair{"shin", knee}, std::pair{"foot", knee}})
    motions[bone + side] = motion;
  move(hip, l.thigh);
  move(knee, l.shin);
  move(knee, l.calf);
  move(knee, l.foot);
  move(knee, l.sole);
  l.toes = knee(l.toes);
}

Design posed_design(const Design& rest, const Pose& pose) {
  Design d = rest;
  d.is_default = false;
  pose_limbs(d.left, pose, "_l", d.bone_motions);
  pose_limbs(d.right, pose, "_r", d.bone_motions);
  const RigidMotion neck = flexion(d.joints.neck_base, d.neck.unit, forward, pose.angle("neck"));
  for (Ellipsoid* e : {&d.head, &d.jaw, &d.nose})
    move(neck, *e);
  move(neck, d.neck);
  d.bone_motions["neck"] = neck;
  d.bone_motions["head"] = neck;
  d.joints.skull_base = neck(d.joints.skull_base);
  d.joints.crown = neck(d.joints.crown);
  return d;
}

// The box the body lies in with a margin that keeps the field positive on
// its boundary (a fillet lowers it by at most a quarter of its 10 cm size).
std::pair<Eigen::Vector3d, Eigen::Vector3d> polygonising_box(const Design& d) {
  if (d.is_default) return {{-0.74, -0.24, -0.02}, {0.74, 0.2, 1.78}}; // fingertips at |x| = 0.69
  Eigen::Vector3d lower = Eigen::Vector3d::Constant(1e9), upper = -lower;
  const auto add = [&](const Eigen::Vector3d& centre, double radius) {
    lower = lower.cwiseMin(centre - Eigen::Vector3d::Constant(radius));
    upper = upper.cwiseMax(centre + Eigen::Vector3d::Constant(radius));
  };
  for (const TaperedCapsule* c : {&d.neck, &d.shoulders}) {
    add(c->a, c->ra);
    add(c->b, c->rb);
  }
  for (const Ellipsoid* e : {&d.head, &d.jaw, &d.nose, &d.chest, &d.waist, &d.hips})
    add(e->centre, e->radii.maxCoeff());
  for (const Limbs* l : {&d.left, &d.right}) {
    for (const TaperedCapsule* c : {&l->upper_arm, &l->forearm, &l->thigh, &l->shin}) {
      add(c->a, c->ra);
      add(c->b, c->rb);
    }
    for (const Ellipsoid* e : {&l->hand, &l->calf, &l->foot, &l->buttock})
      add(e->centre, e->radii.maxCoeff());
  }
  lower -= Eigen::Vector3d::Constant(0.05);
  upper += Eigen::Vector3d::Constant(0.05);
  lower.z() = std::min(lower.z(), -0.02);
  return {lower, upper};
}

// The ellipsoids' first-order distances steepen away from them the more
// the longer their radii exceed their shortest (the hand: 8 for 4.5).
double ellipsoid_slope_bound(const Design& d) {
  double aspect = 0.0;
  const auto add = [&aspect](const Ellipsoid& e) {
    aspect = std::max(aspect, e.radii.maxCoeff() / e.radii.minCoeff());
  };
  for (const Ellipsoid* e : {&d.head, &d.jaw, &d.nose, &d.chest, &d.waist, &d.hips})
    add(*e);
  for (const Limbs* l : {&d.left, &d.right})
    for (const Ellipsoid* e : {&l->hand, &l->calf, &l->foot, &l->buttock})
      add(*e);
  const double default_aspect = 0.085 / 0.019;
  return 8.0 * std::max(1.0, aspect / default_aspect);
}

VerticalMap identity_map() {
  VerticalMap map;
  map.add(0.0, 0.0);
  map.add(default_crown, default_crown);
  return map;
}

Measurements compute_default_measurements() {
  const Design& d = default_design();
  const double inseam = 1e3 * crotch_height(d);
  Measurements m = {{"height", 1e3 * default_crown},
                    {"waistToFloor", 1e3 * default_waist},
                    {"hpsToWaistBack", 1e3 * (default_hps - default_waist)},
                    {"inseam", inseam},
                    {"waistToKnee", 1e3 * (default_waist - default_knee)},
                    {"shoulderToShoulder", 1e3 * default_shoulder_width},
                    {"shoulderToWrist", 1e3 * default_arm_length},
                    {"waistToHips", 120.0},
                    {"waistToSeat", 200.0}};
  for (const auto& [name, value] : measure_girths(d, m, identity_map()))
    m[name] = value;
  return m;
}

std::string millimetres(double value) {
  std::ostringstream out;
  out << value << " mm";
  return out.str();
}

// Each value within half to twice the default's, and the levels in order.
void check_plausible(const Measurements& m) {
  for (const auto& [name, value] : m) {
    const double reference = default_measurements().at(name);
    if (!(value >= 0.5 * reference && value <= 2.0 * reference)) {
      throw InputError("measurement '" + name + "' = " + millimetres(value) +
                       " is implausible: the mannequin takes 0.5 to 2 times its default " +
                       millimetres(reference));
    }
  }
  const double rise = m.at("waistToFloor") - m.at("inseam");
  const auto require = [&m](bool holds, const std::string& what) {
    if (!holds) throw InputError("implausible measurements: " + what);
  };
  require(m.at("height") > m.at("waistToFloor") + m.at("hpsToWaistBack") + 100.0,
          "height must exceed waistToFloor + hpsToWaistBack by more than 100 mm (the head)");
  require(rise > 100.0, "waistToFloor - inseam (the rise) must exceed 100 mm");
  require(m.at("waistToHips") < m.at("waistToSeat") && m.at("waistToSeat") < rise,
          "the levels must run waist, hips (waistToHips), seat (waistToSeat), crotch "
          "(waistToFloor - inseam) from the top");
  require(m.at("waistToKnee") > rise + 100.0 && m.at("waistToKnee") < m.at("waistToFloor") - 100.0,
          "the knee (waistToKnee) must lie more than 100 mm below the crotch and above the floor");
}

} // namespace

// --- public: measurements, poses, the model -----------------------------------

const std::vector<MeasurementUse>& mannequin_measurements() {
  static const std::vector<MeasurementUse> uses = {
      {"height", "the crown's height above the floor", false},
      {"waistToFloor", "the waist's height: where the waist girth is taken", false},
      {"hpsToWaistBack", "the neck's base (high point of the shoulder) above the waist", false},
      {"inseam", "the crotch's height", false},
      {"waistToKnee", "the knee joint below the waist", false},
      {"shoulderToShoulder", "between the shoulder joints", false},
      {"shoulderToWrist", "shoulder joint to wrist joint (the arm's length)", false},
      {"waistToHips", "the hips girth's level below the waist", false},
      {"waistToSeat", "the seat girth's level below the waist", false},
      {"chest", "girth at the chest (horizontal, 190 mm above the default waist, mapped)", true},
      {"waist", "girth at waistToFloor", true},
      {"hips", "girth at waistToHips below the waist", true},
      {"seat", "girth at waistToSeat below the waist", true},
      {"neck", "girth of the neck 60 mm above its base (mapped)", true},
      {"biceps", "girth across the upper arm, 45 % of the way to the elbow", true},
      {"wrist", "girth across the forearm 20 mm above the wrist joint", true},
      {"knee", "girth of the leg at waistToKnee", true},
  };
  return uses;
}

const Measurements& default_measurements() {
  static const Measurements measurements = compute_default_measurements();
  return measurements;
}

bool is_known_measurement(const std::string& name) {
  static const std::set<std::string> names = {"height",
                                              "ankle",
                                              "biceps",
                                              "bustFront",
                                              "bustBack",
                                              "bustPointToUnderbust",
                                              "bustSpan",
                                              "chest",
                                              "crossSeam",
                                              "crossSeamFront",
                                              "crotchDepth",
                                              "heel",
                                              "head",
                                              "highBust",
                                              "highBustBack",
                                              "highBustFront",
                                              "hips",
                                              "hpsToBust",
                                              "hpsToWaistBack",
                                              "hpsToWaistFront",
                                              "inseam",
                                              "knee",
                                              "neck",
                                              "seat",
                                              "seatBack",
                                              "shoulderSlope",
                                              "shoulderToElbow",
                                              "shoulderToShoulder",
                                              "shoulderToWrist",
                                              "underbust",
                                              "upperLeg",
                                              "waist",
                                              "waistBack",
                                              "waistToArmpit",
                                              "waistToFloor",
                                              "waistToHips",
                                              "waistToKnee",
                                              "waistToSeat",
                                              "waistToUnderbust",
                                              "waistToUpperLeg",
                                              "wrist"};
  return names.count(name) != 0;
}

double Pose::angle(const std::string& joint) const {
  const auto found = degrees.find(joint);
  return found == degrees.end() ? 0.0 : found->second;
}

bool Pose::neutral() const {
  for (const auto& [joint, value] : degrees)
    if (value != 0.0) return false;
  return true;
}

const std::vector<JointRange>& pose_joints() {
  static const std::vector<JointRange> joints = {
      {"neck", -40.0, 60.0},   {"shoulder_l", -60.0, 150.0}, {"shoulder_r", -60.0, 150.0},
      {"elbow_l", 0.0, 150.0}, {"elbow_r", 0.0, 150.0},      {"hip_l", -30.0, 130.0},
      {"hip_r", -30.0, 130.0}, {"knee_l", 0.0, 150.0},       {"knee_r", 0.0, 150.0}};
  return joints;
}

void check_pose(const Pose& pose) {
  for (const auto& [joint, value] : pose.degrees) {
    const auto& joints = pose_joints();
    const auto range = std::find_if(joints.begin(), joints.end(),
                                    [&](const JointRange& r) { return r.name == joint; });
    if (range == joints.end()) {
      std::string names;
      for (const JointRange& r : joints)
        names += (names.empty() ? "" : ", ") + r.name;
      throw InputError("pose: unknown joint '" + joint + "' (joints: " + names + ")");
    }
    if (!(value >= range->least && value <= range->most)) {
      std::ostringstream message;
      message << "pose: " << joint << " = " << value << " degrees is outside its range ["
              << range->least << ", " << range->most << "]";
      throw InputError(message.str());
    }
  }
}

Pose parse_pose(const std::string& text) {
  Pose pose;
  std::istringstream items(text);
  std::string item;
  while (std::getline(items, item, ',')) {
    const auto colon = item.find(':');
    double value = 0.0;
    std::size_t used = 0;
    try {
      if (colon != std::string::npos) value = std::stod(item.substr(colon + 1), &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (colon == std::string::npos || used == 0 || colon + 1 + used != item.size() ||
        !std::isfinite(value))
      throw InputError("pose: '" + item + "' is not JOINT:DEGREES (e.g. knee_l:90)");
    if (!pose.degrees.emplace(item.substr(0, colon), value).second)
      throw InputError("pose: joint '" + item.substr(0, colon) + "' is given twice");
  }
  check_pose(pose);
  return pose;
}

struct MannequinModel::Parts {
  explicit Parts(Design body)
      : design(std::move(body)), slope_bound(ellipsoid_slope_bound(design)) {}
  Design design;
  // Asked for at every contact query's cache check: computed once.
  double slope_bound;
};

MannequinModel::MannequinModel()
    : sized_(std::make_shared<Parts>(default_design())), posed_(sized_) {}

MannequinModel::MannequinModel(const Measurements& requested, const Pose& pose) : MannequinModel() {
  requested_ = default_measurements();
  achieved_ = requested_;
  bool is_default = true;
  for (const auto& [name, value] : requested) {
    if (!default_measurements().count(name)) {
      throw InputError("measurement '" + name + "' is not one the mannequin is sized to");
    }
    requested_[name] = value;
    is_default = is_default && value == default_measurements().at(name);
  }
  // Without a height the head keeps its size on top of the neck's base.
  if (!requested.count("height"))
    requested_["height"] = requested_.at("waistToFloor") + requested_.at("hpsToWaistBack") +
                           1e3 * (default_crown - default_hps);
  check_plausible(requested_);
  if (!is_default) {
    sized_ = std::make_shared<Parts>(sized_design(requested_));
    const VerticalMap map = vertical_map(requested_, crotch_height(default_design()));
    achieved_ = requested_;
    for (const auto& [name, value] : measure_girths(sized_->design, requested_, map))
      achieved_[name] = value;
    achieved_["inseam"] = 1e3 * crotch_height(sized_->design);
  }
  posed_ = sized_;
  *this = posed(pose);
}

MannequinModel MannequinModel::posed(const Pose& pose) const {
  check_pose(pose);
  MannequinModel model = *this;
  model.pose_ = pose;
  model.posed_ =
      pose.neutral() ? sized_ : std::make_shared<Parts>(posed_design(sized_->design, pose));
  return model;
}

double MannequinModel::field(const Eigen::Vector3d& p) const {
  return body_field<Derivatives::none>(posed_->design, p).value;
}

MannequinFieldValue MannequinModel::field_gradient(const Eigen::Vector3d& p) const {
  return body_field<Derivatives::gradient>(posed_->design, p);
}

MannequinFieldValue MannequinModel::field_derivatives(const Eigen::Vector3d& p) const {
  return body_field<Derivatives::hessian>(posed_->design, p);
}

double MannequinModel::slope_bound() const {
  return posed_->slope_bound;
}

Mannequin MannequinModel::generate() const {
  const Design& d = posed_->design;
  const auto [lower, upper] = polygonising_box(d);
  Mannequin mannequin;
  mannequin.mesh = marching_tetrahedra(d, lower, upper, {});
  relax(d, mannequin.mesh, 4);
  // Smoothing can fold the thin hands' triangles over one another: polygonised
  // again with the nodes near the crossing faces kept from zero. The mesh
  // elsewhere is the same, bit for bit (smoothing reaches four rings).
  const auto crossing = self_intersecting_faces(mannequin.mesh);
  if (!crossing.empty()) {
    std::vector<Eigen::Vector3d> folds;
    for (const auto& [a, b] : crossing)
      for (std::size_t f : {a, b})
        for (int v : mannequin.mesh.faces[f])
          folds.push_back(mannequin.mesh.vertices[static_cast<std::size_t>(v)]);
    mannequin.mesh = marching_tetrahedra(d, lower, upper, folds);
    relax(d, mannequin.mesh, 4);
    if (!self_intersecting_faces(mannequin.mesh).empty())
      throw std::logic_error("mannequin: the polygonised surface crosses itself");
  }
  mannequin.skeleton = sartor::skeleton(d);
  return mannequin;
}

std::vector<Bone> MannequinModel::skeleton() const {
  return sartor::skeleton(posed_->design);
}

std::vector<BoneMotion> MannequinModel::bone_motions() const {
  std::vector<BoneMotion> motions;
  for (const Bone& bone : skeleton()) {
    const auto moved = posed_->design.bone_motions.find(bone.name);
    if (moved == posed_->design.bone_motions.end()) {
      motions.push_back({bone.name, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()});
    } else {
      motions.push_back({bone.name, moved->second.rotation, moved->second.shift});
    }
  }
  return motions;
}

bool MannequinModel::is_default() const {
  return posed_->design.is_default;
}

const Pose& MannequinModel::pose() const {
  return pose_;
}

// The default model leaves them empty: measuring it takes a tenth of a second.
const Measurements& MannequinModel::requested() const {
  return requested_.empty() ? default_measurements() : requested_;
}

const Measurements& MannequinModel::achieved() const {
  return achieved_.empty() ? default_measurements() : achieved_;
}

Mannequin generate_mannequin() {
  return MannequinModel().generate();
}

double mannequin_field(const Eigen::Vector3d& p) {
  return body_field<Derivatives::none>(default_design(), p).value;
}

MannequinFieldValue mannequin_field_derivatives(const Eigen::Vector3d& p) {
  return body_field<Derivatives::hessian>(default_design(), p);
}

const Bone& Mannequin::bone(const std::string& name) const {
  for (const Bone& b : skeleton)
    if (b.name == name) return b;
  std::string names;
  for (const Bone& b : skeleton)
    names += (names.empty() ? "" : ", ") + b.name;
  throw InputError("the mannequin has no bone '" + name + "' (bones: " + names + ")");
}

const Mannequin& default_mannequin() {
  static const Mannequin mannequin = generate_mannequin();
  return mannequin;
}

} // namespace sartor
