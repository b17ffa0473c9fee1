// Implicit dynamics and prescribed pin motions: the exact backward-Euler
// recurrence of a free fall, energy decay with damping, settling onto the
// static solution (damped and by kinetic damping), each by both solvers of
// the time steps, pin histories in time and
// in load factor, and results independent of the number of MPI ranks.

#include "common/error.hpp"
#include "fem/cloth_problem.hpp"
#include "fem/pin_motion.hpp"
#include "mesh/generators.hpp"
#include "solvers/dynamics.hpp"
#include "solvers/statics.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace sartor {
namespace {

ClothMaterial cotton(double bending) {
  ClothMaterial m(
      {TensionCurve::linear(65200, "test"), TensionCurve::linear(28200, "test"), 4288.0, 0.0});
  m.bending_stiffness = bending;
  m.areal_density = 0.2;
  return m;
}

const Eigen::Vector3d gravity(0, 0, -9.80665);

// A 1 m square in the x-z plane, hanging from its two top corners.
TriangleMesh hanging_sheet(int n, std::vector<int>* pins) {
  TriangleMesh mesh = mesh::rectangle(1.0, 1.0, n, n);
  for (auto& p : mesh.positions)
    p = Eigen::Vector3d(p[0], 0.0, p[1]);
  pins->clear();
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const auto& p = mesh.positions[v];
    if (p[2] == 1.0 && (p[0] == 0.0 || p[0] == 1.0)) pins->push_back(int(v));
  }
  return mesh;
}

// Positions in mesh numbering, on every rank.
std::vector<Eigen::Vector3d> positions_everywhere(ClothProblem& problem, Vec x) {
  std::vector<Eigen::Vector3d> positions;
  EXPECT_EQ(problem.positions_everywhere(x, &positions), 0);
  return positions;
}

double largest_difference(const std::vector<Eigen::Vector3d>& a,
                          const std::vector<Eigen::Vector3d>& b) {
  double largest = 0.0;
  for (std::size_t v = 0; v < a.size(); ++v)
    largest = std::max(largest, (a[v] - b[v]).norm());
  return largest;
}

std::vector<Eigen::Vector3d> static_solution(MPI_Comm comm, const TriangleMesh& mesh,
                                             const ClothMaterial& material,
                                             const std::vector<int>& pins) {
  ClothProblem problem(comm, mesh, material, pins);
  problem.loads.gravity = gravity;
  Vec x = nullptr;
  EXPECT_EQ(problem.create_solution(&x), 0);
  StaticReport report;
  EXPECT_EQ(solve_static(problem, x, {}, &report), 0);
  EXPECT_TRUE(report.converged) << report.reason;
  auto positions = positions_everywhere(problem, x);
  VecDestroy(&x);
  return positions;
}

struct DynamicRun {
  DynamicReport report;
  std::vector<Eigen::Vector3d> positions;
};

DynamicRun run_dynamic(MPI_Comm comm, const TriangleMesh& mesh, const ClothMaterial& material,
                       const std::vector<int>& pins, const DynamicOptions& options,
                       const DynamicObserver& observe = {}) {
  ClothProblem problem(comm, mesh, material, pins);
  problem.loads.gravity = gravity;
  Vec x = nullptr, v = nullptr;
  EXPECT_EQ(problem.create_solution(&x), 0);
  VecDuplicate(x, &v);
  VecSet(v, 0.0);
  DynamicRun run;
  EXPECT_EQ(solve_dynamic(problem, x, v, options, &run.report, observe), 0);
  EXPECT_TRUE(run.report.completed) << run.report.reason;
  run.positions = positions_everywhere(problem, x);
  VecDestroy(&x);
  VecDestroy(&v);
  return run;
}

// Each dynamics test runs with both solvers of the time steps: SNES from the
// predicted positions, and the static minimiser on the step's incremental
// potential from the last state (DynamicOptions::minimise).
class Dynamics : public ::testing::TestWithParam<bool> {
protected:
  DynamicOptions options_with_solver() const {
    DynamicOptions options;
    options.minimise = GetParam();
    return options;
  }
};

INSTANTIATE_TEST_SUITE_P(BothSolvers, Dynamics, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& solver) {
                           return std::string(solver.param ? "Minimiser" : "Snes");
                         });

TEST_P(Dynamics, FreeFallFollowsTheBackwardEulerRecurrence) {
  // An unpinned flat sheet falls without straining: every vertex obeys
  // v_{n+1} = (v_n + dt g) / (1 + alpha dt), x_{n+1} = x_n + dt v_{n+1}.
  const TriangleMesh mesh = mesh::rectangle(0.5, 0.4, 4, 3, mesh::RectanglePattern::perturbed);
  for (double alpha : {0.0, 3.0}) {
    DynamicOptions options = options_with_solver();
    options.time_step = 0.01;
    options.time_end = 0.2;
    options.damping = alpha;
    const DynamicRun run = run_dynamic(PETSC_COMM_WORLD, mesh, cotton(1e-5), {}, options);
    ASSERT_EQ(run.report.steps.size(), 21u);
    Eigen::Vector3d velocity = Eigen::Vector3d::Zero(), drop = Eigen::Vector3d::Zero();
    for (int n = 0; n < 20; ++n) {
      velocity = (velocity + options.time_step * gravity) / (1.0 + alpha * options.time_step);
      drop += options.time_step * velocity;
    }
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      EXPECT_LT((run.positions[v] - mesh.positions[v] - drop).norm(), 1e-12 * drop.norm())
          << "vertex " << v << ", alpha " << alpha;
    }
    const double mass = 0.2 * 0.5 * 0.4;
    EXPECT_NEAR(run.report.steps.back().kinetic_energy, 0.5 * mass * velocity.squaredNorm(),
                1e-10 * mass * velocity.squaredNorm());
  }
}

TEST_P(Dynamics, DampedTotalEnergyDecreasesMonotonically) {
  std::vector<int> pins;
  const TriangleMesh mesh = hanging_sheet(6, &pins);
  DynamicOptions options = options_with_solver();
  options.time_step = 0.005;
  options.time_end = 0.15;
  options.damping = 2.0;
  const DynamicRun run = run_dynamic(PETSC_COMM_WORLD, mesh, cotton(1e-5), pins, options);
  const auto& steps = run.report.steps;
  ASSERT_NEAR(steps.back().time, options.time_end, 1e-12);
  double previous = steps.front().kinetic_energy + steps.front().potential_energy;
  double scale = 0.0; // of the energies, for their round-off
  for (const auto& step : steps)
    scale = std::max(scale, std::abs(step.potential_energy));
  for (std::size_t k = 1; k < steps.size(); ++k) {
    const double total = steps[k].kinetic_energy + steps[k].potential_energy;
    // The energies are sums over the mesh whose round-off changes with the
    // linear solver and the CPU's kernels (1e-13 of the scale was exceeded);
    // a gain of 1e-10 of it would still be a real one.
    EXPECT_LE(total, previous + 1e-10 * scale) << "step " << k;
    previous = total;
  }
  EXPECT_LT(previous, steps.front().potential_energy); // it did dissipate
}

TEST_P(Dynamics, DampedHangingSheetSettlesOnTheStaticSolution) {
  // Released from its flat placement, the sheet sags in its plane; strong
  // mass damping (alpha = 50/s) kills the motion. The remaining distance to
  // the static solution is bounded by |F| / k_min with F the static residual;
  // we ask for 1e-6 of the sag, well above the solver tolerances.
  std::vector<int> pins;
  const TriangleMesh mesh = hanging_sheet(6, &pins);
  const auto reference = static_solution(PETSC_COMM_WORLD, mesh, cotton(1e-5), pins);
  DynamicOptions options = options_with_solver();
  options.time_step = 0.01;
  options.time_end = 1.0;
  options.damping = 50.0;
  const DynamicRun run = run_dynamic(PETSC_COMM_WORLD, mesh, cotton(1e-5), pins, options);
  const double sag = largest_difference(reference, mesh.positions);
  EXPECT_LT(largest_difference(run.positions, reference), 1e-6 * sag) << "sag " << sag << " m";
}

TEST_P(Dynamics, KineticDampingReachesTheStaticEquilibrium) {
  std::vector<int> pins;
  const TriangleMesh mesh = hanging_sheet(6, &pins);
  const auto reference = static_solution(PETSC_COMM_WORLD, mesh, cotton(1e-5), pins);
  DynamicOptions options = options_with_solver();
  options.time_step = 0.01;
  options.time_end = 5.0;
  options.kinetic_damping = true;
  options.rest_tolerance = 1e-7;
  const DynamicRun run = run_dynamic(PETSC_COMM_WORLD, mesh, cotton(1e-5), pins, options);
  EXPECT_TRUE(run.report.at_rest);
  EXPECT_GT(run.report.velocity_resets, 0);
  const double sag = largest_difference(reference, mesh.positions);
  EXPECT_LT(largest_difference(run.positions, reference), 1e-6 * sag) << "sag " << sag << " m";
}

TEST(PinHistory, InterpolatesAndHoldsOutsideItsKnots) {
  const PinHistory history =
      PinHistory::parse("0:0,0,0; 1:0,0,0.1 ; 2:0.2,0,0,90;", "option --pin-motion");
  ASSERT_EQ(history.knots().size(), 3u);
  EXPECT_LT((history.at(0.5).translation - Eigen::Vector3d(0, 0, 0.05)).norm(), 1e-15);
  EXPECT_LT((history.at(1.5).translation - Eigen::Vector3d(0.1, 0, 0.05)).norm(), 1e-15);
  EXPECT_NEAR(history.at(1.5).angle, M_PI / 4, 1e-15);
  EXPECT_EQ(history.at(-3).translation, Eigen::Vector3d::Zero());
  EXPECT_EQ(history.at(7).translation, Eigen::Vector3d(0.2, 0, 0));
  PinGroupMotion group;
  group.history = history;
  group.center = {1, 0, 0};
  // At t = 2: a quarter turn about z through (1, 0, 0), then 0.2 along x.
  EXPECT_LT((group.place({2, 0, 0}, 2.0) - Eigen::Vector3d(1.2, 1, 0)).norm(), 1e-15);
}

TEST(PinHistory, BadHistoriesAreRejectedWithTheOptionName) {
  const auto message = [](const std::string& text) {
    try {
      PinHistory::parse(text, "option --pin-motion");
    } catch (const InputError& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("0:0,0,0; 1:0,0,1; 1:0,0,2"),
            "option --pin-motion: knot times must increase, but knot 3 is at 1 after 1");
  EXPECT_EQ(message("0:0,0,0; 1:0,nan,1"),
            "option --pin-motion, knot 2 '1:0,nan,1': 'nan' is not a finite number");
  EXPECT_EQ(message("0:0,0"), "option --pin-motion, knot 1 '0:0,0': expected 3 displacements "
                              "(m) and optionally an angle (degrees), got 2 numbers");
  EXPECT_EQ(message("0 0,0,0"), "option --pin-motion, knot 1 '0 0,0,0': expected "
                                "TIME:DX,DY,DZ or TIME:DX,DY,DZ,ANGLE_DEG");
  EXPECT_EQ(message(" ; "), "option --pin-motion: a motion history needs at least one knot");
}

// A 1 m x 0.1 m strip along x, held at x = 0, the end x = 1 pinned too.
TriangleMesh strip(std::vector<int>* fixed, std::vector<int>* moving) {
  TriangleMesh mesh = mesh::rectangle(1.0, 0.1, 8, 1);
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    if (mesh.positions[v][0] == 0.0) fixed->push_back(int(v));
    if (mesh.positions[v][0] == 1.0) moving->push_back(int(v));
  }
  return mesh;
}

// Runs `problem` from rest in its mesh's placement.
void run_from_rest(ClothProblem& problem, const DynamicOptions& options, DynamicReport* report,
                   const DynamicObserver& observe = {}) {
  Vec x = nullptr, v = nullptr;
  ASSERT_EQ(problem.create_solution(&x), 0);
  VecDuplicate(x, &v);
  VecSet(v, 0.0);
  EXPECT_EQ(solve_dynamic(problem, x, v, options, report, observe), 0);
  VecDestroy(&x);
  VecDestroy(&v);
}

TEST(PinHistory, PinsFollowTheHistoryInTime) {
  std::vector<int> fixed, moving;
  const TriangleMesh mesh = strip(&fixed, &moving);
  std::vector<int> pins = fixed;
  pins.insert(pins.end(), moving.begin(), moving.end());
  ClothProblem problem(PETSC_COMM_WORLD, mesh, cotton(1e-6), pins);
  PinGroupMotion group;
  group.history = PinHistory::parse("0:0,0,0; 1:0.02,0,0; 2:0.01,0,0.1", "test");
  for (std::size_t i = fixed.size(); i < pins.size(); ++i)
    group.pins.push_back(i);
  problem.pin_groups.push_back(group);
  DynamicOptions options;
  options.time_step = 0.05;
  options.time_end = 2.0;
  options.damping = 5.0;
  options.output_interval = 0.25; // steps land on t = 0.5 even after a cut-back
  std::vector<std::pair<double, std::vector<Eigen::Vector3d>>> states;
  const DynamicObserver record = [&](const DynamicStepReport& step, Vec state, Vec) {
    states.emplace_back(step.time, positions_everywhere(problem, state));
    return PetscErrorCode(0);
  };
  DynamicReport report;
  run_from_rest(problem, options, &report, record);
  ASSERT_TRUE(report.completed) << report.reason;
  ASSERT_GE(states.size(), 41u); // steps of 0.05 s, more where one was cut back
  ASSERT_NEAR(states.back().first, options.time_end, 1e-12);
  for (const auto& [time, positions] : states) {
    const Eigen::Vector3d expected = group.history.at(time).translation;
    for (int p : fixed)
      EXPECT_EQ(positions[std::size_t(p)], mesh.positions[std::size_t(p)]);
    for (int p : moving) {
      EXPECT_LT((positions[std::size_t(p)] - mesh.positions[std::size_t(p)] - expected).norm(),
                1e-15)
          << "t = " << time;
    }
  }
  // Intermediate times interpolate: t = 0.5 lies halfway to the first knot.
  const auto halfway = std::find_if(states.begin(), states.end(), [](const auto& state) {
    return std::abs(state.first - 0.5) < 1e-12;
  });
  ASSERT_NE(halfway, states.end());
  const auto p = std::size_t(moving.front());
  EXPECT_NEAR(halfway->second[p][0] - mesh.positions[p][0], 0.01, 1e-15);
  EXPECT_NEAR(states.back().second[p][2] - mesh.positions[p][2], 0.1, 1e-15);
}

// Time steps end on the outputs, on the knots of a pin motion and on a
// pin's release, whatever the time step: 0.04 s steps with outputs every
// 0.1 s, a knot at 0.13 s and a release at 0.27 s.
TEST(PinHistory, TimeStepsLandOnOutputsKnotsAndReleases) {
  std::vector<int> fixed, moving;
  const TriangleMesh mesh = strip(&fixed, &moving);
  std::vector<int> pins = fixed;
  pins.insert(pins.end(), moving.begin(), moving.end());
  std::vector<double> releases(pins.size(), INFINITY);
  releases.back() = 0.27;
  ClothProblem problem(PETSC_COMM_WORLD, mesh, std::vector<ClothMaterial>{cotton(1e-6)}, pins,
                       releases);
  PinGroupMotion group;
  group.history = PinHistory::parse("0:0,0,0; 0.13:0.01,0,0", "test");
  for (std::size_t i = fixed.size(); i + 1 < pins.size(); ++i)
    group.pins.push_back(i);
  problem.pin_groups.push_back(group);
  problem.loads.gravity = gravity;
  DynamicOptions options;
  options.time_step = 0.04;
  options.time_end = 0.4;
  options.damping = 5.0;
  options.output_interval = 0.1;
  DynamicReport report;
  run_from_rest(problem, options, &report);
  ASSERT_TRUE(report.completed) << report.reason;
  const auto reached = [&](double time) {
    return std::any_of(
        report.steps.begin(), report.steps.end(),
        [&](const DynamicStepReport& step) { return std::abs(step.time - time) < 1e-12; });
  };
  for (double landing : {0.1, 0.13, 0.2, 0.27, 0.3, 0.4})
    EXPECT_TRUE(reached(landing)) << "no step ends at t = " << landing << " s";
  for (const DynamicStepReport& step : report.steps) {
    EXPECT_LE(step.dt, options.time_step + 1e-12) << "t = " << step.time;
    const bool at_output = std::abs(step.time / 0.1 - std::round(step.time / 0.1)) < 1e-9;
    EXPECT_EQ(step.output, at_output || step.step == 0) << "t = " << step.time;
  }
}

TEST(PinHistory, StaticsUseTheLoadFactorAsClock) {
  std::vector<int> fixed, moving;
  const TriangleMesh mesh = strip(&fixed, &moving);
  std::vector<int> pins = fixed;
  pins.insert(pins.end(), moving.begin(), moving.end());
  ClothProblem problem(PETSC_COMM_WORLD, mesh, cotton(1e-6), pins);
  PinGroupMotion group;
  group.history = PinHistory::parse("0:0,0,0; 1:0.01,0,0", "test");
  for (std::size_t i = fixed.size(); i < pins.size(); ++i)
    group.pins.push_back(i);
  problem.pin_groups.push_back(group);
  Vec x = nullptr;
  ASSERT_EQ(problem.create_solution(&x), 0);
  StaticOptions options;
  options.load_steps = 2;
  StaticReport report;
  ASSERT_EQ(solve_static(problem, x, options, &report), 0);
  ASSERT_TRUE(report.converged) << report.reason;
  const auto positions = positions_everywhere(problem, x);
  for (int p : moving) {
    EXPECT_NEAR(positions[std::size_t(p)][0], 1.01, 1e-15);
  }
  // A uniform 1 % warp stretch: the middle of the strip moved 0.005 m.
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    if (std::abs(mesh.positions[v][0] - 0.5) < 1e-12) {
      EXPECT_NEAR(positions[v][0], 0.505, 1e-6);
    }
  }
  VecDestroy(&x);
}

TEST(DynamicsMpi, ResultIndependentOfTheNumberOfRanks) {
  // Swinging: a horizontal sheet released from two corners of one edge.
  TriangleMesh mesh = mesh::rectangle(0.6, 0.6, 6, 6);
  std::vector<int> pins;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const auto& p = mesh.positions[v];
    if (p[1] == 0.6 && (p[0] == 0.0 || p[0] == 0.6)) pins.push_back(int(v));
  }
  DynamicOptions options;
  options.time_step = 0.01;
  options.time_end = 0.1;
  options.damping = 1.0;
  const auto together = run_dynamic(PETSC_COMM_WORLD, mesh, cotton(1e-5), pins, options);
  const auto alone = run_dynamic(PETSC_COMM_SELF, mesh, cotton(1e-5), pins, options);
  const double motion = largest_difference(alone.positions, mesh.positions);
  EXPECT_GT(motion, 0.01);
  EXPECT_LT(largest_difference(together.positions, alone.positions), 1e-8 * motion);
  EXPECT_EQ(together.report.steps.size(), alone.report.steps.size());
}

} // namespace
} // namespace sartor
