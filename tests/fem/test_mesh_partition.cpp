// The default partition of the cloth's triangles over the ranks
// (fem/mesh_partition.hpp): the same every time, every part used, about
// equal parts of connected triangles, and contiguous blocks for meshes too
// small for METIS.

#include "fem/mesh_partition.hpp"
#include "mesh/generators.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <vector>

namespace sartor {
namespace {

TEST(MeshPartition, TheSameMeshIsPartitionedTheSameWayEveryTime) {
  const TriangleMesh mesh = mesh::rectangle(1.0, 0.8, 24, 20, mesh::RectanglePattern::perturbed);
  for (int parts : {2, 3, 4}) {
    const std::vector<int> first = partition_triangles(mesh, parts);
    for (int run = 0; run < 3; ++run)
      EXPECT_EQ(partition_triangles(mesh, parts), first) << parts << " parts";
    std::vector<int> sizes(std::size_t(parts), 0);
    for (int p : first) {
      ASSERT_GE(p, 0);
      ASSERT_LT(p, parts);
      ++sizes[std::size_t(p)];
    }
    const double ideal = double(mesh.triangle_count()) / parts;
    for (int size : sizes) // METIS's default imbalance is 3 %
      EXPECT_LT(std::abs(size - ideal), 0.05 * ideal) << parts << " parts";
  }
}

TEST(MeshPartition, FewerThanTwoTrianglesAPartGiveContiguousBlocks) {
  const TriangleMesh mesh = mesh::rectangle(1.0, 1.0, 2, 1); // 4 triangles
  EXPECT_EQ(partition_triangles(mesh, 4), (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(partition_triangles(mesh, 1), (std::vector<int>{0, 0, 0, 0}));
}

} // namespace
} // namespace sartor
