// Wear and take-off (solvers/wear.hpp): a square sheet held in a frame (its
// border), pushed up 2 cm by a ball (a knee) over the first 5 s and held
// there, then freed (the ball removed) and recovering. The creep law says
// what the bagging must do, reasoned here without the code under test:
//  * the permanent strain grows towards alpha sigma / E at rate lambda_load
//    and never shrinks, so a longer wear, a faster lambda_load or a smaller
//    creep modulus E (the elastic stiffness held) leaves more permanent
//    elongation, and the freed sheet, longer than its frame, bulges more;
//  * with alpha = 0 and a fast lambda_unload the viscoelastic strain decays
//    to what the freed sheet's tension sustains (none: it is flat again) and
//    nothing remains: no bulge;
//  * the staggered coupling lags the tension by one step: the bagging height
//    converges at first order in the time step; the monolithic one at
//    second, to the same height.

#include "common/error.hpp"
#include "contact/analytic_shapes.hpp"
#include "contact/body.hpp"
#include "mesh/generators.hpp"
#include "solvers/posed_mannequin.hpp"
#include "solvers/wear.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <vector>

namespace sartor {
namespace {

constexpr double side = 0.2;            // m
constexpr double elastic_modulus = 6e4; // N/m, the same for every fabric here
constexpr double ball_radius = 0.06;    // m
constexpr double push = 0.02;           // m the ball rises above the frame's plane
constexpr double push_time = 5.0;       // s

struct KneeCase {
  CreepParameters creep{32600, 0.9, 0.0886, 0.002}; // cotton twill's warp (Table 5.1)
  std::vector<double> take_off_times{20.0};
  double recovery_time = 60.0;
  double fixed_step = 0.0; // s; 0: adaptive
  CreepScheme scheme = CreepScheme::staggered;
  bool follow_bodies = false; // CreepOptions::follow_bodies
};

ClothMaterial knee_sheet_material() {
  ClothMaterial material({TensionCurve::linear(elastic_modulus, "test"),
                          TensionCurve::linear(elastic_modulus, "test"), 0.0, 0.0});
  material.membrane.shear_modulus = 0.1 * elastic_modulus;
  material.bending_stiffness = 1e-5;
  return material;
}

std::vector<int> frame_of(const TriangleMesh& mesh) {
  std::vector<int> frame;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const Eigen::Vector3d& p = mesh.positions[v];
    const bool border = std::min({p.x(), p.y(), side - p.x(), side - p.y()}) < 1e-9;
    if (border) frame.push_back(int(v));
  }
  return frame;
}

// The ball 1 cm below the sheet, rising through it by `push` over the push time.
contact::Body rising_knee(double friction) {
  const Eigen::Vector3d centre(0.5 * side, 0.5 * side, -ball_radius - 0.01);
  contact::Body ball("knee", std::make_shared<contact::Sphere>(centre, ball_radius), centre);
  ball.motion.translation.add(0.0, Eigen::Vector3d::Zero());
  ball.motion.translation.add(push_time, Eigen::Vector3d(0.0, 0.0, 0.01 + push));
  ball.friction.static_coefficient = ball.friction.kinetic_coefficient = friction;
  return ball;
}

WearReport wear_knee(const KneeCase& knee) {
  // The sheet's membrane forces (~1e4 N) leave ~1e-8 N of round-off in the
  // residual, and the minimiser stalls at a few 1e-7 N; without a weight to
  // scale a tolerance by, Newton stops at 1e-6 N (the
  // residual relative to a small step's first one would sit at round-off).
  EXPECT_EQ(PetscOptionsSetValue(nullptr, "-snes_atol", "1e-6"), 0);
  const TriangleMesh mesh = mesh::rectangle(side, side, 8, 8);
  const ClothMaterial material = knee_sheet_material();
  const std::vector<int> frame = frame_of(mesh);
  ClothProblem problem(PETSC_COMM_WORLD, mesh, material, frame);
  problem.bodies.push_back(rising_knee(0.0));

  WearGarment garment;
  garment.materials = {material};
  garment.creep = {{knee.creep, knee.creep}};
  garment.held = frame;
  WearOptions options;
  options.wear.time_end = knee.take_off_times.back();
  options.wear.time_step = knee.fixed_step > 0.0 ? knee.fixed_step : 0.5;
  options.wear.max_step = knee.fixed_step;
  options.wear.creep_tolerance = knee.fixed_step > 0.0 ? 1.0 : 2e-3;
  options.wear.scheme = knee.scheme;
  options.wear.follow_bodies = knee.follow_bodies;
  options.wear.equilibrium.minimise = knee.scheme == CreepScheme::staggered;
  // A fixed contact penalty: the adaptive one stiffens by the history of
  // the solves (more steps, more chances), which is not the physics.
  options.wear.equilibrium.max_contact_rounds = 0;
  options.take_off_times = knee.take_off_times;
  options.recovery_time = knee.recovery_time;
  options.certify_steps = false;
  Vec x = nullptr;
  EXPECT_EQ(problem.create_solution(&x), 0);
  WearReport report;
  EXPECT_EQ(solve_wear(problem, x, garment, options, &report), 0);
  EXPECT_EQ(VecDestroy(&x), 0);
  EXPECT_TRUE(report.wear.completed) << report.wear.reason;
  std::printf("wear: %zu states, %ld rejected, %ld Newton iterations\n", report.steps.size(),
              report.wear.rejected_steps, long(report.wear.newton_iterations));
  for (const TakeOffReport& taken : report.take_offs)
    std::printf("  take-off at %g s: %ld recovery steps (%ld rejected), %ld Newton iterations\n",
                taken.wear_time, taken.recovery_steps, taken.rejected_steps,
                long(taken.newton_iterations));
  EXPECT_EQ(report.take_offs.size(), knee.take_off_times.size());
  for (const TakeOffReport& taken : report.take_offs)
    EXPECT_TRUE(taken.converged) << taken.reason;
  return report;
}

double bagging(const KneeCase& knee) {
  return wear_knee(knee).take_offs.back().bagging_height;
}

TEST(Wear, PermanentDomeHeightIsTheCapOfTheAddedArea) {
  // A 0.4 x 0.2 m sheet, 1 % permanent strain along the warp and 3 % along
  // the weft in every triangle: the left half (x <= 0.2) adds
  // 0.04 m^2 (1.01 * 1.03 - 1) of area, a cap of height sqrt(that / pi).
  const TriangleMesh mesh = mesh::rectangle(0.4, 0.2, 8, 4);
  std::vector<ElementCreep> states(mesh.triangle_count());
  for (ElementCreep& s : states) {
    s.warp.permanent = 0.01;
    s.weft.permanent = 0.03;
  }
  std::vector<int> left;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
    if (mesh.positions[v].x() <= 0.2 + 1e-9) left.push_back(int(v));
  const double added = 0.04 * (1.01 * 1.03 - 1.0);
  double excess = 0.0;
  EXPECT_NEAR(permanent_dome_height(mesh, states, left, &excess), std::sqrt(added / M_PI), 1e-15);
  EXPECT_NEAR(excess, added, 1e-15);
  EXPECT_NEAR(permanent_dome_height(mesh, states, {}, &excess), std::sqrt(2.0 * added / M_PI),
              1e-15);
  for (ElementCreep& s : states)
    s.warp.permanent = s.weft.permanent = 0.0;
  EXPECT_EQ(permanent_dome_height(mesh, states, {}, &excess), 0.0);
}

// The knee sheet with 5 % permanent elongation both ways, without weight,
// started flat: longer than its frame, it is in equilibrium flat (squeezed
// in its plane), but that is a saddle: bulging either way lowers Phi. A
// take-off's hanging that ends in a saddle is pushed along the lowest mode
// (push_off_saddle) and solved again: the sheet then bulges by about the
// cap its added area would form, and there is no direction of descent left.
TEST(Wear, ASheetLongerThanItsFrameIsPushedOffTheFlatSaddle) {
  EXPECT_EQ(PetscOptionsSetValue(nullptr, "-snes_atol", "1e-6"), 0);
  const TriangleMesh mesh = mesh::rectangle(side, side, 8, 8);
  ClothProblem problem(PETSC_COMM_WORLD, mesh, knee_sheet_material(), frame_of(mesh));
  const CreepParameters creep = KneeCase{}.creep;
  CreepCoupling coupling(problem, {{creep, creep}});
  std::vector<ElementCreep> states(mesh.triangle_count());
  for (ElementCreep& s : states)
    s.warp.permanent = s.weft.permanent = 0.05;
  coupling.restore(states);
  Vec x = nullptr;
  ASSERT_EQ(problem.create_solution(&x), 0);
  StaticOptions options;
  options.minimise = true;
  StaticReport flat;
  ASSERT_EQ(solve_static(problem, x, options, &flat), 0);
  EXPECT_TRUE(flat.converged) << flat.reason;
  const auto highest_rise = [&] {
    std::vector<Eigen::Vector3d> positions;
    EXPECT_EQ(problem.positions_everywhere(x, &positions), 0);
    double rise = 0.0;
    for (const Eigen::Vector3d& p : positions)
      rise = std::max(rise, std::abs(p.z()));
    return rise;
  };
  EXPECT_LT(highest_rise(), 1e-9);
  ClothEnergy saddle, bulge;
  ASSERT_EQ(problem.energy(x, &saddle), 0);
  bool pushed = false;
  ASSERT_EQ(push_off_saddle(problem, x, CertificateOptions{}, 0.01 * side, &pushed), 0);
  ASSERT_TRUE(pushed);
  options.start_load_factor = problem.load_factor;
  StaticReport bulged;
  ASSERT_EQ(solve_static(problem, x, options, &bulged), 0);
  EXPECT_TRUE(bulged.converged) << bulged.reason;
  ASSERT_EQ(problem.energy(x, &bulge), 0);
  EXPECT_LT(bulge.total(), saddle.total());
  const double cap = std::sqrt(side * side * (1.05 * 1.05 - 1.0) / M_PI); // 3.6 cm
  std::printf("bulge %.4e m, cap of the added area %.4e m\n", highest_rise(), cap);
  EXPECT_GT(highest_rise(), 0.5 * cap);
  EXPECT_LT(highest_rise(), 1.5 * cap);
  ASSERT_EQ(push_off_saddle(problem, x, CertificateOptions{}, 0.01 * side, &pushed), 0);
  EXPECT_FALSE(pushed);
  EXPECT_EQ(VecDestroy(&x), 0);
}

TEST(Wear, KneeBagsAndTheFreedSheetIsCertified) {
  const WearReport report = wear_knee(KneeCase{});
  const TakeOffReport& taken = report.take_offs.back();
  // The push stretches the sheet by about (push / half side)^2 / 2 ~ 2 %:
  // a permanent strain of a good fraction of alpha times that, a bulge of
  // millimetres (sqrt of the extra length times the span), not metres.
  EXPECT_GT(taken.max_permanent, 1e-3);
  EXPECT_LT(taken.max_permanent, 0.05);
  EXPECT_GT(taken.bagging_height, 1e-3);
  EXPECT_LT(taken.bagging_height, push);
  // The same bulge measured two ways: the freed sheet's rise, and the cap
  // its permanent added area would form (1.46 and 1.05 cm); they agree for
  // a spherical cap, and the bulge, highest at the knee's centre, is not one.
  std::printf("bagging height %.4e m, permanent dome height %.4e m\n", taken.bagging_height,
              taken.dome_height);
  EXPECT_GT(taken.dome_height, 0.5 * taken.bagging_height);
  EXPECT_LT(taken.dome_height, 1.5 * taken.bagging_height);
  EXPECT_TRUE(taken.certificate.equilibrium()) << taken.certificate.verdict();
  EXPECT_FALSE(taken.certificate.saddle()) << taken.certificate.verdict();
  EXPECT_TRUE(report.final_certificate.equilibrium()) << report.final_certificate.verdict();
}

TEST(Wear, MoreBaggingForFasterLoadingAndSofterCreep) {
  KneeCase base;
  base.take_off_times = {8.0}; // before the permanent strain saturates (1 / lambda_load ~ 11 s)
  KneeCase fast = base;
  fast.creep.lambda_load = 4.0 * base.creep.lambda_load;
  KneeCase soft = base;
  soft.creep.creep_modulus = 0.5 * base.creep.creep_modulus;
  const TakeOffReport b = wear_knee(base).take_offs.back(), f = wear_knee(fast).take_offs.back(),
                      s = wear_knee(soft).take_offs.back();
  std::printf("bagging height: base %.4e m, lambda_load x4 %.4e m, E / 2 %.4e m\n",
              b.bagging_height, f.bagging_height, s.bagging_height);
  std::printf("permanent dome height: base %.4e m, lambda_load x4 %.4e m, E / 2 %.4e m\n",
              b.dome_height, f.dome_height, s.dome_height);
  EXPECT_GT(f.bagging_height, 1.1 * b.bagging_height);
  EXPECT_GT(s.bagging_height, 1.1 * b.bagging_height);
  EXPECT_GT(f.dome_height, 1.1 * b.dome_height);
  EXPECT_GT(s.dome_height, 1.1 * b.dome_height);
}

TEST(Wear, PurelyElasticFabricRecoversCompletely) {
  KneeCase elastic;
  elastic.creep = {32600, 0.0, 0.0886, 5.0}; // alpha = 0, lambda_unload 5/s
  KneeCase creeping;
  const WearReport report = wear_knee(elastic);
  const double reference = bagging(creeping);
  const TakeOffReport& taken = report.take_offs.back();
  EXPECT_EQ(taken.max_permanent, 0.0);
  EXPECT_LT(taken.max_viscoelastic, 1e-8);
  EXPECT_LT(taken.bagging_height, 1e-3 * reference);
  EXPECT_EQ(taken.dome_height, 0.0);
}

TEST(Wear, BaggingGrowsWithWearTime) {
  KneeCase knee;
  // A recovery long enough for the viscoelastic part to decay (e^-15): what
  // remains is permanent, which never shrinks.
  knee.creep.lambda_unload = 0.05;
  knee.recovery_time = 300.0;
  knee.take_off_times = {6.0, 10.0, 20.0, 60.0, 600.0};
  const WearReport report = wear_knee(knee);
  for (std::size_t k = 1; k < report.take_offs.size(); ++k) {
    const TakeOffReport& before = report.take_offs[k - 1];
    const TakeOffReport& after = report.take_offs[k];
    std::printf("worn %6.0f s: bagging %.6e m, dome %.6e m, permanent %.6e\n", after.wear_time,
                after.bagging_height, after.dome_height, after.max_permanent);
    EXPECT_GE(after.max_permanent, before.max_permanent);
    EXPECT_GE(after.dome_height, before.dome_height);
    // Saturated (after a minute) the heights agree to the solver's
    // tolerance, far below this margin.
    EXPECT_GE(after.bagging_height, before.bagging_height - 1e-6);
  }
  EXPECT_GT(report.take_offs[2].bagging_height, 1.05 * report.take_offs[0].bagging_height);
  EXPECT_GT(report.take_offs[2].dome_height, 1.05 * report.take_offs[0].dome_height);
  // Every worn state's dome height (wear.csv's): it never falls, and at a
  // take-off time it is the worn state's, which the hanging tension can only
  // add to while the garment recovers.
  for (std::size_t k = 1; k < report.steps.size(); ++k)
    EXPECT_GE(report.steps[k].dome_height, report.steps[k - 1].dome_height);
  EXPECT_GT(report.steps.back().dome_height, 0.0);
  for (const TakeOffReport& taken : report.take_offs) {
    const auto worn =
        std::find_if(report.steps.begin(), report.steps.end(), [&](const WearStep& s) {
          return std::abs(s.step.time - taken.wear_time) < 1e-9;
        });
    ASSERT_NE(worn, report.steps.end()) << "no wear state at " << taken.wear_time << " s";
    EXPECT_LE(worn->dome_height, taken.dome_height * (1.0 + 1e-12));
    EXPECT_GT(worn->dome_height, 0.5 * taken.dome_height);
  }
}

// The bagging height at fixed steps halved three times, and the observed
// orders from successive differences (their ratio is 2^order). The steps
// divide the push (5 s) and the wear (20 s).
struct StepStudy {
  std::vector<double> heights;
  std::vector<double> orders;
  // Richardson's extrapolation of the two finest with the expected order.
  double limit(double order) const {
    const double h1 = heights[heights.size() - 2], h2 = heights.back();
    return h2 + (h2 - h1) / (std::pow(2.0, order) - 1.0);
  }
};

StepStudy step_study(CreepScheme scheme) {
  StepStudy study;
  for (double dt : {1.0, 0.5, 0.25, 0.125}) {
    KneeCase knee;
    knee.fixed_step = dt;
    knee.recovery_time = 10.0;
    knee.creep.lambda_unload = 0.05;
    knee.scheme = scheme;
    study.heights.push_back(bagging(knee));
  }
  const std::vector<double>& h = study.heights;
  for (std::size_t k = 2; k < h.size(); ++k)
    study.orders.push_back(std::log2(std::abs(h[k - 2] - h[k - 1]) / std::abs(h[k - 1] - h[k])));
  std::printf("%s: bagging heights %.8e %.8e %.8e %.8e m; observed orders %.3f %.3f\n",
              scheme == CreepScheme::staggered ? "staggered" : "monolithic", h[0], h[1], h[2], h[3],
              study.orders[0], study.orders[1]);
  return study;
}

// The staggered coupling lags the tension by a step (first order); the
// monolithic one integrates the law exactly for a tension linear over the
// step (second order). Both converge to one bagging height.
TEST(Wear, BaggingConvergesInTheTimeStep) {
  const StepStudy staggered = step_study(CreepScheme::staggered);
  const StepStudy monolithic = step_study(CreepScheme::monolithic);
  EXPECT_GT(staggered.orders.back(), 0.7);
  EXPECT_LT(staggered.orders.back(), 1.3);
  EXPECT_GT(monolithic.orders.back(), 1.7);
  EXPECT_LT(monolithic.orders.back(), 2.3);
  const double limit = monolithic.limit(2.0);
  std::printf("extrapolated: staggered %.8e m, monolithic %.8e m\n", staggered.limit(1.0), limit);
  EXPECT_NEAR(staggered.limit(1.0), limit, 1e-4 * limit);
}

// The knee sheet pushed by a ball with friction (mu = 0.3) over 1 s creep
// steps, their contact rounds cut to `rounds`, friction consistent at
// `allowed` N: the largest residual with the friction anchors updated over
// the accepted states, the steps rejected and the Newton iterations.
struct UnsettledContact {
  double worst_residual = 0.0; // N
  long rejected = 0;
  PetscInt newton_iterations = 0;
};

UnsettledContact creep_with_contact_rounds(double allowed, int rounds = 2,
                                           bool plane_at_vertex = false,
                                           bool update_at_start = true) {
  EXPECT_EQ(PetscOptionsSetValue(nullptr, "-snes_atol", "1e-6"), 0);
  const TriangleMesh mesh = mesh::rectangle(side, side, 8, 8);
  const ClothMaterial material = knee_sheet_material();
  ClothProblem problem(PETSC_COMM_WORLD, mesh, material, frame_of(mesh));
  problem.bodies.push_back(rising_knee(0.3));
  problem.contact.friction_plane_at_vertex = plane_at_vertex;
  CreepParameters creep{32600, 0.9, 0.0886, 0.002};
  CreepCoupling coupling(problem, {{creep, creep}});
  CreepOptions options;
  options.time_end = push_time;
  options.time_step = 1.0;
  options.creep_tolerance = 1.0; // the contact alone shortens the steps
  options.equilibrium.minimise = true;
  options.equilibrium.max_contact_rounds = rounds;
  options.equilibrium.update_anchors_at_start = update_at_start;
  options.equilibrium.contact_tolerance = allowed;
  Vec x = nullptr, f = nullptr;
  EXPECT_EQ(problem.create_solution(&x), 0);
  EXPECT_EQ(VecDuplicate(x, &f), 0);
  UnsettledContact found;
  const CreepObserver observe = [&](const CreepStepReport&, Vec state) -> PetscErrorCode {
    PetscFunctionBeginUser;
    double norm = 0.0;
    PetscCall(problem.residual(state, f));
    PetscCall(VecNorm(f, NORM_2, &norm));
    found.worst_residual = std::max(found.worst_residual, norm);
    PetscFunctionReturn(0);
  };
  CreepReport report;
  EXPECT_EQ(solve_creep(problem, coupling, x, options, &report, observe), 0);
  EXPECT_TRUE(report.completed) << report.reason;
  found.rejected = report.rejected_steps;
  found.newton_iterations = report.newton_iterations;
  std::printf("allowed %g N, %d rounds, friction plane at the %s: worst residual %g N, %ld steps "
              "rejected, %zu accepted, %ld Newton iterations\n",
              allowed, rounds, plane_at_vertex ? "vertex" : "anchor", found.worst_residual,
              found.rejected, report.steps.size(), long(found.newton_iterations));
  EXPECT_EQ(VecDestroy(&f), 0);
  EXPECT_EQ(VecDestroy(&x), 0);
  return found;
}

TEST(Wear, AStepWhoseContactRoundsLeaveTooMuchResidualIsRetriedShorter) {
  // Consistent at any residual, no round is run and the pushed sheet's
  // anchors leave tens of newtons; at 1e-3 N, the steps whose two rounds
  // leave more are retried shorter until none does.
  const double allowed = 1e-3;
  const UnsettledContact loose = creep_with_contact_rounds(1e9);
  const UnsettledContact held = creep_with_contact_rounds(allowed);
  EXPECT_GT(loose.worst_residual, 2.0 * allowed);
  EXPECT_LE(held.worst_residual, allowed);
  EXPECT_GT(held.rejected, loose.rejected);
}

// The sheet slides over the rising ball: with the springs in the plane
// frozen where each anchor was placed, every update after a solve turns the
// friction force into the plane at the vertex, and the vertex slides on in
// the next round; in the plane at the vertex the update finds the force
// the solve applied. Both settle (8 rounds are enough for each); the plane
// at the vertex in far fewer Newton iterations (measured: 148 against 972).
TEST(Wear, FrictionInThePlaneAtTheVertexSettlesInFewerRounds) {
  const double allowed = 1e-5;
  const UnsettledContact frozen = creep_with_contact_rounds(allowed, 8, false);
  const UnsettledContact here = creep_with_contact_rounds(allowed, 8, true);
  EXPECT_LE(frozen.worst_residual, allowed);
  EXPECT_LE(here.worst_residual, allowed);
  EXPECT_LE(here.rejected, frozen.rejected);
  EXPECT_LT(here.newton_iterations, frozen.newton_iterations / 3);
}

// Each step's start has the ball 6 mm further into the sheet, and the
// penalty pushes there with far more than at equilibrium: anchors updated
// at that start bound the first solve's friction by those forces and
// anchor the new contacts where the ball first met them, and the rounds
// then slide them back. Started from the last accepted state's anchors
// (consistent there), as a wear step is, the steps settle in a fraction of
// the Newton iterations (measured: 25 against 148).
TEST(Wear, AStepStartedFromTheAcceptedAnchorsSettlesFaster) {
  const double allowed = 1e-5;
  const UnsettledContact updated = creep_with_contact_rounds(allowed, 8, true, true);
  const UnsettledContact kept = creep_with_contact_rounds(allowed, 8, true, false);
  EXPECT_LE(kept.worst_residual, allowed);
  EXPECT_LE(kept.rejected, updated.rejected);
  EXPECT_LT(kept.newton_iterations, updated.newton_iterations / 3);
}

// A flat 20 cm sheet (no pins) over a ball of radius 2 cm whose centre is
// `depth` below the sheet's middle, the ball rising 1 cm over the first second.
struct SheetOverBall {
  explicit SheetOverBall(double depth)
      : mesh(mesh::rectangle(side, side, 8, 8)), centre(0.5 * side, 0.5 * side, -depth),
        problem(PETSC_COMM_WORLD, mesh,
                ClothMaterial({TensionCurve::linear(elastic_modulus, "test"),
                               TensionCurve::linear(elastic_modulus, "test"), 0.0, 0.0}),
                {}) {
    contact::Body ball("ball", std::make_shared<contact::Sphere>(centre, radius), centre);
    ball.motion.translation.add(0.0, Eigen::Vector3d::Zero());
    ball.motion.translation.add(1.0, rise);
    problem.bodies.push_back(ball);
    problem.pins_follow_time = true;
    EXPECT_EQ(problem.create_solution(&x), 0);
  }
  ~SheetOverBall() { VecDestroy(&x); }
  std::vector<Eigen::Vector3d> positions() {
    std::vector<Eigen::Vector3d> p;
    EXPECT_EQ(problem.gather_positions(x, &p), 0);
    return p;
  }
  static constexpr double radius = 0.02;
  const Eigen::Vector3d rise{0.0, 0.0, 0.01};
  TriangleMesh mesh;
  Eigen::Vector3d centre;
  ClothProblem problem;
  Vec x = nullptr;
};

TEST(FollowBodies, ClothNearAMovingBodyIsCarriedAlongByLessTheFurtherItIs) {
  SheetOverBall sheet(0.03); // the sheet's middle 1 cm above the ball
  const double reach = 0.05;
  EXPECT_EQ(sheet.problem.carry_with_bodies(sheet.x, 1.0, reach), 0);
  EXPECT_EQ(sheet.problem.time, 1.0);
  const std::vector<Eigen::Vector3d> carried = sheet.positions();
  long moved = 0, kept = 0;
  for (std::size_t v = 0; v < carried.size(); ++v) {
    const Eigen::Vector3d& start = sheet.mesh.positions[v];
    const double d = (start - sheet.centre).norm() - SheetOverBall::radius;
    const double share = std::max(0.0, 1.0 - d / reach); // the ball translates: all alike
    EXPECT_NEAR((carried[v] - (start + share * sheet.rise)).norm(), 0.0, 1e-12) << "vertex " << v;
    (share > 0.0 ? moved : kept) += 1;
  }
  EXPECT_GT(moved, 10);
  EXPECT_GT(kept, 10);
}

TEST(FollowBodies, VerticesInsideABodyArePushedOutToTheMiddleOfTheOffset) {
  SheetOverBall sheet(0.01); // the ball's top 1 cm above the sheet
  ClothProblem::PushOut pushed;
  EXPECT_EQ(sheet.problem.push_out_of_bodies(sheet.x, &pushed), 0);
  const std::vector<Eigen::Vector3d> out = sheet.positions();
  long inside = 0;
  for (std::size_t v = 0; v < out.size(); ++v) {
    const Eigen::Vector3d& start = sheet.mesh.positions[v];
    const double d = (start - sheet.centre).norm() - SheetOverBall::radius;
    if (d >= 0.0) {
      EXPECT_EQ(out[v], start) << "vertex " << v << " was outside";
      continue;
    }
    ++inside;
    const Eigen::Vector3d radial = (start - sheet.centre).normalized();
    const double wanted = SheetOverBall::radius + 0.5 * sheet.problem.contact.offset;
    EXPECT_NEAR((out[v] - (sheet.centre + wanted * radial)).norm(), 0.0, 1e-12) << "vertex " << v;
  }
  EXPECT_EQ(pushed.pushed, inside);
  EXPECT_GT(inside, 0);
  EXPECT_NEAR(pushed.deepest, 0.01, 1e-12);    // the middle vertex, on the ball's axis
  EXPECT_EQ(pushed.queries, long(out.size())); // the ball has no bone intervals
}

TEST(FollowBodies, TheKneeSheetBagsAsMuchWhenEachStepStartsCarried) {
  // The ball's motion carries the sheet near it at each step's start: the
  // start changes, the equilibria and so the creep do not (to the solves'
  // tolerance).
  KneeCase knee;
  const double plain = bagging(knee);
  knee.follow_bodies = true;
  const double followed = bagging(knee);
  std::printf("bagging: %.9e m plain, %.9e m followed\n", plain, followed);
  EXPECT_GT(plain, 1e-3);
  EXPECT_NEAR(followed, plain, 1e-4 * plain);
}

TEST(BentLimb, FollowsItsAngleOnTheProblemsClock) {
  // An elbow at the origin, the upper arm along -x, the forearm along +x
  // when straight, bent about z by 90 degrees over 10 s.
  const auto limb = std::make_shared<BentLimb>(
      Eigen::Vector3d(-0.3, 0, 0), Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), 0.25, 0.04,
      Eigen::Vector3d::UnitZ(),
      std::vector<std::pair<double, double>>{{0.0, 0.0}, {10.0, M_PI / 2}});
  double clock = 0.0;
  const ShapeOnClock shape(limb, &clock);
  const Eigen::Vector3d hand_straight(0.25, 0.0, 0.0), hand_bent(0.0, 0.25, 0.0);
  EXPECT_NEAR(shape.query(hand_straight).distance, -0.04, 1e-12);
  EXPECT_NEAR(shape.query(hand_bent).distance, 0.25 - 0.04, 1e-12);
  clock = 10.0;
  EXPECT_NEAR(shape.query(hand_bent).distance, -0.04, 1e-12);
  clock = 5.0; // 45 degrees: the forearm's end at 0.25 (cos, sin) 45
  const Eigen::Vector3d half(0.25 * std::sqrt(0.5), 0.25 * std::sqrt(0.5), 0.0);
  EXPECT_NEAR(shape.query(half).distance, -0.04, 1e-12);
  EXPECT_EQ(limb->knots(), (std::vector<double>{0.0, 10.0}));
}

// The default mannequin bending its left knee from straight to 90 degrees
// over 10 s, and its left shin standing.
std::shared_ptr<const PosedMannequin> left_knee_bending() {
  return std::make_shared<PosedMannequin>(MannequinModel(),
                                          contact::parse_pose_history("0:;10:knee_l:90"), 5.0);
}

Bone standing_left_shin() {
  for (const Bone& bone : MannequinModel().skeleton())
    if (bone.name == "shin_l") return bone;
  throw std::logic_error("the mannequin has no bone shin_l");
}

TEST(WearPoses, BendTheKneeOnTheProblemsClock) {
  // The left knee bent from straight to 90 degrees over 10 s: the foot
  // swings backwards (+y) about the knee's transverse axis (x). Halfway (45
  // degrees) the middle of the shin is where neither the straight nor the
  // right-angled shin is.
  const auto poses = left_knee_bending();
  const Bone shin = standing_left_shin();
  const double half_length = 0.5 * (shin.end - shin.start).norm();
  const Eigen::Vector3d middle_at_45 =
      shin.start + half_length * Eigen::Vector3d(0.0, std::sqrt(0.5), -std::sqrt(0.5));
  double clock = 0.0;
  const ShapeOnClock shape(poses, &clock);
  EXPECT_GT(shape.query(middle_at_45).distance, 0.02);
  clock = 5.0;
  EXPECT_LT(shape.query(middle_at_45).distance, 0.0);
  EXPECT_EQ(shape.partial_query(middle_at_45, contact::QueryNeeds::distance).distance,
            shape.query(middle_at_45).distance);
  clock = 10.0;
  EXPECT_GT(shape.query(middle_at_45).distance, 0.02);
}

TEST(WearPoses, CarryAPointOnTheShinWithIt) {
  // Friction anchors ride on the surface: a point on the front of the left
  // shin, taken to the reference frame standing and back with the knee bent
  // 90 degrees, turned with the shin about the knee: as far from the knee,
  // on the bent shin's surface, its normal the surface's there.
  const auto poses = left_knee_bending();
  const Bone shin = standing_left_shin();
  const Eigen::Vector3d knee = shin.start;
  double clock = 0.0;
  const ShapeOnClock shape(poses, &clock);
  const Eigen::Vector3d front = 0.5 * (shin.start + shin.end) + Eigen::Vector3d(0.0, -0.2, 0.0);
  const Eigen::Vector3d on_shin = shape.query(front).closest;
  const contact::SurfaceQuery standing = shape.query(on_shin);
  ASSERT_LT(std::abs(standing.distance), 1e-3);
  const Eigen::Vector3d point = shape.to_reference(on_shin);
  const Eigen::Vector3d normal =
      shape.direction_to_reference(on_shin, standing.normal.normalized());
  clock = 10.0;
  const Eigen::Vector3d carried = shape.from_reference(point);
  EXPECT_NEAR((carried - knee).norm(), (on_shin - knee).norm(), 1e-12);
  EXPECT_GT((carried - on_shin).norm(), 0.1);
  const contact::SurfaceQuery bent = shape.query(carried);
  EXPECT_LT(std::abs(bent.distance), 1e-3);
  EXPECT_GT(shape.direction_from_reference(point, normal).dot(bent.normal.normalized()),
            std::cos(M_PI / 180.0));
  EXPECT_LT((shape.to_reference(carried) - point).norm(), 1e-12);
}

TEST(WearPoses, PointsRoundABentKneeStayWithTheirBone) {
  // Round the left knee bent 54 degrees, points 1 cm outside its flesh in
  // every direction: into the reference frame and back at the same pose they
  // come back where they were, and carried on to 54.9 degrees none moves
  // further than the shin's turn would take a point that far from the knee
  // (the thigh's do not move at all). A carrier chosen afresh on the way back
  // (the bone nearest the point's unposed image) breaks both near the crease.
  const auto poses = left_knee_bending();
  const Bone shin = standing_left_shin();
  const Eigen::Vector3d knee = shin.start;
  const double radius = shin.start_radius + 0.01;
  const double turn = 0.9 * M_PI / 180.0;
  double clock = 6.0;
  const ShapeOnClock shape(poses, &clock);
  for (int i = 0; i < 12; ++i) {
    const double polar = M_PI * (i + 0.5) / 12.0;
    for (int j = 0; j < 24; ++j) {
      const double azimuth = 2.0 * M_PI * j / 24.0;
      const Eigen::Vector3d p =
          knee + radius * Eigen::Vector3d(std::cos(polar), std::sin(polar) * std::cos(azimuth),
                                          std::sin(polar) * std::sin(azimuth));
      clock = 6.0;
      const Eigen::Vector3d point = shape.to_reference(p);
      EXPECT_LT((shape.from_reference(point) - p).norm(), 1e-12)
          << "polar " << polar << ", azimuth " << azimuth;
      clock = 6.1;
      EXPECT_LE((shape.from_reference(point) - p).norm(), turn * radius + 1e-12)
          << "polar " << polar << ", azimuth " << azimuth;
    }
  }
}

TEST(WearPoses, StepsLandWhereNoJointTurnedMoreThanTheLargestTurn) {
  // Sit (hips and knees to 90 degrees over 10 s), stay, stand up (10 s):
  // 18 pieces of 5 degrees each way, the keyframes among the knots.
  const PosedMannequin poses(
      MannequinModel(),
      contact::parse_pose_history("0:;10:hip_l:90,knee_l:90;20:hip_l:90,knee_l:90;30:"), 5.0);
  const std::vector<double> knots = poses.knots();
  ASSERT_EQ(knots.size(), 38u);
  for (double keyframe : {0.0, 10.0, 20.0, 30.0})
    EXPECT_NE(std::find(knots.begin(), knots.end(), keyframe), knots.end()) << keyframe;
  for (std::size_t k = 1; k < knots.size(); ++k) {
    ASSERT_GT(knots[k], knots[k - 1]);
    const double turn = std::abs(poses.history().at(knots[k]).angle("knee_l") -
                                 poses.history().at(knots[k - 1]).angle("knee_l"));
    EXPECT_LE(turn, 5.0 + 1e-9) << "between " << knots[k - 1] << " and " << knots[k] << " s";
  }
  EXPECT_THROW(
      PosedMannequin(MannequinModel(), contact::parse_pose_history("0:;10:knee_l:300"), 5.0),
      InputError);
}

} // namespace
} // namespace sartor
