// The mannequin sized to measurement sets and posed: girths taken by the
// test's own slicing of the surface, the surface's derivatives, the pose's
// rotations, measurement and pose input errors.

#include "common/error.hpp"
#include "contact/body_files.hpp"
#include "contact/mannequin.hpp"
#include "contact/mannequin_surface.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <queue>
#include <random>

namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;
using sartor::MannequinModel;
using sartor::Measurements;

const std::string data = SARTOR_BODY_TEST_DATA_DIR;

const MannequinModel& sized(const std::string& set) {
  static std::map<std::string, MannequinModel> models;
  auto found = models.find(set);
  if (found == models.end()) {
    const Measurements m =
        set == "default"
            ? Measurements{}
            : sartor::read_measurement_file(data + "/measurements_" + set + ".json").measurements;
    found = models.emplace(set, MannequinModel(m)).first;
  }
  return found->second;
}

// Perimeter of the convex hull of 2D points (gift wrapping).
double hull_perimeter(std::vector<Vector2d> points) {
  const auto start = std::min_element(points.begin(), points.end(), [](auto& a, auto& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  std::vector<Vector2d> hull{*start};
  while (true) {
    Vector2d next = points[0] == hull.back() ? points[1] : points[0];
    for (const Vector2d& p : points) {
      const Vector2d a = next - hull.back(), b = p - hull.back();
      const double cross = a.x() * b.y() - a.y() * b.x();
      if (cross < 0.0 || (cross == 0.0 && b.norm() > a.norm())) next = p;
    }
    if (next == hull.front() || hull.size() > points.size()) break;
    hull.push_back(next);
  }
  double perimeter = 0.0;
  for (std::size_t i = 0; i < hull.size(); ++i)
    perimeter += (hull[(i + 1) % hull.size()] - hull[i]).norm();
  return perimeter;
}

// A tape measure round the piece of the horizontal section at height z that
// contains `seed`: the section's cells connected to the seed on a 3 mm grid,
// their boundary crossings found by bisection on the grid edges, and the
// convex hull of those. mm.
double tape_girth(const MannequinModel& body, double z, const Vector2d& seed) {
  const double h = 0.003;
  const int n = 200; // a 0.6 m square around the seed
  const auto at = [&](int i, int j) {
    return Vector3d(seed.x() + (i - n / 2) * h, seed.y() + (j - n / 2) * h, z);
  };
  std::vector<char> inside(n * n), reached(n * n, 0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      inside[j * n + i] = body.field(at(i, j)) < 0.0;
  EXPECT_TRUE(inside[(n / 2) * n + n / 2]) << "the seed is outside the body at z = " << z;
  std::queue<std::pair<int, int>> open;
  open.push({n / 2, n / 2});
  reached[(n / 2) * n + n / 2] = 1;
  std::vector<Vector2d> crossings;
  while (!open.empty()) {
    const auto [i, j] = open.front();
    open.pop();
    for (const auto& [di, dj] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
      const int a = i + di, b = j + dj;
      EXPECT_TRUE(a > 0 && b > 0 && a < n - 1 && b < n - 1) << "the section leaves the window";
      if (inside[b * n + a]) {
        if (!reached[b * n + a]) {
          reached[b * n + a] = 1;
          open.push({a, b});
        }
        continue;
      }
      Vector3d in = at(i, j), out = at(a, b);
      for (int k = 0; k < 30; ++k) {
        const Vector3d middle = 0.5 * (in + out);
        (body.field(middle) < 0.0 ? in : out) = middle;
      }
      crossings.emplace_back(in.x(), in.y());
    }
  }
  return 1e3 * hull_perimeter(crossings);
}

// y of the middle of the body's section on the line x = 0 at height z.
double middle_y(const MannequinModel& body, double x, double z) {
  double lowest = 1.0, highest = -1.0;
  for (double y = -0.3; y <= 0.3; y += 0.001)
    if (body.field({x, y, z}) < 0.0) {
      lowest = std::min(lowest, y);
      highest = std::max(highest, y);
    }
  return 0.5 * (lowest + highest);
}

struct Girth {
  std::string name;
  double z; // m
  double x; // of the seed, m
};

// The levels docs/bodies.md defines, from the requested values alone.
std::vector<Girth> girth_levels(const Measurements& m) {
  const double waist = 1e-3 * m.at("waistToFloor");
  const double hps = waist + 1e-3 * m.at("hpsToWaistBack");
  const double crown = 1e-3 * m.at("height");
  return {{"waist", waist, 0.0},
          {"hips", waist - 1e-3 * m.at("waistToHips"), 0.0},
          {"seat", waist - 1e-3 * m.at("waistToSeat"), 0.0},
          {"chest", waist + 190.0 / 350.0 * (hps - waist), 0.0},
          {"neck", hps + 60.0 / 320.0 * (crown - hps), 0.0},
          {"knee", waist - 1e-3 * m.at("waistToKnee"), 1.0}};
}

class SizedMannequin : public ::testing::TestWithParam<std::string> {};

TEST_P(SizedMannequin, GirthsTakenBySlicingMatchTheRequestWithinOnePercent) {
  const MannequinModel& body = sized(GetParam());
  const Measurements& m = body.requested();
  for (const Girth& g : girth_levels(m)) {
    double x = 0.0;
    if (g.x > 0.0) { // the left leg: the middle of its section on the line y = 0
      double first = 1.0, last = 0.0;
      for (double s = 0.01; s < 0.4; s += 0.001)
        if (body.field({s, 0.0, g.z}) < 0.0) {
          first = std::min(first, s);
          last = std::max(last, s);
        }
      x = 0.5 * (first + last);
    }
    const double girth = tape_girth(body, g.z, {x, middle_y(body, x, g.z)});
    EXPECT_NEAR(girth / m.at(g.name), 1.0, 0.01)
        << GetParam() << ": " << g.name << " " << girth << " mm, asked " << m.at(g.name);
  }
}

TEST_P(SizedMannequin, HeightAndCrotchMatchTheRequestWithinOnePercent) {
  const MannequinModel& body = sized(GetParam());
  const Measurements& m = body.requested();
  // The crown: the highest point of the body over the head's axis.
  double crown = 0.0;
  for (double y = -0.1; y <= 0.1; y += 0.002)
    for (double z = 1.2; z < 2.4; z += 0.001)
      if (body.field({0.0, y, z}) < 0.0) crown = std::max(crown, z);
  EXPECT_NEAR(1e3 * crown / m.at("height"), 1.0, 0.01) << GetParam();
  // The crotch: the lowest point inside the body between the legs (x = 0).
  double crotch = 2.0;
  for (double y = -0.1; y <= 0.15; y += 0.002)
    for (double z = 0.3; z < 1.2; z += 0.001)
      if (body.field({0.0, y, z}) < 0.0) {
        crotch = std::min(crotch, z);
        break;
      }
  EXPECT_NEAR(1e3 * crotch / m.at("inseam"), 1.0, 0.01) << GetParam();
}

// TAGCON wraps its cylinders round these bones (garment/tagcon.cpp).
TEST_P(SizedMannequin, SkeletonFollowsTheMeasurements) {
  const MannequinModel& body = sized(GetParam());
  const Measurements& m = body.requested();
  sartor::Mannequin skeleton_only;
  skeleton_only.skeleton = body.skeleton();
  EXPECT_NEAR(skeleton_only.bone("torso").start.z(), 1e-3 * m.at("waistToFloor"), 1e-3);
  const Vector3d shoulder_l = skeleton_only.bone("upper_arm_l").start;
  const Vector3d shoulder_r = skeleton_only.bone("upper_arm_r").start;
  EXPECT_NEAR((shoulder_l - shoulder_r).norm(), 1e-3 * m.at("shoulderToShoulder"), 1e-3);
  const double arm =
      (skeleton_only.bone("upper_arm_l").end - shoulder_l).norm() +
      (skeleton_only.bone("forearm_l").end - skeleton_only.bone("forearm_l").start).norm();
  EXPECT_NEAR(arm, 1e-3 * m.at("shoulderToWrist"), 1e-3);
  for (const sartor::Bone& bone : skeleton_only.skeleton)
    EXPECT_LT(body.field(0.5 * (bone.start + bone.end)), 0.0) << bone.name << " outside";
}

INSTANTIATE_TEST_SUITE_P(MeasurementSets, SizedMannequin,
                         ::testing::Values("default", "small", "large"));

// Points within 2 cm of the surface, by rejection in the body's box.
std::vector<Vector3d> near_surface(const MannequinModel& body, std::size_t count) {
  std::mt19937 random(5);
  std::uniform_real_distribution<double> x(-0.9, 0.9), y(-0.7, 0.7), z(0.0, 2.0);
  std::vector<Vector3d> points;
  while (points.size() < count) {
    const Vector3d p(x(random), y(random), z(random));
    if (std::abs(body.field(p)) < 0.02) points.push_back(p);
  }
  return points;
}

void expect_derivatives_match_finite_differences(const MannequinModel& body) {
  const double step = 1e-6;
  for (const Vector3d& p : near_surface(body, 1500)) {
    const sartor::MannequinFieldValue at = body.field_derivatives(p);
    for (int d = 0; d < 3; ++d) {
      const Vector3d e = step * Vector3d::Unit(d);
      const sartor::MannequinFieldValue plus = body.field_derivatives(p + e);
      const sartor::MannequinFieldValue minus = body.field_derivatives(p - e);
      ASSERT_NEAR((plus.value - minus.value) / (2 * step), at.gradient[d], 1e-6)
          << "at " << p.transpose() << ", direction " << d;
      if ((plus.hessian - minus.hessian).norm() > 1e-3 * (1 + at.hessian.norm())) continue;
      const Vector3d column = (plus.gradient - minus.gradient) / (2 * step);
      ASSERT_LT((column - at.hessian.col(d)).norm(), 1e-5 * (1.0 + at.hessian.norm()))
          << "at " << p.transpose() << ", direction " << d;
    }
  }
}

void expect_slope_bound_holds(const MannequinModel& body) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> x(-3.0, 3.0), y(-3.0, 3.0), z(-2.0, 4.0);
  double outside = 0.0;
  for (int i = 0; i < 100000; ++i) {
    const sartor::MannequinFieldValue f =
        body.field_derivatives(Vector3d(x(random), y(random), z(random)));
    if (f.value > 0.0) outside = std::max(outside, f.gradient.norm());
  }
  EXPECT_LT(outside, body.slope_bound());
}

sartor::Pose sitting() {
  return sartor::parse_pose("hip_l:90,hip_r:90,knee_l:90,knee_r:90,elbow_l:60,shoulder_r:30,"
                            "neck:20");
}

TEST(SizedMannequinSurface, DerivativesMatchFiniteDifferencesSizedAndPosed) {
  expect_derivatives_match_finite_differences(sized("small"));
  expect_derivatives_match_finite_differences(sized("large").posed(sitting()));
}

TEST(SizedMannequinSurface, SlopeBoundHoldsSizedAndPosed) {
  expect_slope_bound_holds(sized("large"));
  expect_slope_bound_holds(sized("small").posed(sitting()));
}

TEST(SizedMannequinSurface, DefaultValuesGiveTheBuiltInMannequinExactly) {
  const MannequinModel model(sartor::default_measurements());
  EXPECT_TRUE(model.is_default());
  for (const Vector3d& p : near_surface(MannequinModel(), 200))
    ASSERT_EQ(model.field(p), sartor::mannequin_field(p));
}

// --- poses -------------------------------------------------------------------

const sartor::Bone& bone(const std::vector<sartor::Bone>& bones, const std::string& name) {
  return *std::find_if(bones.begin(), bones.end(),
                       [&](const sartor::Bone& b) { return b.name == name; });
}

TEST(PosedMannequin, LimbLengthsArePreserved) {
  const std::vector<sartor::Bone> rest = sized("large").skeleton();
  const std::vector<sartor::Bone> posed = sized("large").posed(sitting()).skeleton();
  for (const std::string name : {"upper_arm_l", "forearm_l", "hand_l", "thigh_l", "shin_l",
                                 "foot_l", "thigh_r", "shin_r", "neck", "head"}) {
    const double before = (bone(rest, name).end - bone(rest, name).start).norm();
    const double after = (bone(posed, name).end - bone(posed, name).start).norm();
    EXPECT_NEAR(after, before, 1e-9) << name;
  }
}

// Rodrigues' formula, written here.
Vector3d rotated(const Vector3d& v, const Vector3d& unit_axis, double radians) {
  return std::cos(radians) * v + std::sin(radians) * unit_axis.cross(v) +
         (1.0 - std::cos(radians)) * unit_axis.dot(v) * unit_axis;
}

TEST(PosedMannequin, KneeBentNinetyDegreesPutsTheAnkleBehindTheKnee) {
  const MannequinModel& body = sized("default");
  const MannequinModel bent = body.posed(sartor::parse_pose("knee_l:90"));
  // bone() returns a reference into the skeleton: keep it alive.
  const std::vector<sartor::Bone> rest_skeleton = body.skeleton();
  const sartor::Bone& shin = bone(rest_skeleton, "shin_l");
  const Vector3d lower_leg = shin.end - shin.start;
  // Flexion about the knee's transverse axis, the foot swinging backwards (+y).
  const Vector3d axis = lower_leg.cross(Vector3d::UnitY()).normalized();
  const Vector3d expected = shin.start + rotated(lower_leg, axis, M_PI / 2);
  const std::vector<sartor::Bone> bent_skeleton = bent.skeleton();
  const sartor::Bone& posed_shin = bone(bent_skeleton, "shin_l");
  EXPECT_LT((posed_shin.start - shin.start).norm(), 1e-12);
  EXPECT_LT((posed_shin.end - expected).norm(), 1e-9) << posed_shin.end.transpose();
  EXPECT_GT(posed_shin.end.y() - shin.start.y(), 0.95 * lower_leg.norm()); // behind the knee
  // The shin's flesh moved with it: the field near mid-shin is the rest one
  // rotated (away from the knee's fillet and the other leg).
  const Vector3d mid = shin.start + 0.6 * lower_leg;
  for (const Vector3d& offset :
       {Vector3d(0.06, 0, 0), Vector3d(0, -0.07, 0), Vector3d(0.0, 0.0, 0.0)})
    EXPECT_NEAR(bent.field(shin.start + rotated(mid + offset - shin.start, axis, M_PI / 2)),
                body.field(mid + offset), 1e-9);
  expect_derivatives_match_finite_differences(bent);
}

TEST(PosedMannequin, PoseHistoryInterpolatesKeyframes) {
  const sartor::contact::PoseHistory history =
      sartor::contact::parse_pose_history("0:;100:knee_l:90,hip_l:60;300:");
  EXPECT_EQ(history.at(-5).angle("knee_l"), 0.0);
  EXPECT_NEAR(history.at(50).angle("knee_l"), 45.0, 1e-12);
  EXPECT_NEAR(history.at(200).angle("hip_l"), 30.0, 1e-12);
  EXPECT_EQ(history.at(400).angle("hip_l"), 0.0);
  const auto shape = sartor::contact::make_posed_mannequin_shape(sized("default"), history.at(50));
  const Vector3d p(0.12, 0.25, 0.3);
  EXPECT_NEAR(shape->query(p).distance,
              sized("default").posed(sartor::parse_pose("knee_l:45,hip_l:30")).field(p), 1e-12);
  EXPECT_THROW(sartor::contact::parse_pose_history("10:;5:knee_l:10"), sartor::InputError);
}

// --- input errors ------------------------------------------------------------

std::string write_file(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

void expect_error(const std::function<void()>& run, const std::string& fragment) {
  try {
    run();
    ADD_FAILURE() << "no error; expected one containing '" << fragment << "'";
  } catch (const sartor::InputError& error) {
    EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos) << error.what();
  }
}

TEST(MeasurementFile, NamesItsDefaultsAndRejectsBadInput) {
  const sartor::MeasurementFile file =
      sartor::read_measurement_file(data + "/measurements_large.json");
  EXPECT_EQ(file.defaulted, std::vector<std::string>{"waistToKnee"});
  EXPECT_EQ(file.measurements.at("seat"), 1120.0);
  const auto read = [](const std::string& text) {
    return [text] { sartor::read_measurement_file(write_file("m.json", text)); };
  };
  expect_error(read(R"({"units": "mm", "measurements": {"waist": 700, "tummy": 3}})"),
               "measurements.tummy: unknown measurement name");
  expect_error(read(R"({"units": "cm", "measurements": {"waist": 70}})"), "\"units\" must be");
  expect_error(read(R"({"units": "mm", "measurements": {"waist": -7}})"),
               "measurements.waist must be a positive number");
  expect_error(
      [] {
        MannequinModel({{"waist", 3000.0}});
      },
      "measurement 'waist' = 3000 mm is implausible");
  expect_error([] { MannequinModel({{"inseam", 1000.0}}); }, "rise");
  expect_error([] { sartor::parse_pose("knee_l:200"); }, "knee_l = 200 degrees is outside");
  expect_error([] { sartor::parse_pose("ankle_l:20"); }, "unknown joint 'ankle_l'");
  expect_error([] { sartor::parse_pose("knee_l=20"); }, "is not JOINT:DEGREES");
}

} // namespace
