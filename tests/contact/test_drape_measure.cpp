// The Cusick measures of app/contact_case.hpp on shapes made here: a
// flat disc whose overhang is folded into N nodes by a radial shrink that
// varies as cos(N theta), so the rim's projected radius has N maxima.

#include "app/contact_case.hpp"
#include "mesh/generators.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace sartor {
namespace {

constexpr double specimen = 0.15, support = 0.09;

// The disc's overhang drawn in by (0.6 + fold cos(N theta)) of its width,
// plus a ripple of `ripple` m at `ripple_waves` per turn.
std::vector<Eigen::Vector3d> folded(const TriangleMesh& disc, int nodes, double fold,
                                    double ripple = 0.0, int ripple_waves = 0) {
  std::vector<Eigen::Vector3d> positions;
  for (const Eigen::Vector3d& p : disc.positions) {
    const double r = p.head<2>().norm(), theta = std::atan2(p.y(), p.x());
    double shrunk = r;
    if (r > support) {
      shrunk = support + (r - support) * (0.6 + fold * std::cos(nodes * theta)) +
               ripple * std::cos(ripple_waves * theta) * (r - support) / (specimen - support);
    }
    const double scale = r > 0.0 ? shrunk / r : 1.0;
    positions.emplace_back(scale * p.x(), scale * p.y(), -(r - shrunk));
  }
  return positions;
}

TEST(DrapeNodes, CountsTheFoldsOfTheRim) {
  const TriangleMesh disc = mesh::disk(specimen, 18);
  const double prominence = 0.01 * specimen;
  for (int nodes : {4, 6, 8, 10, 12}) {
    EXPECT_EQ(drape_nodes(disc, folded(disc, nodes, 0.2), prominence), nodes) << nodes;
  }
}

TEST(DrapeNodes, AnAxisymmetricDrapeHasNone) {
  const TriangleMesh disc = mesh::disk(specimen, 18);
  EXPECT_EQ(drape_nodes(disc, folded(disc, 8, 0.0), 0.01 * specimen), 0);
}

// A ripple of 0.5 mm (a third of the prominence) at 30 waves per turn
// does not add nodes to 6 folds of 12 mm.
TEST(DrapeNodes, RipplesBelowTheProminenceAreNotNodes) {
  const TriangleMesh disc = mesh::disk(specimen, 18);
  EXPECT_EQ(drape_nodes(disc, folded(disc, 6, 0.2, 5e-4, 30), 0.01 * specimen), 6);
  EXPECT_EQ(drape_nodes(disc, folded(disc, 6, 0.2, 5e-3, 30), 0.01 * specimen), 30);
}

} // namespace
} // namespace sartor
