#include "mesh/mannequin.hpp"

#include "common/error.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace sartor {

namespace {

// --- primitives: signed distances with their gradients and, when `curved`,
// their Hessians (exact for the capsule, first-order for the ellipsoid),
// negative inside. Polygonising the body needs no Hessians, and computing
// them made its generation three times as long. ------------------------------

using FieldValue = MannequinFieldValue;

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

  template <bool curved>
  FieldValue distance(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d pa = p - a;
    const double y = pa.dot(unit);
    const Eigen::Vector3d radial = pa - y * unit;
    const double x = radial.norm();
    const double along_side = c * y - s * x;
    const auto sphere = [&p](const Eigen::Vector3d& centre, double r) {
      const Eigen::Vector3d d = p - centre;
      const double norm = d.norm();
      if (norm == 0.0) return FieldValue{-r, Eigen::Vector3d::UnitZ(), Eigen::Matrix3d::Zero()};
      const Eigen::Vector3d n = d / norm;
      if constexpr (!curved) return FieldValue{norm - r, n, Eigen::Matrix3d::Zero()};
      return FieldValue{norm - r, n, across_projector(n) / norm};
    };
    if (along_side < 0.0) return sphere(a, ra);
    if (along_side > c * length) return sphere(b, rb);
    const Eigen::Vector3d across = x > 0.0 ? Eigen::Vector3d(radial / x) : unit.unitOrthogonal();
    const Eigen::Matrix3d curvature =
        curved && x > 0.0
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

  template <bool curved>
  FieldValue distance(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d q = frame * (p - centre);
    const Eigen::Vector3d r2 = radii.cwiseProduct(radii);
    const Eigen::Vector3d q_r2 = q.cwiseQuotient(r2);
    const Eigen::Vector3d q_r4 = q_r2.cwiseQuotient(r2);
    const double k0 = std::sqrt(q.dot(q_r2));
    const double k1 = q_r2.norm();
    if (k1 == 0.0) return {-radii.minCoeff(), Eigen::Vector3d::UnitZ(), Eigen::Matrix3d::Zero()};
    const Eigen::Vector3d dk0 = q_r2 / k0;
    const Eigen::Vector3d dk1 = q_r4 / k1;
    // value g(k0) / k1 with g = k0 (k0 - 1)
    const double g = k0 * (k0 - 1.0);
    const double dg = 2.0 * k0 - 1.0;
    const Eigen::Vector3d local = (dg * k1 * dk0 - g * dk1) / (k1 * k1);
    if constexpr (!curved) return {g / k1, frame.transpose() * local, Eigen::Matrix3d::Zero()};
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
template <bool curved>
FieldValue smooth_min(const FieldValue& a, const FieldValue& b, double k) {
  const double h = std::max(k - std::abs(a.value - b.value), 0.0) / k;
  const double weight_a = a.value < b.value ? 1.0 - 0.5 * h : 0.5 * h;
  FieldValue blend{std::min(a.value, b.value) - 0.25 * k * h * h,
                   weight_a * a.gradient + (1.0 - weight_a) * b.gradient, Eigen::Matrix3d::Zero()};
  if constexpr (curved) {
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

  Joints() {
    const Eigen::Vector3d down_arm(std::sin(arm_abduction), 0.0, -std::cos(arm_abduction));
    elbow = shoulder + 0.29 * down_arm;
    wrist = elbow + 0.25 * down_arm;
    // Short of the fingertips (wrist + 0.165): the hand is thin there, and
    // at 45 degrees the 2 cm grid leaves less of it than the joint needs.
    fingers = wrist + 0.12 * down_arm;
  }
};

Eigen::Vector3d mirrored(Eigen::Vector3d p) {
  p.x() = -p.x();
  return p;
}

struct Limbs {
  TaperedCapsule upper_arm;
  TaperedCapsule forearm;
  Ellipsoid hand;
  TaperedCapsule thigh;
  TaperedCapsule shin;
  Ellipsoid calf;
  Ellipsoid foot;
  Ellipsoid buttock;
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
          {{0.065, 0.045, 0.9}, {0.085, 0.075, 0.1}}};
}

Limbs mirrored(const Limbs& left) {
  Limbs right = left;
  for (TaperedCapsule* c : {&right.upper_arm, &right.forearm, &right.thigh, &right.shin})
    *c = TaperedCapsule(mirrored(c->a), mirrored(c->b), c->ra, c->rb);
  for (Ellipsoid* e : {&right.hand, &right.calf, &right.foot, &right.buttock}) {
    e->centre = mirrored(e->centre);
    e->frame.col(0) = -e->frame.col(0);
  }
  return right;
}

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
};

const Design& design() {
  static const Design d;
  return d;
}

template <bool curved>
FieldValue arm_field(const Limbs& l, const Eigen::Vector3d& p) {
  const FieldValue arm =
      smooth_min<curved>(l.upper_arm.distance<curved>(p), l.forearm.distance<curved>(p), 0.02);
  return smooth_min<curved>(arm, l.hand.distance<curved>(p), 0.02);
}

// Flat soles: the foot is cut by the floor z = 0.
template <bool curved>
FieldValue leg_field(const Limbs& l, const Eigen::Vector3d& p) {
  const FieldValue leg =
      smooth_min<curved>(l.thigh.distance<curved>(p), l.shin.distance<curved>(p), 0.03);
  const FieldValue calf = smooth_min<curved>(leg, l.calf.distance<curved>(p), 0.03);
  const FieldValue floor{-p.z(), -Eigen::Vector3d::UnitZ(), Eigen::Matrix3d::Zero()};
  return smooth_min<curved>(calf, max(l.foot.distance<curved>(p), floor), 0.03);
}

template <bool curved>
FieldValue body_field(const Eigen::Vector3d& p) {
  const Design& d = design();
  FieldValue trunk =
      smooth_min<curved>(d.chest.distance<curved>(p), d.waist.distance<curved>(p), 0.1);
  trunk = smooth_min<curved>(trunk, d.hips.distance<curved>(p), 0.1);
  trunk = smooth_min<curved>(trunk, d.shoulders.distance<curved>(p), 0.06);
  trunk = smooth_min<curved>(trunk, d.left.buttock.distance<curved>(p), 0.04);
  trunk = smooth_min<curved>(trunk, d.right.buttock.distance<curved>(p), 0.04);
  FieldValue head = smooth_min<curved>(d.head.distance<curved>(p), d.jaw.distance<curved>(p), 0.04);
  head = smooth_min<curved>(head, d.nose.distance<curved>(p), 0.015);
  FieldValue body = smooth_min<curved>(trunk, d.neck.distance<curved>(p), 0.04);
  body = smooth_min<curved>(body, head, 0.03);
  body = smooth_min<curved>(body, arm_field<curved>(d.left, p), 0.03);
  body = smooth_min<curved>(body, arm_field<curved>(d.right, p), 0.03);
  body = smooth_min<curved>(body, leg_field<curved>(d.left, p), 0.04);
  return smooth_min<curved>(body, leg_field<curved>(d.right, p), 0.04);
}

// Newton steps along the gradient onto the zero level set.
Eigen::Vector3d project_to_surface(Eigen::Vector3d p) {
  for (int iteration = 0; iteration < 3; ++iteration) {
    const FieldValue f = body_field<false>(p);
    const double g2 = f.gradient.squaredNorm();
    if (std::abs(f.value) < 1e-10 || g2 < 1e-12) break;
    p -= (f.value / g2) * f.gradient;
  }
  return p;
}

// --- marching tetrahedra -----------------------------------------------------

constexpr double grid_spacing = 0.02; // m; sets the triangle count (about 36k)

// The zero set of the piecewise-linear interpolant of the field on the
// Freudenthal subdivision of a regular grid (six tetrahedra per cube around
// its main diagonal; neighbouring cubes split their shared faces alike). With
// no node value exactly zero and the field positive on the grid's boundary,
// that set is a closed 2-manifold; each crossing vertex is shared by all the
// tetrahedra around its grid edge. Triangles are wound so that their normal
// points from the negative (inside) corners to the positive ones.
BodyMesh marching_tetrahedra() {
  const Eigen::Vector3d lower(-0.74, -0.24, -0.02); // fingertips at |x| = 0.69
  const Eigen::Vector3d upper(0.74, 0.2, 1.78);
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
        const double f = body_field<false>(position(i, j, k)).value;
        value[static_cast<std::size_t>(node(i, j, k))] = f == 0.0 ? 1e-12 : f;
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
void relax(BodyMesh& mesh, int sweeps) {
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
      const Eigen::Vector3d normal = body_field<false>(p).gradient.normalized();
      Eigen::Vector3d move = 0.5 * (centre - p);
      move -= move.dot(normal) * normal;
      next[v] = project_to_surface(p + move);
    }
    mesh.vertices.swap(next);
  }
}

Bone bone(std::string name, std::string parent, const Eigen::Vector3d& start,
          const Eigen::Vector3d& end, double start_radius, double end_radius) {
  return {std::move(name), std::move(parent), start, end, start_radius, end_radius};
}

std::vector<Bone> skeleton() {
  const Design& d = design();
  const Joints& j = d.joints;
  std::vector<Bone> bones = {
      bone("pelvis", "", j.pelvis, j.lumbar, d.hips.radii.x(), d.waist.radii.x()),
      bone("torso", "pelvis", j.lumbar, j.neck_base, d.waist.radii.x(), d.chest.radii.x()),
      bone("neck", "torso", j.neck_base, j.skull_base, d.neck.ra, d.neck.rb),
      bone("head", "neck", j.skull_base, j.crown, d.head.radii.y(), d.head.radii.y()),
  };
  for (const auto& [side, limbs, sign] : {std::tuple{std::string("_l"), &d.left, 1.0},
                                          std::tuple{std::string("_r"), &d.right, -1.0}}) {
    const auto place = [sign = sign](Eigen::Vector3d p) {
      p.x() *= sign;
      return p;
    };
    const Limbs& l = *limbs;
    bones.push_back(bone("clavicle" + side, "torso", j.neck_base, place(j.shoulder), d.shoulders.ra,
                         d.shoulders.rb));
    bones.push_back(bone("upper_arm" + side, "clavicle" + side, place(j.shoulder), place(j.elbow),
                         l.upper_arm.ra, l.upper_arm.rb));
    bones.push_back(bone("forearm" + side, "upper_arm" + side, place(j.elbow), place(j.wrist),
                         l.forearm.ra, l.forearm.rb));
    bones.push_back(bone("hand" + side, "forearm" + side, place(j.wrist), place(j.fingers),
                         l.hand.radii.y(), l.hand.radii.y()));
    bones.push_back(bone("hip" + side, "pelvis", j.pelvis, place(j.hip), l.thigh.ra, l.thigh.ra));
    bones.push_back(
        bone("thigh" + side, "hip" + side, place(j.hip), place(j.knee), l.thigh.ra, l.thigh.rb));
    bones.push_back(
        bone("shin" + side, "thigh" + side, place(j.knee), place(j.ankle), l.shin.ra, l.shin.rb));
    bones.push_back(bone("foot" + side, "shin" + side, place(j.ankle), place(j.toes),
                         l.foot.radii.x(), l.foot.radii.x()));
  }
  return bones;
}

} // namespace

Mannequin generate_mannequin() {
  Mannequin mannequin;
  mannequin.mesh = marching_tetrahedra();
  relax(mannequin.mesh, 4);
  mannequin.skeleton = skeleton();
  return mannequin;
}

double mannequin_field(const Eigen::Vector3d& p) {
  return body_field<false>(p).value;
}

MannequinFieldValue mannequin_field_derivatives(const Eigen::Vector3d& p) {
  return body_field<true>(p);
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
