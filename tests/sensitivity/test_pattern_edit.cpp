// Pattern edits (garment/pattern_edit.hpp): mean value coordinates, positive
// mean value coordinates and the outline edits built on them, against closed
// forms: affine maps reproduced, the centre of a regular polygon, linear
// interpolation along edges, mirrored edits; the positive coordinates also
// against plain mean value coordinates where the whole outline is visible
// and against their definition, an integral over rays, cast one by one.

#include "common/error.hpp"
#include "garment/pattern_edit.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace sartor::garment {
namespace {

using Eigen::Vector2d;

// A non-convex hexagon (a panel with a notch), counter-clockwise.
std::vector<Vector2d> notched_panel() {
  return {Vector2d(0.0, 0.0), Vector2d(0.5, 0.0), Vector2d(0.5, 0.6),
          Vector2d(0.3, 0.3), Vector2d(0.1, 0.6), Vector2d(0.0, 0.5)};
}

// An L: a unit square with a second unit square to its right and one above.
std::vector<Vector2d> l_panel() {
  return {Vector2d(0.0, 0.0), Vector2d(2.0, 0.0), Vector2d(2.0, 1.0),
          Vector2d(1.0, 1.0), Vector2d(1.0, 2.0), Vector2d(0.0, 2.0)};
}

// A U: two prongs 1 wide and 2 high on a base 3 wide, a square notch
// between them; counter-clockwise, corners 2..5 those of the right prong and
// the notch.
std::vector<Vector2d> u_panel() {
  return {Vector2d(0.0, 0.0), Vector2d(3.0, 0.0), Vector2d(3.0, 2.0), Vector2d(2.0, 2.0),
          Vector2d(2.0, 1.0), Vector2d(1.0, 1.0), Vector2d(1.0, 2.0), Vector2d(0.0, 2.0)};
}

// A comb: five teeth 0.1 wide and 0.8 long on a back 0.2 deep, gaps 0.1 wide.
std::vector<Vector2d> comb_panel() {
  std::vector<Vector2d> outline = {Vector2d(0.0, 0.0), Vector2d(0.9, 0.0)};
  for (int tooth = 4; tooth >= 0; --tooth) {
    const double right = 0.2 * tooth + 0.1;
    outline.emplace_back(right, 1.0);
    outline.emplace_back(right - 0.1, 1.0);
    if (tooth > 0) {
      outline.emplace_back(right - 0.1, 0.2);
      outline.emplace_back(right - 0.2, 0.2);
    }
  }
  return outline;
}

// Inside by the winding number: the turn of the directions to the outline
// is a full turn from inside, none from outside.
bool inside_by_winding(const std::vector<Vector2d>& outline, const Vector2d& point) {
  double turn = 0.0;
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const Vector2d a = outline[i] - point;
    const Vector2d b = outline[(i + 1) % outline.size()] - point;
    turn += std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
  }
  return std::abs(turn) > M_PI;
}

// Interior points of a panel on a grid, offset so that none is on an edge.
std::vector<Vector2d> interior_grid(const std::vector<Vector2d>& outline, double step) {
  Vector2d low = outline.front(), high = outline.front();
  for (const Vector2d& p : outline) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  std::vector<Vector2d> points;
  for (double x = low.x() + 0.37 * step; x < high.x(); x += step)
    for (double y = low.y() + 0.61 * step; y < high.y(); y += step)
      if (inside_by_winding(outline, Vector2d(x, y))) points.emplace_back(x, y);
  return points;
}

// The definition of the positive coordinates, integrated by the midpoint rule
// over `rays` rays from the point: each ray's first hit on the outline,
// interpolated linearly on its edge, weighed by 1 / its distance.
std::vector<double> ray_cast_coordinates(const std::vector<Vector2d>& outline,
                                         const Vector2d& point, int rays) {
  const std::size_t n = outline.size();
  std::vector<double> lambda(n, 0.0);
  for (int k = 0; k < rays; ++k) {
    const double angle = 2.0 * M_PI * (k + 0.5) / rays;
    const Vector2d u(std::cos(angle), std::sin(angle));
    double nearest = std::numeric_limits<double>::infinity(), nearest_t = 0.0;
    std::size_t nearest_edge = 0;
    for (std::size_t i = 0; i < n; ++i) {
      // point + s u = P_i + t (P_j - P_i), solved by Cramer's rule.
      const Vector2d edge = outline[(i + 1) % n] - outline[i];
      const Vector2d to_start = outline[i] - point;
      const double det = edge.x() * u.y() - edge.y() * u.x();
      if (det == 0.0) continue;
      const double s = (edge.x() * to_start.y() - edge.y() * to_start.x()) / det;
      const double t = (u.x() * to_start.y() - u.y() * to_start.x()) / det;
      if (s > 0.0 && t >= 0.0 && t <= 1.0 && s < nearest) {
        nearest = s;
        nearest_t = t;
        nearest_edge = i;
      }
    }
    lambda[nearest_edge] += (1.0 - nearest_t) / nearest;
    lambda[(nearest_edge + 1) % n] += nearest_t / nearest;
  }
  const double total = std::accumulate(lambda.begin(), lambda.end(), 0.0);
  for (double& l : lambda)
    l /= total;
  return lambda;
}

double largest_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double largest = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
    largest = std::max(largest, std::abs(a[i] - b[i]));
  return largest;
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
  for (InteriorCoordinates coordinates :
       {InteriorCoordinates::mean_value, InteriorCoordinates::positive_mean_value}) {
    const std::vector<Vector2d> change = outline_edit(outline, delta, points, coordinates);
    for (std::size_t i = 0; i < points.size(); ++i)
      EXPECT_LT((change[i] - (a * points[i] + b)).norm(), 1e-14) << "point " << i;
  }
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

TEST(PatternEdit, PositiveCoordinatesAreMeanValueCoordinatesWhereTheWholeOutlineIsSeen) {
  std::vector<Vector2d> heptagon;
  for (int i = 0; i < 7; ++i)
    heptagon.emplace_back(std::cos(2.0 * M_PI * i / 7.0), std::sin(2.0 * M_PI * i / 7.0));
  const std::vector<Vector2d> pentagon = {Vector2d(0.1, -0.2), Vector2d(1.3, 0.05),
                                          Vector2d(1.7, 0.9), Vector2d(0.6, 1.4),
                                          Vector2d(-0.3, 0.7)};
  for (const Vector2d& p : {Vector2d(0.0, 0.0), Vector2d(0.3, -0.2), Vector2d(-0.9, 0.05)})
    EXPECT_LT(largest_difference(positive_mean_value_coordinates(heptagon, p),
                                 mean_value_coordinates(heptagon, p)),
              1e-14);
  for (const Vector2d& p : interior_grid(pentagon, 0.1))
    EXPECT_LT(largest_difference(positive_mean_value_coordinates(pentagon, p),
                                 mean_value_coordinates(pentagon, p)),
              1e-14)
        << "at (" << p.x() << ", " << p.y() << ")";
  // Non-convex panels, from points of their kernel.
  EXPECT_LT(
      largest_difference(positive_mean_value_coordinates(notched_panel(), Vector2d(0.25, 0.1)),
                         mean_value_coordinates(notched_panel(), Vector2d(0.25, 0.1))),
      1e-14);
  EXPECT_LT(largest_difference(positive_mean_value_coordinates(l_panel(), Vector2d(0.5, 0.5)),
                               mean_value_coordinates(l_panel(), Vector2d(0.5, 0.5))),
            1e-14);
}

TEST(PatternEdit, PositiveCoordinatesArePositiveSumToOneAndReproduceThePoint) {
  for (const std::vector<Vector2d>& outline :
       {notched_panel(), l_panel(), u_panel(), comb_panel()}) {
    const std::vector<Vector2d> points = interior_grid(outline, 0.013);
    ASSERT_GT(points.size(), 100u);
    for (const Vector2d& p : points) {
      const std::vector<double> lambda = positive_mean_value_coordinates(outline, p);
      Vector2d reproduced = Vector2d::Zero();
      for (std::size_t i = 0; i < outline.size(); ++i)
        reproduced += lambda[i] * outline[i];
      EXPECT_GE(*std::min_element(lambda.begin(), lambda.end()), 0.0);
      EXPECT_NEAR(std::accumulate(lambda.begin(), lambda.end(), 0.0), 1.0, 1e-14);
      EXPECT_LT((reproduced - p).norm(), 1e-14) << "at (" << p.x() << ", " << p.y() << ")";
    }
  }
}

TEST(PatternEdit, PositiveCoordinatesDoNotDependOnTheOutlinesOrientation) {
  std::vector<Vector2d> clockwise = u_panel();
  std::reverse(clockwise.begin(), clockwise.end());
  const Vector2d p(0.5, 1.8);
  const std::vector<double> lambda = positive_mean_value_coordinates(u_panel(), p);
  std::vector<double> reversed = positive_mean_value_coordinates(clockwise, p);
  std::reverse(reversed.begin(), reversed.end());
  EXPECT_LT(largest_difference(lambda, reversed), 1e-15);
}

// The midpoint rule over 2^18 rays misses by up to about one ray's angle
// (2.4e-5 rad) times the jump of the integrand where the first hit jumps from
// edge to edge, at the reflex corners' directions: 1.6e-6 at most here.
TEST(PatternEdit, PositiveCoordinatesIntegrateTheVisibleOutline) {
  const int rays = 1 << 18;
  for (const auto& [outline, p] :
       {std::pair(u_panel(), Vector2d(0.5, 1.8)), std::pair(u_panel(), Vector2d(1.7, 0.6)),
        std::pair(notched_panel(), Vector2d(0.07, 0.52)),
        std::pair(comb_panel(), Vector2d(0.25, 0.61)),
        std::pair(comb_panel(), Vector2d(0.43, 0.1))})
    EXPECT_LT(largest_difference(positive_mean_value_coordinates(outline, p),
                                 ray_cast_coordinates(outline, p, rays)),
              2.0 * M_PI / rays)
        << "at (" << p.x() << ", " << p.y() << ")";
}

TEST(PatternEdit, PositiveCoordinatesArePositiveWhereMeanValueCoordinatesAreNot) {
  const Vector2d p(0.5, 1.8); // high in the U's left prong
  const std::vector<double> mean_value = mean_value_coordinates(u_panel(), p);
  const std::vector<double> positive = positive_mean_value_coordinates(u_panel(), p);
  EXPECT_LT(*std::min_element(mean_value.begin(), mean_value.end()), 0.0);
  EXPECT_GE(*std::min_element(positive.begin(), positive.end()), 0.0);
}

TEST(PatternEdit, HiddenCornersGetNoWeight) {
  // From high in the U's left prong the notch hides the right prong's top
  // corners and the notch's far corner with all their edges; the base's right
  // corner is hidden, but part of its base edge is seen.
  const std::vector<double> lambda = positive_mean_value_coordinates(u_panel(), Vector2d(0.5, 1.8));
  EXPECT_EQ(lambda[2], 0.0);
  EXPECT_EQ(lambda[3], 0.0);
  EXPECT_EQ(lambda[4], 0.0);
  EXPECT_GT(lambda[1], 0.0);
  // A point near the tip of one of the comb's teeth sees no other tooth's tip.
  const std::vector<Vector2d> comb = comb_panel();
  const std::vector<double> comb_lambda =
      positive_mean_value_coordinates(comb, Vector2d(0.45, 0.9));
  for (std::size_t i = 0; i < comb.size(); ++i) {
    if (comb[i].y() == 1.0 && std::abs(comb[i].x() - 0.45) > 0.1) {
      EXPECT_EQ(comb_lambda[i], 0.0) << "tip at x = " << comb[i].x();
    }
  }
}

TEST(PatternEdit, PositiveCoordinatesAreContinuousWhereTheViewChanges) {
  // Points whose view changes: on the line through the U's reflex corner
  // (1, 1) and its base corner (3, 0), the grazing ray ends at that corner;
  // on the line of the notch's floor, the grazing ray runs along an edge;
  // (1.5, 0.5) is on the lines through each reflex corner and the top corner
  // beyond it, (0, 2) and (3, 2).
  struct Crossing {
    Vector2d at, across;
  };
  const std::vector<Crossing> crossings = {{Vector2d(0.2, 1.4), Vector2d(1.0, 2.0).normalized()},
                                           {Vector2d(0.5, 1.0), Vector2d(0.0, 1.0)},
                                           {Vector2d(1.5, 0.5), Vector2d(1.0, 0.0)}};
  const std::vector<Vector2d> outline = u_panel();
  for (const Crossing& c : crossings) {
    const std::vector<double> on_line = positive_mean_value_coordinates(outline, c.at);
    // 1e-7 across changes the weights by about 1e-7 over the distance to the
    // reflex corner (0.7 or more): 5e-8 here; 1e-6 allows a factor of 7
    // on top.
    for (double step : {1e-7, -1e-7})
      EXPECT_LT(largest_difference(positive_mean_value_coordinates(outline, c.at + step * c.across),
                                   on_line),
                1e-6)
          << "from (" << c.at.x() << ", " << c.at.y() << ") by " << step;
    // Round-off on either side picks different gaps, but nothing jumps.
    for (double step : {1e-15, -1e-15})
      EXPECT_LT(largest_difference(positive_mean_value_coordinates(outline, c.at + step * c.across),
                                   on_line),
                1e-14)
          << "from (" << c.at.x() << ", " << c.at.y() << ") by " << step;
  }
}

TEST(PatternEdit, PositiveCoordinatesRejectPointsOutsideAndInterpolateOnTheOutline) {
  const std::vector<Vector2d> outline = u_panel();
  for (const Vector2d& p :
       {Vector2d(1.5, 1.5), Vector2d(4.0, 1.0), Vector2d(1.5, 2.0), Vector2d(-1e-9, 0.5)})
    EXPECT_THROW(positive_mean_value_coordinates(outline, p), InputError);
  try {
    positive_mean_value_coordinates(notched_panel(), Vector2d(0.3, 0.5));
    ADD_FAILURE() << "a point in the notch is accepted";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()),
              "pattern edit: point (0.3, 0.5) is outside the panel's outline");
  }
  const std::vector<double> on_edge = positive_mean_value_coordinates(outline, Vector2d(1.5, 1.0));
  EXPECT_NEAR(on_edge[4], 0.5, 1e-15); // the notch's floor, halfway
  EXPECT_NEAR(on_edge[5], 0.5, 1e-15);
  const std::vector<double> a_third =
      positive_mean_value_coordinates(outline, Vector2d(3.0, 2.0 / 3.0));
  EXPECT_NEAR(a_third[1], 2.0 / 3.0, 1e-15);
  EXPECT_NEAR(a_third[2], 1.0 / 3.0, 1e-15);
  for (std::size_t i = 0; i < outline.size(); ++i)
    EXPECT_EQ(positive_mean_value_coordinates(outline, outline[i])[i], 1.0) << "corner " << i;
  EXPECT_THROW(
      positive_mean_value_coordinates({Vector2d(0.0, 0.0), Vector2d(1.0, 0.0)}, Vector2d(0.5, 0.1)),
      InputError);
  EXPECT_THROW(positive_mean_value_coordinates(
                   {Vector2d(0.0, 0.0), Vector2d(1.0, 0.0), Vector2d(1.0, 0.0), Vector2d(0.0, 1.0)},
                   Vector2d(0.2, 0.2)),
               InputError);
}

TEST(PatternEdit, AffineOutlineEditsMoveNotchedPanelsAffinelyByPositiveCoordinates) {
  Eigen::Matrix2d a;
  a << 0.3, -0.1, 0.05, -0.2;
  const Vector2d b(-0.02, 0.04);
  for (const std::vector<Vector2d>& outline : {l_panel(), u_panel(), comb_panel()}) {
    std::vector<Vector2d> delta;
    for (const Vector2d& p : outline)
      delta.push_back(a * p + b);
    const std::vector<Vector2d> points = interior_grid(outline, 0.05);
    const std::vector<Vector2d> change = outline_edit(outline, delta, points);
    for (std::size_t i = 0; i < points.size(); ++i)
      EXPECT_LT((change[i] - (a * points[i] + b)).norm(), 1e-14) << "point " << i;
  }
}

// A mesh vertex on a curved line lies a little outside the polygon that
// flattens it: it takes the interpolation at the polygon's nearest point
// (by hand: the notched panel's bottom edge from (0, 0) to (0.5, 0)), and
// inside the panel_coordinates are the interior coordinates.
TEST(PatternEdit, PointsJustOutsideFollowTheNearestEdge) {
  const std::vector<Vector2d> outline = notched_panel();
  for (const auto kind :
       {InteriorCoordinates::positive_mean_value, InteriorCoordinates::mean_value}) {
    const std::vector<double> below = panel_coordinates(kind, outline, Vector2d(0.2, -1e-4));
    EXPECT_NEAR(below[0], 0.6, 1e-14);
    EXPECT_NEAR(below[1], 0.4, 1e-14);
    // Beyond a corner: the corner itself.
    const std::vector<double> corner = panel_coordinates(kind, outline, Vector2d(0.51, -0.01));
    EXPECT_NEAR(corner[1], 1.0, 1e-14);
    const Vector2d inside(0.25, 0.1);
    EXPECT_EQ(panel_coordinates(kind, outline, inside),
              interior_coordinates(kind, outline, inside));
  }
  // Continuous across the edge: just inside, the edge's interpolation too.
  const std::vector<double> above =
      panel_coordinates(InteriorCoordinates::positive_mean_value, outline, Vector2d(0.2, 1e-9));
  EXPECT_NEAR(above[0], 0.6, 1e-6);
  EXPECT_NEAR(above[1], 0.4, 1e-6);
}

} // namespace
} // namespace sartor::garment
