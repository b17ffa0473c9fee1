// Wrapping by marks (garment/wrap.hpp): the sample sleeve on a capsule arm.
// The references are the arm's closed-form geometry, computed here.

#include "contact/analytic_shapes.hpp"
#include "garment/wrap.hpp"

#include <Eigen/LU>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace {

using namespace sartor;
using namespace sartor::garment;

const std::string cases = SARTOR_WRAP_CASES_DIR;
// The arm of cases/wrap/sleeve_marks.json.
const Eigen::Vector3d arm_a(0.0, 0.0, 1.2), arm_b(0.6, 0.0, 1.2);
constexpr double arm_radius = 0.05;

// The nearest point of the arm's axis segment.
Eigen::Vector3d on_axis(const Eigen::Vector3d& p) {
  const Eigen::Vector3d axis = arm_b - arm_a;
  const double t = std::clamp((p - arm_a).dot(axis) / axis.squaredNorm(), 0.0, 1.0);
  return arm_a + t * axis;
}

double cross2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

double arm_distance(const Eigen::Vector3d& p) {
  return (p - on_axis(p)).norm() - arm_radius;
}

// The 3D point of the wrapped mesh at panel point `q` (panel 0, its grain
// making material (u, v) = (y, -x)), by barycentric interpolation.
Eigen::Vector3d cloth_point(const TriangleMesh& mesh, const Eigen::Vector2d& q) {
  const Eigen::Vector2d uv(q.y(), -q.x());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const auto& c = mesh.material_uv[t];
    Eigen::Matrix2d edges;
    edges << c[1] - c[0], c[2] - c[0];
    const Eigen::Vector2d w = edges.inverse() * (uv - c[0]);
    if (w.minCoeff() < -1e-9 || w.sum() > 1.0 + 1e-9) continue;
    const auto& v = mesh.triangles[t];
    return (1.0 - w.sum()) * mesh.positions[std::size_t(v[0])] +
           w.x() * mesh.positions[std::size_t(v[1])] + w.y() * mesh.positions[std::size_t(v[2])];
  }
  ADD_FAILURE() << "panel point " << q.transpose() << " not in the mesh";
  return Eigen::Vector3d::Zero();
}

struct WrappedSleeve {
  Pattern pattern;
  TriangleMesh sewn;
  WrapResult result;
};

const WrappedSleeve& wrapped_sleeve() {
  static const WrappedSleeve sleeve = [] {
    WrappedSleeve s;
    std::vector<ClothMark> pattern_marks;
    s.pattern = read_pattern_with_marks(cases + "/sleeve.json", pattern_marks);
    WrapMarks marks = read_marks(cases + "/sleeve_marks.json", s.pattern, pattern_marks);
    const contact::Capsule arm(arm_a, arm_b, arm_radius);
    for (MarkPair& pair : marks.pairs)
      pair.body = body_surface_path(arm, pair.body, 0.01);
    s.sewn = sew_panels(s.pattern, marks.seams, 0.04, 25.0);
    s.result = wrap(s.sewn, s.pattern, marks.pairs, arm, WrapOptions{});
    return s;
  }();
  return sleeve;
}

TEST(Wrap, SleeveIsSewnIntoATube) {
  const WrappedSleeve& sleeve = wrapped_sleeve();
  // A tube has two boundary loops (cuff and top), no seam edge left open:
  // every boundary vertex lies on y = 0 or y = 0.36 of the panel.
  for (int v : boundary_vertices(sleeve.sewn)) {
    bool on_end = false;
    for (std::size_t t = 0; t < sleeve.sewn.triangle_count(); ++t)
      for (std::size_t c = 0; c < 3; ++c)
        if (sleeve.sewn.triangles[t][c] == v) {
          const double along = sleeve.sewn.material_uv[t][c].x();
          on_end = on_end || std::abs(along) < 1e-9 || std::abs(along - 0.36) < 1e-9;
        }
    EXPECT_TRUE(on_end) << "vertex " << v << " is on an open boundary";
  }
}

TEST(Wrap, SleeveMarksLandOnTheArmMarks) {
  const WrappedSleeve& sleeve = wrapped_sleeve();
  // Along each cloth mark, the arm point under the cloth is compared with
  // the body mark's point at the same fraction of its length.
  struct Line {
    double panel_x, body_y;
  };
  double worst = 0.0;
  for (const Line line : {Line{0.3, -arm_radius}, Line{0.1, arm_radius}}) {
    for (int k = 0; k <= 10; ++k) {
      const double fraction = k / 10.0;
      const Eigen::Vector3d cloth =
          cloth_point(sleeve.result.mesh, {line.panel_x, 0.04 + 0.28 * fraction});
      const Eigen::Vector3d axis = on_axis(cloth);
      const Eigen::Vector3d under = axis + arm_radius * (cloth - axis).normalized();
      const Eigen::Vector3d target(0.1 + 0.28 * fraction, line.body_y, 1.2);
      worst = std::max(worst, (under - target).norm());
    }
  }
  // Bound: half an edge length (0.04 m) of the mesh.
  EXPECT_LT(worst, 0.02);
  RecordProperty("mark_mismatch_max_m", std::to_string(worst));
}

TEST(Wrap, NoSleeveVertexInsideTheArm) {
  const WrappedSleeve& sleeve = wrapped_sleeve();
  double closest = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& p : sleeve.result.mesh.positions)
    closest = std::min(closest, arm_distance(p));
  EXPECT_GE(closest, 0.0);
  // Every vertex is kept at the 12 mm offset: well above the half of it.
  EXPECT_GT(closest, 0.006);
}

TEST(Wrap, SleeveEdgesStayNearTheirRestLengths) {
  const WrappedSleeve& sleeve = wrapped_sleeve();
  double low = std::numeric_limits<double>::infinity(), high = 0.0;
  const TriangleMesh& mesh = sleeve.result.mesh;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    for (std::size_t c = 0; c < 3; ++c) {
      const double rest = (mesh.material_uv[t][c] - mesh.material_uv[t][(c + 1) % 3]).norm();
      const double now = (mesh.positions[std::size_t(mesh.triangles[t][c])] -
                          mesh.positions[std::size_t(mesh.triangles[t][(c + 1) % 3])])
                             .norm();
      low = std::min(low, now / rest);
      high = std::max(high, now / rest);
    }
  EXPECT_GT(low, 0.8);
  EXPECT_LT(high, 1.35);
}

TEST(Wrap, EveryVertexIsMappedOnce) {
  const WrappedSleeve& sleeve = wrapped_sleeve();
  std::vector<int> order = sleeve.result.growth_order;
  std::sort(order.begin(), order.end());
  EXPECT_EQ(std::unique(order.begin(), order.end()), order.end());
  EXPECT_EQ(order.size(), sleeve.sewn.vertex_count());
}

// Rewrapping with a pushpin: new marks on the cuff half, 2 cm further
// along the arm; a pin at the far end of the sleeve. Everything at least as
// far from the new marks as the pin stays exactly where it was.
TEST(Wrap, RewrapKeepsTheClothBeyondThePin) {
  const WrappedSleeve& sleeve = wrapped_sleeve();
  const contact::Capsule arm(arm_a, arm_b, arm_radius);
  std::vector<MarkPair> pairs(2);
  for (std::size_t k = 0; k < 2; ++k) {
    const double panel_x = k == 0 ? 0.3 : 0.1, side = k == 0 ? -arm_radius : arm_radius;
    pairs[k].id = k == 0 ? "front" : "back";
    pairs[k].cloth.points = {{panel_x, 0.04}, {panel_x, 0.12}};
    pairs[k].body = body_surface_path(arm, {{0.12, side, 1.2}, {0.20, side, 1.2}}, 0.01);
  }
  // The pin: the vertex nearest panel point (0.3, 0.28), above the front mark.
  Rewrap rewrap{sleeve.result.mesh.positions, {}};
  const Eigen::Vector3d pin_at = cloth_point(sleeve.result.mesh, {0.3, 0.28});
  int pin = 0;
  for (std::size_t v = 0; v < rewrap.positions.size(); ++v)
    if ((rewrap.positions[v] - pin_at).norm() <
        (rewrap.positions[std::size_t(pin)] - pin_at).norm())
      pin = int(v);
  rewrap.pins = {pin};
  const WrapResult again = wrap(sleeve.sewn, sleeve.pattern, pairs, arm, WrapOptions{}, &rewrap);
  EXPECT_GT(again.kept_vertices, 10);
  EXPECT_LT(again.kept_vertices, int(rewrap.positions.size()) / 2);
  EXPECT_LT((again.mesh.positions[std::size_t(pin)] - rewrap.positions[std::size_t(pin)]).norm(),
            1e-12);
  int unmoved = 0;
  for (std::size_t v = 0; v < rewrap.positions.size(); ++v)
    unmoved += (again.mesh.positions[v] - rewrap.positions[v]).norm() < 1e-12 ? 1 : 0;
  EXPECT_GE(unmoved, again.kept_vertices);
  // The cuff moved: its marks now lie on the new body marks.
  for (const double panel_x : {0.3, 0.1}) {
    const Eigen::Vector3d cloth = cloth_point(again.mesh, {panel_x, 0.08});
    EXPECT_NEAR(on_axis(cloth).x(), 0.16, 0.01);
  }
  double closest = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& p : again.mesh.positions)
    closest = std::min(closest, arm_distance(p));
  EXPECT_GE(closest, 0.0);
}

// A finger (radius 15 mm) in a coarse tube (6 cm edges): the chords between
// vertices 12 mm above it cut into it until the sqrt(3) subdivision splits
// them. Edges are judged here by their midpoints' distance to the finger.
TEST(EdgeSweep, MeetsTheSegmentsItSweepsAcrossOnly) {
  // The edge from (-1, 0, 1) to (1, 0, 1) moved straight down to z = z1
  // sweeps the rectangle |x| <= 1, y = 0, z1 <= z <= 1.
  const Eigen::Vector3d a0(-1.0, 0.0, 1.0), b0(1.0, 0.0, 1.0), down(0.0, 0.0, 1.0);
  const Eigen::Vector3d across_start(0.5, -1.0, 0.0), across_end(0.5, 1.0, 0.0);
  EXPECT_TRUE(
      edge_sweep_meets_segment(a0, b0, a0 - 2.0 * down, b0 - 2.0 * down, across_start, across_end));
  EXPECT_FALSE(
      edge_sweep_meets_segment(a0, b0, a0 - 0.5 * down, b0 - 0.5 * down, across_start, across_end));
  // Beyond the edge's ends, and a segment ending before the swept plane.
  const Eigen::Vector3d beyond(1.5, 0.0, 0.0);
  EXPECT_FALSE(edge_sweep_meets_segment(a0, b0, a0 - 2.0 * down, b0 - 2.0 * down,
                                        beyond - Eigen::Vector3d::UnitY(),
                                        beyond + Eigen::Vector3d::UnitY()));
  EXPECT_FALSE(edge_sweep_meets_segment(a0, b0, a0 - 2.0 * down, b0 - 2.0 * down, across_start,
                                        Eigen::Vector3d(0.5, -0.1, 0.0)));
  // One end held: the triangle a0, b0, a1 is swept; (-0.5, 0, 0.5) is in it,
  // (0.5, 0, 0.5) is not.
  for (const double x : {-0.5, 0.5}) {
    const Eigen::Vector3d through(x, 0.0, 0.5);
    EXPECT_EQ(edge_sweep_meets_segment(a0, b0, a0 - down, b0, through - Eigen::Vector3d::UnitY(),
                                       through + Eigen::Vector3d::UnitY()),
              x < 0.0);
  }
}

// How many times the sleeve's ring at panel height `along` winds around
// the arm's axis (seen along the axis).
int sleeve_winding(const TriangleMesh& mesh, double along) {
  double turned = 0.0;
  constexpr int samples = 80;
  Eigen::Vector2d previous;
  for (int k = 0; k <= samples; ++k) {
    // Panel x = 0 and 0.4 are sewn together: the ring closes.
    const Eigen::Vector3d p = cloth_point(mesh, {0.4 * k / samples, along});
    const Eigen::Vector2d around(p.y() - arm_a.y(), p.z() - arm_a.z());
    if (k > 0) turned += std::atan2(cross2d(previous, around), previous.dot(around));
    previous = around;
  }
  return int(std::lround(turned / (2.0 * M_PI)));
}

TEST(Bones, HoldTheSleeveOnTheArmThroughLongFalls) {
  const WrappedSleeve& sleeve = wrapped_sleeve();
  ASSERT_EQ(std::abs(sleeve_winding(sleeve.result.mesh, 0.18)), 1);
  // Falls of 0.15 m a step carry the sleeve's top past the 0.1 m thick arm:
  // kept above the arm, its vertices land below it.
  RelaxParameters falls;
  falls.gravity_step = 0.15;
  falls.max_step = 0.15;
  const contact::Capsule arm(arm_a, arm_b, arm_radius);
  ClothOnBody loose(sleeve.result.mesh, arm, falls), held(sleeve.result.mesh, arm, falls);
  held.bones = {{"axis", "", arm_a, arm_b, arm_radius, arm_radius}};
  loose.relax(10);
  held.relax(10);
  EXPECT_EQ(loose.bone_holds(), 0);
  EXPECT_EQ(sleeve_winding(loose.mesh(), 0.18), 0);
  EXPECT_GT(held.bone_holds(), 0);
  for (const double along : {0.06, 0.18, 0.3})
    EXPECT_EQ(std::abs(sleeve_winding(held.mesh(), along)), 1) << "ring at " << along;
}

// A tube of one panel wrapped on a finger of 15 mm radius: its 6 cm edges
// cut into it.
struct FingerTube {
  Eigen::Vector3d tip{0.0, 0.0, 1.0}, knuckle{0.3, 0.0, 1.0};
  double radius = 0.015;
  contact::Capsule finger{tip, knuckle, radius};
  Pattern pattern;
  TriangleMesh sewn;
  std::vector<MarkPair> pairs;

  FingerTube() {
    pattern = parse_pattern(R"({"format": "sartor-pattern", "version": 1,
      "name": "finger tube", "units": "m", "panels": [{"id": "tube", "fabric": "cotton_twill",
      "tag": {"cylinder": "arm_l", "side": "front", "layer": 0}, "grain": {"angle_deg": 90},
      "outline": [
        {"id": "t_end", "type": "straight", "points": [[0.0, 0.0], [0.17, 0.0]]},
        {"id": "t_right", "type": "straight", "points": [[0.17, 0.0], [0.17, 0.2]]},
        {"id": "t_top", "type": "straight", "points": [[0.17, 0.2], [0.0, 0.2]]},
        {"id": "t_left", "type": "straight", "points": [[0.0, 0.2], [0.0, 0.0]]}]}]})",
                            "finger tube");
    sewn = sew_panels(pattern, {{"t_right", "t_left", true, "test seam"}}, 0.06, 25.0);
    pairs.resize(2);
    for (std::size_t k = 0; k < 2; ++k) {
      const double panel_x = k == 0 ? 0.1275 : 0.0425, side = k == 0 ? -radius : radius;
      pairs[k].id = k == 0 ? "front" : "back";
      pairs[k].cloth.points = {{panel_x, 0.02}, {panel_x, 0.18}};
      pairs[k].body = body_surface_path(finger, {{0.07, side, 1.0}, {0.23, side, 1.0}}, 0.005);
    }
  }
  double distance(const Eigen::Vector3d& p) const {
    const double t =
        std::clamp((p - tip).dot(knuckle - tip) / (knuckle - tip).squaredNorm(), 0.0, 1.0);
    return (p - tip - t * (knuckle - tip)).norm() - radius;
  }
  // Edges whose midpoints lie inside the finger.
  int cutting_edges(const TriangleMesh& mesh) const {
    int cutting = 0;
    for (const auto& edge : rest_edges(mesh).edges)
      cutting += distance(0.5 * (mesh.positions[std::size_t(edge[0])] +
                                 mesh.positions[std::size_t(edge[1])])) < 0.0;
    return cutting;
  }
};

TEST(Wrap, SubdivisionSplitsEdgesThatCutIntoAFinger) {
  const FingerTube tube;
  WrapOptions options;
  const WrapResult plain = wrap(tube.sewn, tube.pattern, tube.pairs, tube.finger, options);
  options.subdivide = true;
  const WrapResult refined = wrap(tube.sewn, tube.pattern, tube.pairs, tube.finger, options);
  const int before = tube.cutting_edges(plain.mesh), after = tube.cutting_edges(refined.mesh);
  EXPECT_GT(before, 0);
  EXPECT_GT(refined.split_edges, 0);
  EXPECT_LT(after, before);
  EXPECT_EQ(refined.mesh.vertex_count(),
            tube.sewn.vertex_count() + 2 * std::size_t(refined.split_edges));
  EXPECT_EQ(refined.mesh.triangle_count(),
            tube.sewn.triangle_count() + 4 * std::size_t(refined.split_edges));
  double closest = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& p : refined.mesh.positions)
    closest = std::min(closest, tube.distance(p));
  EXPECT_GE(closest, 0.0);
  RecordProperty("cutting_edges_before", before);
  RecordProperty("cutting_edges_after", after);
  RecordProperty("splits", std::to_string(refined.splits));
  RecordProperty("merges", std::to_string(refined.merges));
}

TEST(Wrap, SplitEdgesMergeBackWhenTheClothLeavesTheFinger) {
  const FingerTube tube;
  const WrapResult plain = wrap(tube.sewn, tube.pattern, tube.pairs, tube.finger, WrapOptions{});
  ClothOnBody cloth(plain.mesh, tube.finger, RelaxParameters{});
  AdaptiveSubdivision subdivision(plain.mesh);
  ASSERT_TRUE(subdivision.update(cloth));
  const int split = subdivision.split_edges();
  EXPECT_GT(split, 0);
  EXPECT_EQ(cloth.mesh().vertex_count(), plain.mesh.vertex_count() + 2 * std::size_t(split));
  EXPECT_LT(tube.cutting_edges(cloth.mesh()), tube.cutting_edges(plain.mesh));
  // Unchanged positions: nothing more to split or merge.
  EXPECT_FALSE(subdivision.update(cloth));
  // Lifted 0.3 m off the finger, no edge comes near cutting: all merge back
  // and the base mesh returns, its vertices where they were lifted to.
  const Eigen::Vector3d lift(0.0, 0.0, 0.3);
  for (Eigen::Vector3d& p : cloth.positions())
    p += lift;
  ASSERT_TRUE(subdivision.update(cloth));
  EXPECT_EQ(subdivision.split_edges(), 0);
  EXPECT_EQ(subdivision.merges(), split);
  ASSERT_EQ(cloth.mesh().vertex_count(), plain.mesh.vertex_count());
  EXPECT_EQ(cloth.mesh().triangles, plain.mesh.triangles);
  for (std::size_t v = 0; v < plain.mesh.vertex_count(); ++v)
    EXPECT_EQ(cloth.mesh().positions[v], plain.mesh.positions[v] + lift);
}

} // namespace
