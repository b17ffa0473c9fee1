// Pattern edits (garment/pattern_edit.hpp): mean value coordinates and the
// outline edits built on them, against closed forms: affine maps reproduced,
// the centre of a regular polygon, linear interpolation along edges, mirrored
// edits.

#include "common/error.hpp"
#include "garment/pattern_edit.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace sartor::garment {
namespace {

using Eigen::Vector2d;

// A non-convex hexagon (a panel with a notch), counter-clockwise.
std::vector<Vector2d> notched_panel() {
  return {Vector2d(0.0, 0.0), Vector2d(0.5, 0.0), Vector2d(0.5, 0.6),
          Vector2d(0.3, 0.3), Vector2d(0.1, 0.6), Vector2d(0.0, 0.5)};
}

TEST(PatternEdit, AffineOutlineEditsMoveThePanelAffinely) {
  const std::vector<Vector2d> outline = notched_panel();
  Eigen::Matrix2d a;
  a << 0.1, -0.05, 0.02, 0.2;
  const Vector2d b(0.03, -0.01);
  std::vector<Vector2d> delta;
  for (const Vector2d& p : outline)
    delta.push_back(a * p + b);
  const std::vector<Vector2d> points = {Vector2d(0.25, 0.1),  Vector2d(0.45, 0.5),
                                        Vector2d(0.05, 0.45), Vector2d(0.25, 0.0),
                                        Vector2d(0.5, 0.6),   Vector2d(0.4, 0.45)};
  const std::vector<Vector2d> change = outline_edit(outline, delta, points);
  for (std::size_t i = 0; i < points.size(); ++i)
    EXPECT_LT((change[i] - (a * points[i] + b)).norm(), 1e-14) << "point " << i;
}

TEST(PatternEdit, CentreOfARegularPolygonWeighsEveryCornerAlike) {
  std::vector<Vector2d> outline;
  for (int i = 0; i < 7; ++i)
    outline.emplace_back(std::cos(2.0 * M_PI * i / 7.0), std::sin(2.0 * M_PI * i / 7.0));
  for (double lambda : mean_value_coordinates(outline, Vector2d::Zero()))
    EXPECT_NEAR(lambda, 1.0 / 7.0, 1e-15);
}

TEST(PatternEdit, EdgesInterpolateLinearlyAndCornersAreTheirOwn) {
  const std::vector<Vector2d> outline = notched_panel();
  const std::vector<double> on_edge = mean_value_coordinates(outline, Vector2d(0.4, 0.45));
  EXPECT_NEAR(on_edge[2], 0.5, 1e-14); // halfway from (0.5, 0.6) to (0.3, 0.3)
  EXPECT_NEAR(on_edge[3], 0.5, 1e-14);
  const std::vector<double> corner = mean_value_coordinates(outline, outline[4]);
  EXPECT_NEAR(corner[4], 1.0, 1e-14);
  double sum = 0.0;
  for (double lambda : mean_value_coordinates(outline, Vector2d(0.2, 0.2)))
    sum += lambda;
  EXPECT_NEAR(sum, 1.0, 1e-14);
}

TEST(PatternEdit, SymmetricEditMirrorsAboutTheAxis) {
  // A rectangle symmetric about x = 0.25: corners 0 <-> 1 and 2 <-> 3.
  const std::vector<Vector2d> delta = {Vector2d(-0.02, -0.01), Vector2d::Zero(), Vector2d::Zero(),
                                       Vector2d::Zero()};
  const std::vector<Vector2d> edit = symmetric_edit(delta, {1, -1, -1, -1}, Vector2d(0.0, 1.0));
  EXPECT_LT((edit[0] - Vector2d(-0.02, -0.01)).norm(), 1e-15);
  EXPECT_LT((edit[1] - Vector2d(0.02, -0.01)).norm(), 1e-15);
}

TEST(PatternEdit, BadOutlinesAreRejected) {
  EXPECT_THROW(mean_value_coordinates({Vector2d(0.0, 0.0), Vector2d(1.0, 0.0)}, Vector2d(0.5, 0.1)),
               InputError);
  EXPECT_THROW(mean_value_coordinates({Vector2d(0.0, 0.0), Vector2d(0.0, 0.0), Vector2d(1.0, 1.0)},
                                      Vector2d(0.5, 0.1)),
               InputError);
  EXPECT_THROW(outline_edit(notched_panel(), {Vector2d::Zero()}, {Vector2d(0.2, 0.2)}), InputError);
  EXPECT_THROW(symmetric_edit({Vector2d::Zero()}, {3}, Vector2d(0.0, 1.0)), InputError);
}

} // namespace
} // namespace sartor::garment
