// Surface dragging and pushpins (garment/surface_drag.hpp) on a flat sheet
// lying on a plane: there the body frames all agree, so an unpinned drag is
// a rigid translation and mesh distances along a row are closed-form.

#include "contact/analytic_shapes.hpp"
#include "garment/surface_drag.hpp"

#include <gtest/gtest.h>

namespace {

using namespace sartor;
using namespace sartor::garment;

constexpr double offset = 0.012, spacing = 0.02;

// A grid of columns x rows vertices, `spacing` apart, at height `offset`
// above the plane z = 0; vertex (i, j) is j * columns + i.
TriangleMesh sheet(int columns, int rows) {
  TriangleMesh mesh;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i)
      mesh.positions.emplace_back(i * spacing, j * spacing, offset);
  const auto uv = [&](int v) { return mesh.positions[std::size_t(v)].head<2>().eval(); };
  for (int j = 0; j + 1 < rows; ++j)
    for (int i = 0; i + 1 < columns; ++i) {
      const int a = j * columns + i, b = a + 1, c = a + columns, d = c + 1;
      mesh.triangles.push_back({a, b, d});
      mesh.material_uv.push_back({uv(a), uv(b), uv(d)});
      mesh.triangles.push_back({a, d, c});
      mesh.material_uv.push_back({uv(a), uv(d), uv(c)});
    }
  return mesh;
}

const contact::Plane floor_plane(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ());

RelaxParameters parameters() {
  RelaxParameters p;
  p.offset = offset;
  return p;
}

TEST(SurfaceDrag, UnpinnedDragOnAPlaneTranslatesTheWholeSheet) {
  ClothOnBody cloth(sheet(5, 5), floor_plane, parameters());
  const std::vector<Eigen::Vector3d> start = cloth.positions();
  SurfaceDrag drag(cloth, 12, {}, DragOptions{});
  // The normal part of each step is dropped: the drag follows the surface.
  for (int k = 0; k < 4; ++k)
    drag.step({0.01, -0.005, 0.03});
  for (std::size_t v = 0; v < start.size(); ++v)
    EXPECT_LT((cloth.positions()[v] - start[v] - Eigen::Vector3d(0.04, -0.02, 0.0)).norm(), 1e-9)
        << "vertex " << v;
}

TEST(SurfaceDrag, DraggedVertexReachesItsTargetAndThePinStays) {
  const int columns = 11;
  ClothOnBody cloth(sheet(columns, 2), floor_plane, parameters());
  const std::vector<Eigen::Vector3d> start = cloth.positions();
  const int grabbed = 2, pin = 8;
  SurfaceDrag drag(cloth, grabbed, {pin}, DragOptions{});
  for (int k = 0; k < 4; ++k)
    drag.step({0.005, 0.0, 0.0});
  EXPECT_LT((cloth.positions()[grabbed] - start[grabbed] - Eigen::Vector3d(0.02, 0, 0)).norm(),
            1e-9);
  EXPECT_LT((cloth.positions()[pin] - start[pin]).norm(), 1e-12);
  // Beyond the pin the cloth hardly moves; before the grabbed vertex it follows.
  EXPECT_LT((cloth.positions()[10] - start[10]).norm(), 0.002);
  EXPECT_GT((cloth.positions()[0] - start[0]).x(), 0.015);
}

TEST(SurfaceDrag, AttenuationFallsFromGrabbedToPinAsThePaperSays) {
  const int columns = 11;
  ClothOnBody cloth(sheet(columns, 2), floor_plane, parameters());
  const int grabbed = 1, pin = 9;
  SurfaceDrag drag(cloth, grabbed, {pin}, DragOptions{});
  // Along the bottom row mesh distances are the differences in x.
  const double c = (pin - grabbed) * spacing;
  double before = 2.0;
  for (int i = 0; i < columns; ++i) {
    const double a = std::abs(i - grabbed) * spacing, b = std::abs(pin - i) * spacing;
    const double expected = std::clamp((c - a + b) / (2.0 * c), 0.0, 1.0);
    EXPECT_NEAR(drag.ratios()[std::size_t(i)], expected, 1e-9) << "vertex " << i;
    if (i >= grabbed) {
      EXPECT_LE(drag.ratios()[std::size_t(i)], before) << "vertex " << i;
      before = drag.ratios()[std::size_t(i)];
    }
  }
  EXPECT_DOUBLE_EQ(drag.ratios()[std::size_t(grabbed)], 1.0);
  EXPECT_DOUBLE_EQ(drag.ratios()[std::size_t(pin)], 0.0);
}

TEST(SurfaceDrag, DependencyGraphParentsComeFirst) {
  ClothOnBody cloth(sheet(4, 3), floor_plane, parameters());
  const DependencyGraph graph = dependency_graph(cloth.edges(), 5);
  ASSERT_EQ(graph.order.size(), 12u);
  EXPECT_EQ(graph.order.front(), 5);
  std::vector<int> position(12);
  for (std::size_t k = 0; k < graph.order.size(); ++k)
    position[std::size_t(graph.order[k])] = int(k);
  for (int v = 0; v < 12; ++v) {
    if (v == 5) continue;
    EXPECT_FALSE(graph.parents[std::size_t(v)].empty());
    for (int parent : graph.parents[std::size_t(v)])
      EXPECT_LT(position[std::size_t(parent)], position[std::size_t(v)]);
  }
}

} // namespace
