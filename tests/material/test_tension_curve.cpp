// Unit tests of the immediate-elastic tension-strain curve: values,
// inverse, derivatives (checked by finite differences), extrapolation and
// input checks.

#include "material/tension_curve.hpp"

#include "common/error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace sartor {
namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr double inf = std::numeric_limits<double>::infinity();

// Slopes 1e4, 4e4, 1e5 N/m; kinks at strains 0.01 and 0.03.
TensionCurve three_segment_curve() {
  return TensionCurve::piecewise({{0.01, 100.0}, {0.03, 900.0}, {0.05, 2900.0}}, "test curve");
}

const std::vector<double> kinks{0.0, 0.01, 0.03, 0.05};

bool near_a_kink(double strain, double distance) {
  for (const double k : kinks) {
    if (std::abs(strain - k) < distance) return true;
  }
  return false;
}

// --- linear ------------------------------------------------------------------

TEST(TensionCurveLinear, TensionStiffnessEnergyAndInverse) {
  const double k = 65200.0;
  const TensionCurve curve = TensionCurve::linear(k, "cotton_twill:warp");
  EXPECT_TRUE(curve.is_linear());
  EXPECT_EQ(curve.initial_modulus(), k);
  for (const double strain : {-0.2, -0.01, 0.0, 1e-6, 0.0376, 0.5, 3.0}) {
    SCOPED_TRACE(strain);
    EXPECT_NEAR(curve.tension(strain), k * strain, 1e-12 * k * std::abs(strain));
    EXPECT_EQ(curve.stiffness(strain), k);
    EXPECT_NEAR(curve.energy_density(strain), 0.5 * k * strain * strain,
                1e-12 * k * strain * strain);
    EXPECT_NEAR(curve.strain_at_tension(k * strain), strain, 1e-14 * std::abs(strain));
  }
  EXPECT_EQ(curve.tension(0.0), 0.0);
  EXPECT_EQ(curve.energy_density(0.0), 0.0);
  EXPECT_EQ(curve.strain_at_tension(0.0), 0.0);
}

TEST(TensionCurveLinear, RejectsNonPositiveOrNonFiniteModulus) {
  for (const double bad : {0.0, -1.0, nan, inf}) {
    SCOPED_TRACE(bad);
    try {
      (void)TensionCurve::linear(bad, "silk:weft");
      ADD_FAILURE() << "accepted modulus " << bad;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("silk:weft"), std::string::npos) << what;
      EXPECT_NE(what.find("elastic modulus"), std::string::npos) << what;
    }
  }
}

// --- piecewise ---------------------------------------------------------------

TEST(TensionCurvePiecewise, PassesThroughItsPointsAndInterpolatesLinearly) {
  const TensionCurve curve = three_segment_curve();
  EXPECT_FALSE(curve.is_linear());
  EXPECT_EQ(curve.initial_modulus(), 1e4);
  ASSERT_EQ(curve.points().size(), 4u);
  EXPECT_EQ(curve.points().front().strain, 0.0);
  EXPECT_EQ(curve.points().front().tension, 0.0);
  EXPECT_NEAR(curve.tension(0.01), 100.0, 1e-12);
  EXPECT_NEAR(curve.tension(0.03), 900.0, 1e-12);
  EXPECT_NEAR(curve.tension(0.05), 2900.0, 1e-12);
  EXPECT_NEAR(curve.tension(0.005), 50.0, 1e-12);
  EXPECT_NEAR(curve.tension(0.02), 500.0, 1e-12);
  EXPECT_NEAR(curve.tension(0.04), 1900.0, 1e-12);
  EXPECT_NEAR(curve.stiffness(0.005), 1e4, 1e-8);
  EXPECT_NEAR(curve.stiffness(0.02), 4e4, 1e-8);
  EXPECT_NEAR(curve.stiffness(0.04), 1e5, 1e-8);
}

TEST(TensionCurvePiecewise, ExplicitOriginGivesTheSameCurve) {
  const TensionCurve implied = three_segment_curve();
  const TensionCurve given = TensionCurve::piecewise(
      {{0.0, 0.0}, {0.01, 100.0}, {0.03, 900.0}, {0.05, 2900.0}}, "test curve");
  ASSERT_EQ(given.points().size(), implied.points().size());
  for (const double strain : {-0.01, 0.005, 0.02, 0.04, 0.08}) {
    EXPECT_EQ(given.tension(strain), implied.tension(strain));
    EXPECT_EQ(given.energy_density(strain), implied.energy_density(strain));
  }
}

TEST(TensionCurvePiecewise, EnergyAtPointsIsTrapezoidSum) {
  const TensionCurve curve = three_segment_curve();
  const double at_1 = 0.5 * 100.0 * 0.01;
  const double at_2 = at_1 + 0.5 * (100.0 + 900.0) * 0.02;
  const double at_3 = at_2 + 0.5 * (900.0 + 2900.0) * 0.02;
  EXPECT_NEAR(curve.energy_density(0.01), at_1, 1e-12);
  EXPECT_NEAR(curve.energy_density(0.03), at_2, 1e-12);
  EXPECT_NEAR(curve.energy_density(0.05), at_3, 1e-12);
  // Beyond the last point: the last segment extended, 2900 + 1e5 (e - 0.05).
  const double d = 0.03;
  EXPECT_NEAR(curve.energy_density(0.05 + d), at_3 + 2900.0 * d + 0.5 * 1e5 * d * d, 1e-10);
}

TEST(TensionCurvePiecewise, ExtrapolatesLastSegmentBeyondLastPoint) {
  const TensionCurve curve = three_segment_curve();
  for (const double strain : {0.06, 0.1, 0.5}) {
    SCOPED_TRACE(strain);
    EXPECT_NEAR(curve.tension(strain), 2900.0 + 1e5 * (strain - 0.05), 1e-9);
    EXPECT_NEAR(curve.stiffness(strain), 1e5, 1e-6);
    EXPECT_NEAR(curve.strain_at_tension(2900.0 + 1e5 * (strain - 0.05)), strain, 1e-14);
  }
}

TEST(TensionCurvePiecewise, ExtendsFirstSegmentIntoCompression) {
  const TensionCurve curve = three_segment_curve();
  for (const double strain : {-1e-4, -0.01, -0.2}) {
    SCOPED_TRACE(strain);
    EXPECT_NEAR(curve.tension(strain), 1e4 * strain, 1e-10);
    EXPECT_NEAR(curve.stiffness(strain), 1e4, 1e-8);
    EXPECT_NEAR(curve.energy_density(strain), 0.5 * 1e4 * strain * strain, 1e-10);
    EXPECT_NEAR(curve.strain_at_tension(1e4 * strain), strain, 1e-15);
  }
}

TEST(TensionCurvePiecewise, StrainAtTensionInvertsTension) {
  const TensionCurve curve = three_segment_curve();
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> strains(-0.05, 0.2);
  std::uniform_real_distribution<double> tensions(-500.0, 20000.0);
  for (int i = 0; i < 1000; ++i) {
    const double strain = strains(rng);
    EXPECT_NEAR(curve.strain_at_tension(curve.tension(strain)), strain, 1e-14) << strain;
    const double tension = tensions(rng);
    EXPECT_NEAR(curve.tension(curve.strain_at_tension(tension)), tension,
                1e-12 * std::max(1.0, std::abs(tension)))
        << tension;
  }
  // At the points themselves.
  for (const CurvePoint& p : curve.points()) {
    EXPECT_NEAR(curve.strain_at_tension(p.tension), p.strain, 1e-15);
  }
}

TEST(TensionCurvePiecewise, StiffnessIsFiniteDifferenceOfTension) {
  const TensionCurve curve = three_segment_curve();
  const double h = 1e-6;
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> strains(-0.05, 0.2);
  int checked = 0;
  while (checked < 500) {
    const double strain = strains(rng);
    if (near_a_kink(strain, 2.0 * h)) continue;
    ++checked;
    const double fd = (curve.tension(strain + h) - curve.tension(strain - h)) / (2.0 * h);
    EXPECT_NEAR(curve.stiffness(strain), fd, 1e-6 * curve.stiffness(strain)) << strain;
  }
}

TEST(TensionCurvePiecewise, TensionIsFiniteDifferenceOfEnergy) {
  const TensionCurve curve = three_segment_curve();
  const double h = 1e-6;
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> strains(-0.05, 0.2);
  int checked = 0;
  while (checked < 500) {
    const double strain = strains(rng);
    if (near_a_kink(strain, 2.0 * h)) continue;
    ++checked;
    const double fd =
        (curve.energy_density(strain + h) - curve.energy_density(strain - h)) / (2.0 * h);
    EXPECT_NEAR(curve.tension(strain), fd, 1e-6 * std::max(1.0, std::abs(fd))) << strain;
  }
}

TEST(TensionCurvePiecewise, TensionAndEnergyContinuousAtKinks) {
  const TensionCurve curve = three_segment_curve();
  for (const double kink : {0.01, 0.03, 0.05}) {
    const double below = std::nextafter(kink, 0.0);
    const double above = std::nextafter(kink, 1.0);
    EXPECT_NEAR(curve.tension(below), curve.tension(above), 1e-9) << kink;
    EXPECT_NEAR(curve.energy_density(below), curve.energy_density(above), 1e-12) << kink;
  }
}

// --- invalid curves ------------------------------------------------------------

void expect_rejected(const std::vector<CurvePoint>& points, const std::vector<std::string>& words) {
  try {
    (void)TensionCurve::piecewise(points, "fabric.yaml:7: denim:warp");
    ADD_FAILURE() << "accepted an invalid curve";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("fabric.yaml:7: denim:warp"), std::string::npos) << what;
    for (const auto& word : words)
      EXPECT_NE(what.find(word), std::string::npos) << what;
  }
}

TEST(TensionCurveInvalid, EmptyOrOriginOnlyThrows) {
  expect_rejected({}, {"at least one point"});
  expect_rejected({{0.0, 0.0}}, {"at least one point"});
}

TEST(TensionCurveInvalid, NonIncreasingStrainNamesThePoint) {
  expect_rejected({{0.01, 100.0}, {0.01, 200.0}}, {"point 2", "strain 0.01", "tension 200"});
  expect_rejected({{0.02, 100.0}, {0.015, 200.0}}, {"point 2", "strain 0.015", "tension 200"});
  expect_rejected({{-0.01, 100.0}}, {"point 1", "strain -0.01"});
}

TEST(TensionCurveInvalid, NonIncreasingTensionNamesThePoint) {
  expect_rejected({{0.01, 100.0}, {0.02, 100.0}}, {"point 2", "strain 0.02", "tension 100"});
  expect_rejected({{0.01, 100.0}, {0.02, 50.0}, {0.03, 400.0}},
                  {"point 2", "strain 0.02", "tension 50"});
  expect_rejected({{0.01, -5.0}}, {"point 1", "tension -5"});
}

TEST(TensionCurveInvalid, NonFinitePointNamesThePoint) {
  expect_rejected({{0.01, 100.0}, {nan, 200.0}}, {"point 2", "not finite"});
  expect_rejected({{0.01, 100.0}, {0.02, inf}}, {"point 2", "not finite"});
  expect_rejected({{nan, nan}}, {"point 1", "not finite"});
}

// A measured softening: the ordinate falls on one segment; the energy is
// still the integral (trapezoids written here), the stiffness there negative.
TEST(TensionCurveSoftening, FallingSegmentKeepsTheIntegralAsEnergy) {
  CurveRules rules;
  rules.softening = true;
  const TensionCurve curve =
      TensionCurve::piecewise({{1.0, 10.0}, {2.0, 4.0}, {4.0, 8.0}}, "table", rules);
  EXPECT_DOUBLE_EQ(curve.stiffness(1.5), -6.0);
  EXPECT_DOUBLE_EQ(curve.tension(1.5), 7.0);
  EXPECT_NEAR(curve.energy_density(3.0), 0.5 * 10.0 + 0.5 * (10.0 + 4.0) + 0.5 * (4.0 + 6.0),
              1e-12);
  EXPECT_DOUBLE_EQ(curve.tension(5.0), 10.0); // the last segment goes on rising
}

TEST(TensionCurveSoftening, OrdinatesMustStayPositiveAndTheLastSegmentRise) {
  CurveRules rules{"moment-curvature curve", "curvature", "moment", "N", true};
  const auto rejected = [&](const std::vector<CurvePoint>& points, const std::string& words) {
    try {
      (void)TensionCurve::piecewise(points, "denim.json: bending", rules);
      ADD_FAILURE() << "accepted an invalid curve";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("denim.json: bending: moment-curvature curve: " + words),
                std::string::npos)
          << what;
    }
  };
  rejected({{1.0, 10.0}, {2.0, -1.0}, {3.0, 5.0}},
           "point 2 (curvature 2, moment -1 N): moments must be >= 0");
  rejected({{1.0, 10.0}, {2.0, 12.0}, {3.0, 11.0}},
           "point 3 (curvature 3, moment 11 N): the last segment");
  // A zero moment (a rigidity held at 0) and a flat last segment are kept.
  const TensionCurve held =
      TensionCurve::piecewise({{1.0, 10.0}, {2.0, 0.0}, {3.0, 0.0}}, "table", rules);
  EXPECT_DOUBLE_EQ(held.energy_density(5.0), 10.0);
}

} // namespace
} // namespace sartor
