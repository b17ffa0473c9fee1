// The mesh body's signed distance, normal and Hessian: against an analytic
// sphere (an icosphere mesh, within its discretisation error), against the
// exact answers of a cube at its faces, edges and vertices, and against
// finite differences of themselves; the smoothed distance across a concave
// crease (an L-shaped prism).

#include "common/error.hpp"
#include "contact/mesh_shape.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <map>
#include <random>

namespace {

using sartor::contact::Shape;
using sartor::contact::SurfaceQuery;

struct Mesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> faces;
};

// An icosahedron split `levels` times, vertices pushed onto the sphere.
Mesh icosphere(double radius, int levels) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  Mesh m;
  for (const auto& v : std::vector<Eigen::Vector3d>{{-1, t, 0},
                                                    {1, t, 0},
                                                    {-1, -t, 0},
                                                    {1, -t, 0},
                                                    {0, -1, t},
                                                    {0, 1, t},
                                                    {0, -1, -t},
                                                    {0, 1, -t},
                                                    {t, 0, -1},
                                                    {t, 0, 1},
                                                    {-t, 0, -1},
                                                    {-t, 0, 1}})
    m.vertices.push_back(v.normalized());
  m.faces = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
             {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
             {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> middle;
    const auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto [it, inserted] = middle.try_emplace(key, static_cast<int>(m.vertices.size()));
      if (inserted) {
        m.vertices.push_back(
            (m.vertices[static_cast<std::size_t>(a)] + m.vertices[static_cast<std::size_t>(b)])
                .normalized());
      }
      return it->second;
    };
    std::vector<std::array<int, 3>> finer;
    for (const auto& f : m.faces) {
      const int ab = midpoint(f[0], f[1]);
      const int bc = midpoint(f[1], f[2]);
      const int ca = midpoint(f[2], f[0]);
      finer.push_back({f[0], ab, ca});
      finer.push_back({f[1], bc, ab});
      finer.push_back({f[2], ca, bc});
      finer.push_back({ab, bc, ca});
    }
    m.faces = finer;
  }
  for (auto& v : m.vertices)
    v *= radius;
  return m;
}

Mesh unit_cube() {
  Mesh m;
  for (int k = 0; k < 8; ++k)
    m.vertices.emplace_back((k & 1) - 0.5, ((k >> 1) & 1) - 0.5, ((k >> 2) & 1) - 0.5);
  // Quads (counter-clockwise from outside) split into triangles.
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.faces.push_back({q[0], q[1], q[2]});
    m.faces.push_back({q[0], q[2], q[3]});
  }
  return m;
}

TEST(MeshShape, IcosphereMatchesTheSphereWithinItsDiscretisation) {
  const double radius = 0.3;
  const Mesh sphere = icosphere(radius, 4); // 5120 triangles
  const auto shape = sartor::contact::make_mesh_shape(sphere.vertices, sphere.faces, "icosphere");
  // The flat faces lie inside the sphere by at most the sagitta of the
  // longest edge's circumcircle.
  double longest = 0.0;
  for (const auto& f : sphere.faces)
    for (int k = 0; k < 3; ++k)
      longest = std::max(longest, (sphere.vertices[static_cast<std::size_t>(f[k])] -
                                   sphere.vertices[static_cast<std::size_t>(f[(k + 1) % 3])])
                                      .norm());
  const double circumradius = longest / std::sqrt(3.0);
  const double sagitta = radius - std::sqrt(radius * radius - circumradius * circumradius);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_real_distribution<double> shell(0.3 * radius, 2.0 * radius);
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3d direction =
        Eigen::Vector3d(unit(random), unit(random), unit(random)).normalized();
    const Eigen::Vector3d p = shell(random) * direction;
    const double exact = p.norm() - radius;
    const SurfaceQuery q = shape->query(p);
    ASSERT_NEAR(q.distance, exact, sagitta) << "at " << p.transpose();
    if (std::abs(exact) > sagitta) {
      ASSERT_EQ(q.distance > 0.0, exact > 0.0);
    }
    EXPECT_NEAR(q.closest.norm(), radius - 0.5 * sagitta, 0.5 * sagitta + 1e-15);
    EXPECT_NEAR((p - q.closest).norm(), std::abs(q.distance), 1e-12);
    EXPECT_NEAR(q.normal.norm(), 1.0, 1e-12);
    // The gradient of the distance to a polyhedron inscribed in the sphere
    // stays within an edge's angle of the radial direction.
    EXPECT_GT(q.normal.dot(direction), std::cos(longest / radius)) << "at " << p.transpose();
  }
}

TEST(MeshShape, CubeFacesEdgesAndVerticesAreExact) {
  const Mesh cube = unit_cube();
  const auto shape = sartor::contact::make_mesh_shape(cube.vertices, cube.faces, "cube");
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  {
    const SurfaceQuery face = shape->query({0.1, 0.2, 0.8});
    EXPECT_NEAR(face.distance, 0.3, 1e-15);
    EXPECT_TRUE(face.normal.isApprox(Eigen::Vector3d::UnitZ()));
    EXPECT_TRUE(face.hessian.isZero());
    const SurfaceQuery inside = shape->query({0.1, 0.2, 0.45});
    EXPECT_NEAR(inside.distance, -0.05, 1e-15);
    EXPECT_TRUE(inside.normal.isApprox(Eigen::Vector3d::UnitZ()));
  }
  {
    // Nearest to the edge x = y = 0.5 (direction z).
    const Eigen::Vector3d p(0.7, 0.8, 0.1);
    const SurfaceQuery edge = shape->query(p);
    const Eigen::Vector3d offset(0.2, 0.3, 0.0);
    const double d = offset.norm();
    const Eigen::Vector3d n = offset / d;
    EXPECT_NEAR(edge.distance, d, 1e-15);
    EXPECT_TRUE(edge.closest.isApprox(Eigen::Vector3d(0.5, 0.5, 0.1)));
    EXPECT_TRUE(edge.normal.isApprox(n));
    const Eigen::Vector3d e = Eigen::Vector3d::UnitZ();
    EXPECT_TRUE(edge.hessian.isApprox((I - e * e.transpose() - n * n.transpose()) / d, 1e-12));
  }
  {
    const Eigen::Vector3d p(0.6, -0.7, 0.9);
    const SurfaceQuery vertex = shape->query(p);
    const Eigen::Vector3d offset = p - Eigen::Vector3d(0.5, -0.5, 0.5);
    const double d = offset.norm();
    const Eigen::Vector3d n = offset / d;
    EXPECT_NEAR(vertex.distance, d, 1e-15);
    EXPECT_TRUE(vertex.normal.isApprox(n));
    EXPECT_TRUE(vertex.hessian.isApprox((I - n * n.transpose()) / d, 1e-12));
  }
  // Points just off an edge and a vertex, outside and inside: the
  // pseudo-normals give the right sign where a face normal would not.
  for (const double gap : {1e-9, 1e-6, 1e-3}) {
    EXPECT_GT(
        shape->query(Eigen::Vector3d(0.5, 0.5, 0.5) + gap * Eigen::Vector3d(1, 1, 1)).distance,
        0.0);
    EXPECT_LT(
        shape->query(Eigen::Vector3d(0.5, 0.5, 0.5) - gap * Eigen::Vector3d(1, 1, 1)).distance,
        0.0);
    EXPECT_GT(shape->query(Eigen::Vector3d(0.5 + gap, 0.5 + 2 * gap, 0.0)).distance, 0.0);
    EXPECT_LT(shape->query(Eigen::Vector3d(0.5 - gap, 0.5 - 2 * gap, 0.0)).distance, 0.0);
  }
}

// Central differences of distance -> normal and normal -> Hessian at random
// points. The Hessian is checked only where the nearest feature is the same
// at p +- h along every axis (the Hessian jumps where it changes).
void check_derivatives(const Shape& shape, const std::vector<Eigen::Vector3d>& points, int& curved,
                       int& flat) {
  const double h = 1e-6;
  for (const Eigen::Vector3d& p : points) {
    const SurfaceQuery q = shape.query(p);
    Eigen::Vector3d gradient;
    Eigen::Matrix3d hessian;
    bool same_feature = true;
    for (Eigen::Index k = 0; k < 3; ++k) {
      const Eigen::Vector3d step = h * Eigen::Vector3d::Unit(k);
      const SurfaceQuery plus = shape.query(p + step);
      const SurfaceQuery minus = shape.query(p - step);
      gradient[k] = (plus.distance - minus.distance) / (2 * h);
      hessian.col(k) = (plus.normal - minus.normal) / (2 * h);
      const double scale = 1.0 + q.hessian.norm();
      same_feature = same_feature && (plus.hessian - q.hessian).norm() < 1e-3 * scale &&
                     (minus.hessian - q.hessian).norm() < 1e-3 * scale;
    }
    ASSERT_LT((gradient - q.normal).norm(), 1e-6) << "at " << p.transpose();
    if (!same_feature) continue;
    ASSERT_LT((hessian - q.hessian).norm(), 1e-5 * (1.0 + q.hessian.norm()))
        << "at " << p.transpose() << "\nanalytic\n"
        << q.hessian << "\nfinite differences\n"
        << hessian;
    ASSERT_LT((q.hessian - q.hessian.transpose()).norm(), 1e-12);
    (q.hessian.isZero() ? flat : curved)++;
  }
}

TEST(MeshShape, DerivativesMatchFiniteDifferences) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (const auto& [mesh, name] :
       {std::pair{icosphere(0.3, 2), "icosphere"}, std::pair{unit_cube(), "cube"}}) {
    const auto shape = sartor::contact::make_mesh_shape(mesh.vertices, mesh.faces, name);
    std::vector<Eigen::Vector3d> points;
    for (int i = 0; i < 600; ++i)
      points.emplace_back(0.8 * unit(random), 0.8 * unit(random), 0.8 * unit(random));
    int curved = 0;
    int flat = 0;
    check_derivatives(*shape, points, curved, flat);
    // Both kinds of feature were exercised, inside and outside.
    EXPECT_GT(curved, 50) << name;
    EXPECT_GT(flat, 50) << name;
  }
}

// An L-shaped prism (the L of [0,2]x[0,1] and [0,1]x[0,2], z in [0,1]): its
// vertical edge at (1, 1) is concave, a crease of the exact distance.
Mesh l_prism() {
  const std::vector<Eigen::Vector2d> outline = {{0, 0}, {2, 0}, {2, 1}, {1, 1},
                                                {1, 2}, {0, 2}, {0, 1}}; // counter-clockwise
  const int n = int(outline.size());
  Mesh m;
  for (const double z : {0.0, 1.0})
    for (const auto& c : outline)
      m.vertices.emplace_back(c.x(), c.y(), z);
  const int cap[5][3] = {{0, 1, 2}, {0, 2, 3}, {0, 3, 6}, {6, 3, 4}, {6, 4, 5}};
  for (const auto& t : cap) {
    m.faces.push_back({t[0] + n, t[1] + n, t[2] + n}); // top, seen from +z
    m.faces.push_back({t[0], t[2], t[1]});             // bottom, reversed
  }
  for (int a = 0; a < n; ++a) {
    const int b = (a + 1) % n;
    m.faces.push_back({a, b, b + n});
    m.faces.push_back({a, b + n, a + n});
  }
  return m;
}

// Smoothed, the distance has no crease: its normal is continuous across the
// concave edge's bisector (exact: it jumps from one wall's normal to the
// other's), it stays within eps ln(triangles) below the exact distance, and
// far from other triangles it is the exact one.
TEST(MeshShape, SmoothedDistanceHasNoCreaseAndStaysNearTheExactOne) {
  const Mesh l = l_prism();
  const double eps = 0.01;
  const auto exact = sartor::contact::make_mesh_shape(l.vertices, l.faces, "L");
  const auto smooth = sartor::contact::make_mesh_shape(l.vertices, l.faces, "L", eps);
  const Eigen::Vector3d bisector(1.3, 1.3, 0.5), across(1e-7, -1e-7, 0.0);
  const double exact_jump =
      (exact->query(bisector + across).normal - exact->query(bisector - across).normal).norm();
  EXPECT_NEAR(exact_jump, std::sqrt(2.0), 1e-9);
  const double smooth_jump =
      (smooth->query(bisector + across).normal - smooth->query(bisector - across).normal).norm();
  // Continuous: it turns at the smoothed crease's curvature, about 1/(2 eps).
  EXPECT_LT(smooth_jump, (1.0 / eps) * (2.0 * across).norm());
  std::mt19937 random(5);
  std::uniform_real_distribution<double> coordinate(-0.4, 2.4);
  for (int i = 0; i < 300; ++i) {
    const Eigen::Vector3d p(coordinate(random), coordinate(random), 0.5 * coordinate(random));
    const double gap = exact->query(p).distance - smooth->query(p).distance;
    const double sign = exact->query(p).distance >= 0.0 ? 1.0 : -1.0;
    EXPECT_GE(sign * gap, -1e-12) << p.transpose();
    EXPECT_LE(sign * gap, eps * std::log(double(l.faces.size()))) << p.transpose();
  }
  // Over the middle of a wall, 0.05 from it, every other triangle is more
  // than 12 eps farther: the exact distance and normal.
  const Eigen::Vector3d over_wall(1.5, -0.05, 0.25);
  EXPECT_NEAR(smooth->query(over_wall).distance, 0.05, 1e-9);
  EXPECT_LT((smooth->query(over_wall).normal - Eigen::Vector3d(0, -1, 0)).norm(), 1e-9);
}

TEST(MeshShape, SmoothedDerivativesMatchFiniteDifferences) {
  std::mt19937 random(13);
  std::uniform_real_distribution<double> coordinate(-0.3, 2.3);
  const Mesh l = l_prism();
  const auto shape = sartor::contact::make_mesh_shape(l.vertices, l.faces, "L", 0.02);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 400; ++i)
    points.emplace_back(coordinate(random), coordinate(random), 0.5 * coordinate(random));
  int curved = 0;
  int flat = 0;
  check_derivatives(*shape, points, curved, flat);
  EXPECT_GT(curved, 50);
  EXPECT_EQ(shape->describe(), "mesh L (24 triangles, distance smoothed over 0.02 m)");
}

TEST(MeshShape, RejectsAnOpenMeshNamingIt) {
  Mesh cube = unit_cube();
  cube.faces.pop_back();
  try {
    sartor::contact::make_mesh_shape(cube.vertices, cube.faces, "lidless box");
    FAIL() << "an open mesh was accepted";
  } catch (const sartor::InputError& error) {
    EXPECT_NE(std::string(error.what()).find("lidless box: face "), std::string::npos)
        << error.what();
    EXPECT_NE(std::string(error.what()).find("not closed"), std::string::npos) << error.what();
  }
}

TEST(MeshShape, DescribesItself) {
  const Mesh cube = unit_cube();
  EXPECT_EQ(sartor::contact::make_mesh_shape(cube.vertices, cube.faces, "cube")->describe(),
            "mesh cube (12 triangles)");
}

} // namespace
