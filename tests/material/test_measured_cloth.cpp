// Measured fabrics (Wang, Ramamoorthi & O'Brien 2011, ARCSim's JSON layout):
// the stretching stiffness, the converted tension-strain and
// moment-curvature curves and the file readers, against evaluations of the
// model's definition written here (a table made up for the test).

#include "common/error.hpp"
#include "material/fabric.hpp"
#include "material/measured_cloth.hpp"
#include "tests/support/scratch_folder.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <fstream>

namespace sartor {
namespace {

constexpr double pi = 3.14159265358979323846;

StretchingTable made_up_stretching() {
  StretchingTable t;
  t.rows = {{{2500, 300, 2000, 100},
             {20000, 500, 16000, 300},
             {15000, 450, 12000, 400},
             {8000, 400, 7000, 600},
             {14000, 450, 13000, 400},
             {18000, 500, 17000, 300}}};
  return t;
}

BendingTable made_up_bending() {
  BendingTable t;
  t.rows = {{{4.0e-6, 4.6e-6, 5.2e-6, 5.8e-6, 6.4e-6},
             {3.5e-6, 4.0e-6, 4.5e-6, 5.0e-6, 5.5e-6},
             {5.0e-6, 5.8e-6, 6.6e-6, 7.4e-6, 8.2e-6}}};
  return t;
}

// The model's stiffness by its definition: the largest eigenvalue of
// C = I + 2G and its direction's angle to the warp (Eigen's solver, the
// angle by acos), the strain weight 6 (w - 1), the angle rows every 22.5
// degrees, doubled.
Eigen::Vector4d definition(const StretchingTable& t, const Eigen::Matrix2d& green) {
  const Eigen::Matrix2d c = Eigen::Matrix2d::Identity() + 2.0 * green;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(c);
  const double largest = eigen.eigenvalues()[1];
  const double angle = std::acos(std::min(1.0, std::abs(eigen.eigenvectors().col(1)[0])));
  const double s = std::clamp(6.0 * (std::sqrt(largest) - 1.0), 0.0, 1.0);
  const double position = angle / (pi / 8.0);
  const int low = std::min(int(position), 3);
  const double f = position - low;
  Eigen::Vector4d k;
  for (int i = 0; i < 4; ++i) {
    const double along = (1 - f) * t.rows[std::size_t(1 + low)][std::size_t(i)] +
                         f * t.rows[std::size_t(2 + low)][std::size_t(i)];
    k[i] = 2.0 * std::max(0.0, (1 - s) * t.rows[0][std::size_t(i)] + s * along);
  }
  return k;
}

TEST(MeasuredStretching, StiffnessFollowsTheDefinition) {
  const StretchingTable t = made_up_stretching();
  // Warp and weft axes, away from the eigenvalue tie at G = 0.
  for (const double e : {0.01, 0.05, 0.2}) {
    Eigen::Matrix2d warp, weft;
    warp << e, 0, 0, 0;
    weft << 0, 0, 0, e;
    EXPECT_LT((table_stiffness(t, e, 0, 0) - definition(t, warp)).norm(), 1e-9);
    EXPECT_LT((table_stiffness(t, 0, e, 0) - definition(t, weft)).norm(), 1e-9);
  }
  // Principal direction at 30 degrees: between the 22.5 and 45 degree rows.
  const double angle = pi / 6.0, stretch = 1.1;
  Eigen::Matrix2d f = Eigen::Matrix2d::Identity();
  const Eigen::Vector2d n(std::cos(angle), std::sin(angle));
  f += (stretch - 1.0) * n * n.transpose();
  const Eigen::Matrix2d g = 0.5 * (f.transpose() * f - Eigen::Matrix2d::Identity());
  EXPECT_LT((table_stiffness(t, g(0, 0), g(1, 1), g(0, 1)) - definition(t, g)).norm(), 1e-8);
  // By hand: s = 0.6, f = 1/3 between rows 2 and 3, warp component.
  const double by_hand = 2.0 * (0.4 * 2500 + 0.6 * (2.0 / 3.0 * 15000 + 1.0 / 3.0 * 8000));
  EXPECT_NEAR(table_stiffness(t, g(0, 0), g(1, 1), g(0, 1))[0], by_hand, 1e-6 * by_hand);
}

TEST(MeasuredStretching, EnergyDerivativesMatchFiniteDifferences) {
  const MeasuredStretching table(made_up_stretching());
  for (const Eigen::Vector3d& g :
       {Eigen::Vector3d(0.031, -0.012, 0.021), Eigen::Vector3d(0.12, 0.043, -0.052),
        Eigen::Vector3d(-0.07, 0.2, 0.008)}) {
    const StrainEnergy w = table.energy(g[0], g[1], g[2]);
    const double h = 1e-7; // far inside a grid cell (1/30)
    for (int m = 0; m < 3; ++m) {
      Eigen::Vector3d plus = g, minus = g;
      plus[m] += h;
      minus[m] -= h;
      const StrainEnergy wp = table.energy(plus[0], plus[1], plus[2]);
      const StrainEnergy wm = table.energy(minus[0], minus[1], minus[2]);
      const double scale = w.gradient.cwiseAbs().maxCoeff();
      EXPECT_NEAR((wp.energy - wm.energy) / (2 * h), w.gradient[m], 1e-6 * scale);
      const Eigen::Vector3d column = (wp.gradient - wm.gradient) / (2 * h);
      EXPECT_LT((column - w.hessian.col(m)).cwiseAbs().maxCoeff(),
                1e-5 * w.hessian.cwiseAbs().maxCoeff());
    }
  }
}

// The stress (the energy's gradient) is continuous across a face of the grid
// and across G01 = 0, where |G01| folds the grid: the stiffness has no kink
// there. (Trilinear on the same nodes, the gradient jumps at both, by about
// q dk/dg, and Newton's residual stalls at that size.)
TEST(MeasuredStretching, StressIsContinuousAcrossGridFacesAndZeroShear) {
  const MeasuredStretching table(made_up_stretching());
  const double face = MeasuredStretching::lowest + 9 * MeasuredStretching::spacing; // node 9
  const double h = 1e-9;
  for (const Eigen::Vector3d& g :
       {Eigen::Vector3d(face, 0.04, 0.013), Eigen::Vector3d(0.05, face, 0.021),
        Eigen::Vector3d(0.06, 0.02, 0.0), Eigen::Vector3d(0.07, -0.01, 2.0 / 30.0)}) {
    for (int m = 0; m < 3; ++m) {
      Eigen::Vector3d below = g, above = g;
      below[m] -= h;
      above[m] += h;
      const StrainEnergy wb = table.energy(below[0], below[1], below[2]);
      const StrainEnergy wa = table.energy(above[0], above[1], above[2]);
      const double scale = wa.gradient.cwiseAbs().maxCoeff();
      EXPECT_LT((wa.gradient - wb.gradient).cwiseAbs().maxCoeff(), 1e-6 * scale)
          << g.transpose() << ", axis " << m;
    }
  }
  // The energy is even in G01.
  EXPECT_DOUBLE_EQ(table.energy(0.05, 0.02, -0.013).energy, table.energy(0.05, 0.02, 0.013).energy);
}

TEST(MeasuredCurves, TensionCurveIsTheTablesStressAlongWarpAndWeft) {
  const StretchingTable t = made_up_stretching();
  const TensionCurve warp_green = table_tension_curve(t, false, true, "test");
  const TensionCurve weft_bw = table_tension_curve(t, true, false, "test");
  for (const double principal : {4.0 / 48.0, 7.0 / 48.0, 0.3}) {
    const double s = std::min(1.0, 6.0 * principal);
    const double green = 0.5 * ((1 + principal) * (1 + principal) - 1.0);
    const double k_warp = 2.0 * ((1 - s) * 2500 + s * 20000);
    const double k_weft = 2.0 * ((1 - s) * 2000 + s * 17000);
    EXPECT_NEAR(warp_green.tension(green), k_warp * green, 1e-9 * k_warp * green) << principal;
    if (principal < 1.0 / 6.0) { // the Baraff-Witkin curve is exact at its samples
      EXPECT_NEAR(weft_bw.tension(principal), k_weft * green * (1 + principal),
                  1e-9 * k_weft * green)
          << principal;
    }
  }
}

TEST(MeasuredCurves, MomentCurveGivesTheTablesMomentAtItsCurvatures) {
  const BendingTable t = made_up_bending();
  const MomentCurve warp = table_moment_curve(t, pi / 2.0, "test");
  const MomentCurve weft = table_moment_curve(t, 0.0, "test");
  for (int j = 1; j < 5; ++j) {
    const double kappa = 5.0 * j;
    EXPECT_NEAR(warp.moment(kappa), t.rows[2][std::size_t(j)] * kappa, 1e-12 * kappa);
    EXPECT_NEAR(weft.moment(-kappa), -t.rows[0][std::size_t(j)] * kappa, 1e-12 * kappa);
  }
  // Between columns ke is linear: at 2.5 1/m the mean of the first two.
  EXPECT_NEAR(warp.moment(2.5), 0.5 * (5.0e-6 + 5.8e-6) * 2.5, 1e-15);
  // Beyond 20 1/m the secant rigidity stays at the last column's.
  EXPECT_NEAR(warp.moment(35.0), 8.2e-6 * 35.0, 1e-12);
  // Energy is the integral of the moment: trapezoids on the pieces through
  // 1.25 1/m (ke = 4.15e-6 N m) and 2.5 1/m (4.3e-6 N m).
  const double m1 = 4.15e-6 * 1.25, m2 = 4.3e-6 * 2.5;
  EXPECT_NEAR(weft.energy_density(2.5), 0.5 * 1.25 * m1 + 0.5 * 1.25 * (m1 + m2), 1e-18);
  // Fold line at 22.5 degrees: halfway between the 0 and 45 degree rows.
  EXPECT_NEAR(table_bending_rigidity(t, 10.0, pi / 8.0), 0.5 * (5.2e-6 + 4.5e-6), 1e-15);
}

// Measured tables may soften faster than 1/curvature (the 11oz denim of
// Wang et al. 2011, warp: ke about 62 then 20 uN m at 15 and 20 1/m): the
// moment ke * kappa falls there, and the curve keeps it.
TEST(MeasuredCurves, SofteningTableGivesAFallingMoment) {
  BendingTable t = made_up_bending();
  t.rows[2] = {64e-6, 60e-6, 61e-6, 62e-6, 20e-6};
  const MomentCurve warp = table_moment_curve(t, pi / 2.0, "denim.json: bending");
  EXPECT_NEAR(warp.moment(15.0), 62e-6 * 15.0, 1e-12);
  EXPECT_NEAR(warp.moment(20.0), 20e-6 * 20.0, 1e-12);
  EXPECT_LT(warp.stiffness(17.0), 0.0);
  EXPECT_GT(warp.stiffness(30.0), 0.0); // beyond the table: ke stays at 20 uN m
  // Energy through the fall: the integral of the moment's pieces (4 per
  // table interval: ke linear in kappa between columns, so the moment is
  // sampled at 16.25, 17.5, 18.75 1/m).
  double energy = warp.energy_density(15.0);
  double kappa = 15.0, moment = 62e-6 * 15.0;
  for (int j = 1; j <= 4; ++j) {
    const double next = 15.0 + 1.25 * j;
    const double next_moment = (62e-6 + (20e-6 - 62e-6) * (next - 15.0) / 5.0) * next;
    energy += 0.5 * (moment + next_moment) * (next - kappa);
    kappa = next;
    moment = next_moment;
  }
  EXPECT_NEAR(warp.energy_density(20.0), energy, 1e-12 * energy);
}

std::string write(const std::string& name, const std::string& text) {
  const auto path = test_support::scratch_folder("sartor_measured_cloth") / name;
  std::ofstream(path) << text;
  return path.string();
}

const char* measured_json = R"({"density": 0.18,
  "stretching": [[2500, 300, 2000, 100], [20000, 500, 16000, 300], [15000, 450, 12000, 400],
                 [8000, 400, 7000, 600], [14000, 450, 13000, 400], [18000, 500, 17000, 300]],
  "bending": [[4.0e-6, 4.6e-6, 5.2e-6, 5.8e-6, 6.4e-6], [3.5e-6, 4.0e-6, 4.5e-6, 5.0e-6, 5.5e-6],
              [5.0e-6, 5.8e-6, 6.6e-6, 7.4e-6, 8.2e-6]]})";

TEST(MeasuredFabricFile, ArcsimLayoutGivesDensityCurvesAndTable) {
  const Fabric fabric = load_measured_fabric(write("cotton.json", measured_json));
  EXPECT_EQ(fabric.name, "cotton");
  EXPECT_DOUBLE_EQ(*fabric.areal_density, 0.18);
  ASSERT_TRUE(fabric.stretching && fabric.bending);
  EXPECT_DOUBLE_EQ(fabric.stretching->table().rows[3][3], 600.0);
  // G g^2 / 2 = k3 G01^2 / 2 with g = 2 G01, k3 = 2 x 100 N/m.
  EXPECT_DOUBLE_EQ(*fabric.shear_modulus, 50.0);
  EXPECT_NEAR(fabric.bending->warp.moment(10.0), 6.6e-5, 1e-15);
  // Twist: D_45 - (D_warp + D_weft) / 4 at 10 1/m.
  EXPECT_NEAR(fabric.bending->twist.moment(10.0), 10.0 * (4.5e-6 - 0.25 * (6.6e-6 + 5.2e-6)),
              1e-15);
  EXPECT_FALSE(fabric.in(Direction::warp).has_creep);
  EXPECT_THROW(fabric.check_creep(), InputError);
  // A measured file as --fabric.
  EXPECT_EQ(resolve_fabrics(write("cotton2.json", measured_json)).size(), 2u);
}

// A bias row below a quarter of warp + weft (Wang et al.'s gray interlock at
// 20 1/m) would need a negative twist rigidity: it is held at 0 there, and a
// warning names the file, the curvatures and the excess of the bias rigidity.
TEST(MeasuredFabricFile, LowBiasRowHoldsTheTwistAtZeroAndWarns) {
  const Fabric fabric = load_measured_fabric(write("interlock.json", R"({"density": 0.19,
  "stretching": [[2500, 300, 2000, 100], [20000, 500, 16000, 300], [15000, 450, 12000, 400],
                 [8000, 400, 7000, 600], [14000, 450, 13000, 400], [18000, 500, 17000, 300]],
  "bending": [[4.0e-6, 4.6e-6, 5.2e-6, 5.8e-6, 6.4e-6], [3.5e-6, 4.0e-6, 4.5e-6, 5.0e-6, 1.0e-6],
              [5.0e-6, 5.8e-6, 6.6e-6, 7.4e-6, 8.2e-6]]})"));
  // At 15 1/m: 5.0 - (5.8 + 7.4) / 4 = 1.7 uN m; at 20 1/m: 1.0 - 3.65 < 0.
  EXPECT_NEAR(fabric.bending->twist.moment(15.0), 15.0 * 1.7e-6, 1e-15);
  EXPECT_EQ(fabric.bending->twist.moment(20.0), 0.0);
  EXPECT_EQ(fabric.bending->twist.moment(30.0), 0.0);
  ASSERT_EQ(fabric.warnings.size(), 1u);
  const std::string& warning = fabric.warnings.front();
  for (const std::string words : {"interlock.json: bending: the 45 degree row", "17.5 to 40 1/m",
                                  "held at 0", "up to 265 % stiffer"})
    EXPECT_NE(warning.find(words), std::string::npos) << warning;
}

TEST(MeasuredFabricFile, BadTablesNameTheFileAndTheKey) {
  const std::string path =
      write("short.json", R"({"density": 0.1, "stretching": [[1, 2, 3, 4]], "bending": []})");
  try {
    load_measured_fabric(path);
    FAIL() << "accepted a one-row stretching table";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find("'stretching' must be 6 rows of 4 numbers"), std::string::npos) << what;
  }
  const std::string colour = write("colour.json", R"({"density": 0.1, "colour": "red"})");
  EXPECT_THROW(load_measured_fabric(colour), InputError);
  EXPECT_THROW(load_measured_fabric(write("broken.json", "{\"density\": ")), InputError);
}

TEST(MeasuredFabricFile, YamlFabricHoldsEverything) {
  write("table.json", measured_json);
  const std::string path = write("full.yaml", R"(name: full
density: 0.2
measured: table.json
bending:
  warp: [[10, 1.0e-5], [20, 3.0e-5]]
  weft: 2.0e-6
warp: {E: 30000, alpha: 0.8, lambda_load: 0.05, lambda_unload: 0.004}
weft: {E: 12000, alpha: 0.5, lambda_load: 0.02, lambda_unload: 0.003}
)");
  const Fabric fabric = load_fabric_file(path);
  EXPECT_DOUBLE_EQ(*fabric.areal_density, 0.2); // the file's own, over the table's
  EXPECT_NO_THROW(fabric.check_creep());
  EXPECT_FALSE(fabric.in(Direction::warp).elastic_given); // from the table
  EXPECT_NEAR(fabric.bending->warp.moment(15.0), 2.0e-5, 1e-15);
  EXPECT_NEAR(fabric.bending->weft.moment(3.0), 6.0e-6, 1e-18);
  EXPECT_NEAR(fabric.bending->twist.initial_rigidity(), 0.25 * (1.0e-6 + 2.0e-6), 1e-18);
  // A direction with neither creep nor an elastic curve needs a table.
  const std::string bare = write("bare.yaml", "warp: {elastic_modulus: 1000}\nweft: {}\n");
  EXPECT_THROW(load_fabric_file(bare), InputError);
}

} // namespace
} // namespace sartor
