// The step controller's landings, slivers and periodic events, against
// step sequences worked out by hand.
#include "solvers/step_controller.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace sartor {
namespace {

struct Step {
  double to;
  bool shortened;
  bool output;
  bool checkpoint;
};

// Accepts every plan for steps of `asked` length to the end.
std::vector<Step> run(StepController& clock, double asked) {
  std::vector<Step> steps;
  while (!clock.finished() && steps.size() < 100) {
    const StepPlan plan = clock.plan(asked);
    clock.accept(plan);
    Step step{plan.to, plan.shortened, clock.output_due(), clock.checkpoint_due()};
    if (step.output) clock.pass_output();
    if (step.checkpoint) clock.pass_checkpoint();
    steps.push_back(step);
  }
  return steps;
}

TEST(StepController, StepsEndOnOutputsAndLandings) {
  StepController clock(0.0, 1.0, 1e-9, {0.8, 0.35, -1.0, 2.0});
  clock.output_every(0.5);
  const std::vector<Step> steps = run(clock, 0.21);
  // 0.21, the landing 0.35, 0.5 (an output), 0.71, the landing 0.8, the end.
  const std::vector<double> ends{0.21, 0.35, 0.5, 0.71, 0.8, 1.0};
  ASSERT_EQ(steps.size(), ends.size());
  for (std::size_t k = 0; k < ends.size(); ++k)
    EXPECT_NEAR(steps[k].to, ends[k], 1e-12) << k;
  for (std::size_t k : {1, 2, 4, 5}) // landed on exactly
    EXPECT_EQ(steps[k].to, ends[k]) << k;
  const std::vector<bool> outputs{false, false, true, false, false, true};
  const std::vector<bool> shortened{false, true, true, false, true, true};
  for (std::size_t k = 0; k < ends.size(); ++k) {
    EXPECT_EQ(steps[k].output, outputs[k]) << k;
    EXPECT_EQ(steps[k].shortened, shortened[k]) << k;
  }
}

TEST(StepController, ASliverBeforeALandingJoinsTheStep) {
  StepController clock(0.0, 1.0, 1e-9);
  const std::vector<Step> steps = run(clock, 0.3333);
  // 1 - 2 * 0.3333 - 0.3333 = 1e-4 < 1e-3 of the step: three steps.
  ASSERT_EQ(steps.size(), 3u);
  EXPECT_EQ(steps[2].to, 1.0);
  EXPECT_FALSE(steps[2].shortened);
}

// A ramp in ten increments of 0.1, whose sum falls short of 1 by a
// round-off, takes ten steps, the last to exactly 1.
TEST(StepController, TenTenthsMakeTheWhole) {
  StepController fraction(0.0, 1.0, 0.0);
  const std::vector<Step> steps = run(fraction, 0.1);
  ASSERT_EQ(steps.size(), 10u);
  EXPECT_EQ(steps.back().to, 1.0);
}

// Steps doubling from 1 s over 1023 s (1, 2, 4, ... 512 s: ten steps): after
// k of them, t = 2^k - 1 and the geometric share is k/10 exactly, where the
// share of the simulated time is (2^k - 1)/1023; done at the end.
TEST(StepController, GeometricShareCountsDoublingSteps) {
  StepController clock(0.0, 1023.0, 1e-9);
  EXPECT_EQ(clock.geometric_fraction_done(1.0), 0.0);
  double step = 1.0;
  for (int k = 1; k <= 9; ++k, step *= 2.0) {
    clock.accept(clock.plan(step));
    EXPECT_NEAR(clock.geometric_fraction_done(1.0), k / 10.0, 1e-12) << "after step " << k;
  }
  EXPECT_NEAR(clock.fraction_done(), 511.0 / 1023.0, 1e-12);
  clock.accept(clock.plan(step));
  EXPECT_TRUE(clock.finished());
  EXPECT_EQ(clock.geometric_fraction_done(1.0), 1.0);
}

TEST(StepController, CheckpointsThatDoNotLandAreTakenPastTheirTimes) {
  StepController clock(0.0, 1.0, 1e-9);
  clock.checkpoint_every(0.3, PeriodicEvent::Landing::first_step_past_it);
  const std::vector<Step> steps = run(clock, 0.25);
  ASSERT_EQ(steps.size(), 4u);
  // 0.25, 0.5 (past 0.3), 0.75 (past 0.6), 1.0 (past 0.9); every step an
  // output without an output interval.
  const std::vector<bool> checkpoints{false, true, true, true};
  for (std::size_t k = 0; k < steps.size(); ++k) {
    EXPECT_NEAR(steps[k].to, 0.25 * double(k + 1), 1e-12);
    EXPECT_EQ(steps[k].checkpoint, checkpoints[k]) << k;
    EXPECT_TRUE(steps[k].output) << k;
  }
}

TEST(StepController, LandingCheckpointsCutSteps) {
  StepController clock(0.0, 1.0, 1e-9);
  clock.checkpoint_every(0.3, PeriodicEvent::Landing::steps_end_on_it);
  const std::vector<Step> steps = run(clock, 0.5);
  const std::vector<double> ends{0.3, 0.6, 0.9, 1.0};
  ASSERT_EQ(steps.size(), ends.size());
  for (std::size_t k = 0; k < ends.size(); ++k) {
    EXPECT_NEAR(steps[k].to, ends[k], 1e-12) << k;
    EXPECT_EQ(steps[k].checkpoint, k < 3) << k;
  }
}

// A resumed clock's next output is the one the uninterrupted clock had:
// the multiples of the interval, not counted from the start.
TEST(StepController, OutputsAreMultiplesAndResume) {
  StepController clock(0.35, 1.0, 1e-9);
  clock.output_every(0.25);
  EXPECT_NEAR(clock.plan(1.0).to, 0.5, 1e-12);
  StepController resumed(0.35, 1.0, 1e-9);
  resumed.output_every(0.25);
  resumed.resume(0.7);
  EXPECT_NEAR(resumed.plan(1.0).to, 0.75, 1e-12);
  EXPECT_NEAR(resumed.fraction_done(), (0.7 - 0.35) / 0.65, 1e-12);
}

} // namespace
} // namespace sartor
