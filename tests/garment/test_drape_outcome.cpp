// How a drape ended (app/drape_outcome.hpp), on made-up garments around
// a sphere of radius 0.3 m centred 1 m above a floor at z = 0: the distance
// to it is |p - c| - 0.3, and the heights are chosen so that each limit is
// crossed by a wide margin or not at all.

#include "app/drape_outcome.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace sartor {
namespace {

using Eigen::Vector3d;

const Vector3d centre(0, 0, 1);
double sphere_distance(const Vector3d& p) {
  return (p - centre).norm() - 0.3;
}

// A ring of 8 vertices of radius r at height z.
std::vector<Vector3d> ring(double r, double z) {
  std::vector<Vector3d> points;
  for (int k = 0; k < 8; ++k)
    points.emplace_back(r * std::cos(k * M_PI / 4), r * std::sin(k * M_PI / 4), z);
  return points;
}

TEST(DrapeOutcome, Resting) {
  // Started 0.05 m above the equator, ended on it, touching the sphere.
  const DrapeOutcome o =
      classify_drape_end(ring(0.31, 1.05), ring(0.305, 1.0), 0.0, sphere_distance);
  EXPECT_EQ(o.end, DrapeEnd::on_body);
  EXPECT_NEAR(o.centroid_drop, 0.05, 1e-12);
  EXPECT_NEAR(o.nearest_body_distance, 0.005, 1e-12);
  EXPECT_EQ(o.description(), "on the body");
}

TEST(DrapeOutcome, SlidDown) {
  // From the equator to 0.2 m below the centre, radius hugging the sphere
  // (sqrt(0.3^2 - 0.2^2) = 0.2236): touching it, 0.2 m down.
  const DrapeOutcome o =
      classify_drape_end(ring(0.305, 1.0), ring(0.2246, 0.8), 0.0, sphere_distance);
  EXPECT_EQ(o.end, DrapeEnd::slid_down);
  EXPECT_NEAR(o.centroid_drop, 0.2, 1e-12);
  EXPECT_FALSE(o.on_floor);
  EXPECT_FALSE(o.off_body);
  EXPECT_EQ(o.description().rfind("slid down 0.200 m", 0), 0u) << o.description();
  // A wider tolerance accepts the same drop.
  DrapeEndLimits loose;
  loose.drop_tolerance = 0.25;
  EXPECT_EQ(
      classify_drape_end(ring(0.305, 1.0), ring(0.2246, 0.8), 0.0, sphere_distance, loose).end,
      DrapeEnd::on_body);
}

TEST(DrapeOutcome, OnTheFloorAndOffTheBody) {
  // Fallen to the floor, 0.6 m from the sphere's bottom: off the body too,
  // which takes precedence.
  const DrapeOutcome fallen =
      classify_drape_end(ring(0.305, 1.0), ring(0.3, 0.002), 0.0, sphere_distance);
  EXPECT_TRUE(fallen.on_floor);
  EXPECT_TRUE(fallen.slid_down);
  EXPECT_TRUE(fallen.off_body);
  EXPECT_EQ(fallen.end, DrapeEnd::off_body);
  // A long garment touching the sphere at the equator and trailing on the
  // floor: on the floor, not off the body.
  std::vector<Vector3d> start = ring(0.305, 1.0), end = ring(0.305, 1.0);
  for (const Vector3d& p : ring(0.305, 0.5))
    start.push_back(p);
  for (const Vector3d& p : ring(0.305, 0.005))
    end.push_back(p);
  const DrapeOutcome trailing = classify_drape_end(start, end, 0.0, sphere_distance);
  EXPECT_EQ(trailing.end, DrapeEnd::on_floor);
  EXPECT_NEAR(trailing.lowest, 0.005, 1e-12);
  // Blown away sideways at the same height: off the body, not slid.
  std::vector<Vector3d> away = ring(0.305, 1.0);
  for (Vector3d& p : away)
    p.x() += 2.0;
  const DrapeOutcome gone = classify_drape_end(ring(0.305, 1.0), away, 0.0, sphere_distance);
  EXPECT_EQ(gone.end, DrapeEnd::off_body);
  EXPECT_FALSE(gone.slid_down);
}

TEST(DrapeOutcome, MismatchedListsAreRefused) {
  EXPECT_THROW(classify_drape_end(ring(0.3, 1), {}, 0.0, sphere_distance), std::invalid_argument);
}

} // namespace
} // namespace sartor
