// TriangleMesh checks (validate), hinge lists (interior_edges) and boundary
// vertices: counts from Euler's formula on generated meshes, the corner
// mapping of every hinge, and the errors users see.

#include "mesh/triangle_mesh.hpp"

#include "common/error.hpp"
#include "mesh/generators.hpp"

#include "mesh_checks.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>

namespace sartor {
namespace {

using mesh::RectanglePattern;

// Two triangles on the unit square sharing the diagonal 0-2.
TriangleMesh two_triangles() {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  m.material_uv = {{Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0), Eigen::Vector2d(1, 1)},
                   {Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1), Eigen::Vector2d(0, 1)}};
  return m;
}

std::string validate_error(const TriangleMesh& m) {
  try {
    validate(m, "case.obj");
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "validate accepted the mesh";
  return "";
}

TEST(Validate, AcceptsAValidMesh) {
  EXPECT_NO_THROW(validate(two_triangles(), "square"));
}

TEST(Validate, NamesTheTriangleAndTheProblem) {
  {
    auto m = two_triangles();
    m.triangles[1][2] = 4;
    const std::string e = validate_error(m);
    EXPECT_NE(e.find("case.obj: triangle 1 (vertices 0 2 4): vertex index 4 is out of range"),
              std::string::npos)
        << e;
  }
  {
    auto m = two_triangles();
    m.triangles[0][1] = -1;
    EXPECT_NE(validate_error(m).find("triangle 0"), std::string::npos);
  }
  {
    auto m = two_triangles();
    m.triangles[1] = {0, 2, 0};
    const std::string e = validate_error(m);
    EXPECT_NE(e.find("case.obj: triangle 1 (vertices 0 2 0) repeats a vertex"), std::string::npos)
        << e;
  }
  {
    auto m = two_triangles();
    m.positions[3].y() = std::numeric_limits<double>::quiet_NaN();
    const std::string e = validate_error(m);
    EXPECT_NE(e.find("case.obj: vertex 3: the position is not finite"), std::string::npos) << e;
  }
  {
    auto m = two_triangles();
    m.material_uv[1][2].x() = std::numeric_limits<double>::infinity();
    const std::string e = validate_error(m);
    EXPECT_NE(e.find("triangle 1 (vertices 0 2 3): the material coordinate of corner 2 is not "
                     "finite"),
              std::string::npos)
        << e;
  }
  {
    auto m = two_triangles();
    m.material_uv[0][2] = Eigen::Vector2d(2, 0);
    const std::string e = validate_error(m);
    EXPECT_NE(e.find("triangle 0 (vertices 0 1 2) has no material area"), std::string::npos) << e;
  }
  {
    auto m = two_triangles();
    m.material_uv.pop_back();
    EXPECT_NE(validate_error(m).find("2 triangles but material coordinates for 1"),
              std::string::npos);
  }
  {
    auto m = two_triangles();
    m.material_ids = {1};
    EXPECT_NE(validate_error(m).find("2 triangles but 1 material ids"), std::string::npos);
  }
}

TEST(Validate, MaterialAreaThresholdIsRelativeToSize) {
  // A sliver with det / size^2 = 1e-12 is kept at any scale; 1e-16 is not.
  for (const double scale : {1e-6, 1.0, 1e6}) {
    auto m = two_triangles();
    m.material_uv[0] = {Eigen::Vector2d(0, 0), Eigen::Vector2d(scale, 0),
                        Eigen::Vector2d(0.5 * scale, 1e-12 * scale)};
    EXPECT_NO_THROW(validate(m, "sliver")) << scale;
    m.material_uv[0][2].y() = 1e-16 * scale;
    EXPECT_THROW(validate(m, "sliver"), InputError) << scale;
  }
}

TEST(InteriorEdges, TwoTrianglesGiveOneHingeInKernelOrder) {
  const auto m = two_triangles();
  const auto hinges = interior_edges(m);
  ASSERT_EQ(hinges.size(), 1u);
  const Hinge& h = hinges[0];
  // Triangle 0 = (0, 1, 2) runs 2 -> 0 along the shared edge.
  EXPECT_EQ(h.vertices, (std::array<int, 4>{2, 0, 1, 3}));
  EXPECT_EQ(h.triangles, (std::array<int, 2>{0, 1}));
  EXPECT_EQ(h.corners[0], (std::array<int, 3>{2, 0, 1}));
  EXPECT_EQ(h.corners[1], (std::array<int, 3>{0, 1, 2}));
}

// Every hinge's corners name its vertices, in the documented order, and the
// shared edge's two triangles agree on its uv unless the edge is on a seam.
void expect_consistent_hinges(const TriangleMesh& m, bool oriented) {
  for (const Hinge& h : interior_edges(m)) {
    ASSERT_LT(h.triangles[0], h.triangles[1]);
    const std::array<std::array<int, 3>, 2> expected{
        {{h.vertices[0], h.vertices[1], h.vertices[2]},
         {h.vertices[1], h.vertices[0], h.vertices[3]}}};
    for (std::size_t k = 0; k < 2; ++k) {
      const auto t = static_cast<std::size_t>(h.triangles[k]);
      std::set<int> corners(h.corners[k].begin(), h.corners[k].end());
      EXPECT_EQ(corners, (std::set<int>{0, 1, 2}));
      for (std::size_t i = 0; i < 3; ++i)
        EXPECT_EQ(m.triangles[t][static_cast<std::size_t>(h.corners[k][i])], expected[k][i]);
    }
    // The first triangle runs v0 -> v1, the second v1 -> v0 when oriented.
    EXPECT_EQ(h.corners[0][1], (h.corners[0][0] + 1) % 3);
    if (oriented) {
      EXPECT_EQ(h.corners[1][1], (h.corners[1][0] + 1) % 3);
    }
    EXPECT_NE(h.vertices[2], h.vertices[3]);
  }
}

TEST(InteriorEdges, CountsFollowEulersFormula) {
  for (const auto pattern :
       {RectanglePattern::alternating, RectanglePattern::right, RectanglePattern::perturbed}) {
    for (const auto& [nx, ny] : {std::pair{1, 1}, std::pair{3, 2}, std::pair{4, 7}}) {
      const auto m = mesh::rectangle(2.0, 1.0, nx, ny, pattern);
      EXPECT_EQ(interior_edges(m).size(), static_cast<std::size_t>(3 * nx * ny - nx - ny));
      expect_consistent_hinges(m, true);
    }
  }
  for (const int rings : {1, 2, 5}) {
    EXPECT_EQ(interior_edges(mesh::disk(1.0, rings)).size(),
              static_cast<std::size_t>(9 * rings * rings - 3 * rings));
    EXPECT_EQ(interior_edges(mesh::sphere_cap(1.0, 1.0, rings)).size(),
              static_cast<std::size_t>(9 * rings * rings - 3 * rings));
    expect_consistent_hinges(mesh::disk(1.0, rings), true);
  }
  for (const auto& [n, rows] : {std::pair{3, 1}, std::pair{8, 3}, std::pair{7, 4}}) {
    const auto m = mesh::cylinder_band(0.5, 1.0, n, rows);
    EXPECT_EQ(interior_edges(m).size(), static_cast<std::size_t>(3 * n * rows - n));
    expect_consistent_hinges(m, true);
  }
}

TEST(InteriorEdges, SeamHingesCarryEachTrianglesOwnUv) {
  const double radius = 0.5;
  const int segments = 6;
  const auto m = mesh::cylinder_band(radius, 1.0, segments, 2);
  const double circumference = 2.0 * 3.14159265358979323846 * radius;
  int seam_hinges = 0;
  for (const Hinge& h : interior_edges(m)) {
    const auto uv = [&](std::size_t k, std::size_t i) {
      const auto t = static_cast<std::size_t>(h.triangles[k]);
      return m.material_uv[t][static_cast<std::size_t>(h.corners[k][i])];
    };
    // Corners 0, 1 of the first triangle are v0, v1; of the second v1, v0.
    const Eigen::Vector2d jump0 = uv(0, 0) - uv(1, 1);
    const Eigen::Vector2d jump1 = uv(0, 1) - uv(1, 0);
    EXPECT_DOUBLE_EQ(jump0.y(), 0.0);
    EXPECT_DOUBLE_EQ(jump1.y(), 0.0);
    EXPECT_DOUBLE_EQ(jump0.x(), jump1.x());
    if (jump0.x() != 0.0) {
      ++seam_hinges;
      EXPECT_NEAR(std::abs(jump0.x()), circumference, 1e-15);
    }
  }
  EXPECT_EQ(seam_hinges, 2); // the seam's vertical edges, one per row
}

TEST(InteriorEdges, MapsCornersWhereTheOrientationIsInconsistent) {
  auto m = two_triangles();
  m.triangles[1] = {3, 2, 0}; // wound the other way, corners rotated
  m.material_uv[1] = {Eigen::Vector2d(0, 1), Eigen::Vector2d(1, 1), Eigen::Vector2d(0, 0)};
  const auto hinges = interior_edges(m);
  ASSERT_EQ(hinges.size(), 1u);
  EXPECT_EQ(hinges[0].vertices, (std::array<int, 4>{2, 0, 1, 3}));
  EXPECT_EQ(hinges[0].corners[1], (std::array<int, 3>{2, 1, 0}));
  expect_consistent_hinges(m, false);
}

TEST(InteriorEdges, RejectsNonManifoldEdges) {
  auto m = two_triangles();
  m.positions.emplace_back(1, 1, 1);
  m.triangles.push_back({0, 2, 4});
  m.material_uv.push_back({Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1), Eigen::Vector2d(0, 2)});
  try {
    (void)interior_edges(m);
    FAIL() << "accepted an edge with three triangles";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("edge 0-2 is shared by 3 triangles (0, 1, 2)"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW((void)boundary_vertices(m), InputError);
}

TEST(InteriorEdges, RejectsTwoTrianglesOnTheSameVertices) {
  auto m = two_triangles();
  m.triangles[1] = {0, 2, 1};
  m.material_uv[1] = {Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1), Eigen::Vector2d(1, 0)};
  try {
    (void)interior_edges(m);
    FAIL() << "accepted a doubled triangle";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("triangles 0 and 1 have the same three vertices"),
              std::string::npos)
        << e.what();
  }
}

TEST(BoundaryVertices, RectangleDiskBandAndClosedSurface) {
  const auto rect = mesh::rectangle(2.0, 1.0, 4, 3, RectanglePattern::perturbed);
  const auto border = boundary_vertices(rect);
  EXPECT_EQ(border.size(), 2u * (4 + 3));
  for (const int v : border) {
    const Eigen::Vector3d& p = rect.positions[static_cast<std::size_t>(v)];
    EXPECT_TRUE(p.x() == 0.0 || p.x() == 2.0 || p.y() == 0.0 || p.y() == 1.0) << v;
  }
  const auto disk = mesh::disk(1.0, 3);
  const auto rim = boundary_vertices(disk);
  ASSERT_EQ(rim.size(), 18u);
  EXPECT_EQ(rim.front(), 1 + 3 * 3 * 2); // the outer ring, numbered last
  EXPECT_EQ(rim.back(), static_cast<int>(disk.vertex_count()) - 1);
  EXPECT_EQ(boundary_vertices(mesh::cylinder_band(1.0, 1.0, 5, 3)),
            (std::vector<int>{0, 1, 2, 3, 4, 15, 16, 17, 18, 19}));

  TriangleMesh tetrahedron;
  tetrahedron.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  tetrahedron.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  for (int t = 0; t < 4; ++t)
    tetrahedron.material_uv.push_back(
        {Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0), Eigen::Vector2d(0, 1)});
  EXPECT_TRUE(boundary_vertices(tetrahedron).empty());
  EXPECT_EQ(interior_edges(tetrahedron).size(), 6u);
  expect_consistent_hinges(tetrahedron, true);
}

} // namespace
} // namespace sartor
