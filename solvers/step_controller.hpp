#pragma once
// The clock of a stepping loop: statics' load ramp (over the fraction of
// the load), dynamics and creep (over time) step by it. It ends steps on the
// end, on the times events fall on (load knots, body motions, pin releases)
// and on periodic events that land steps (outputs; creep's checkpoints),
// merges a sliver before such a time into the step, and says which periodic
// events a step reached. The length of the next attempt after an accepted or
// a rejected step, and when to give up, are each solver's own rule (creep's
// tolerance, halving).
//
// Dynamics kept a landing of its own until its step rejections stopped
// hinging on round-off (a time step SNES fails is minimised instead,
// IncrementalSystem::solve): on this clock its time grid moved by round-offs
// (outputs at exact multiples, steps of exactly dt), and the coarse skirt's
// dynamic drape then rejected a step natively that it accepted under
// OPENBLAS_CORETYPE=Prescott (reliability.prescott_drape_skirt_dynamic).

#include <cmath>
#include <vector>

namespace sartor {

// An event at every multiple of an interval (none without an interval). Times within `tiny` of one
// count as on it.
class PeriodicEvent {
public:
  // Whether steps must end on the event, or it is taken at the first step
  // that reaches it (a checkpoint that should not change the answer).
  enum class Landing { steps_end_on_it, first_step_past_it };

  PeriodicEvent() = default; // never
  PeriodicEvent(double interval, double tiny, Landing landing)
      : interval_(interval), tiny_(tiny), landing_(landing) {}

  bool periodic() const { return interval_ > 0.0; }
  bool lands_steps() const { return landing_ == Landing::steps_end_on_it; }
  double next() const { return next_; }
  bool reached(double time) const { return time >= next_ - tiny_; }

  // The next event is the first multiple after `time`.
  void passed(double time) {
    next_ = periodic() ? (std::floor((time + tiny_) / interval_) + 1.0) * interval_ : INFINITY;
  }

private:
  double interval_ = 0.0;
  double tiny_ = 0.0;
  Landing landing_ = Landing::first_step_past_it;
  double next_ = INFINITY;
};

// One attempt from the clock's time: to `to`, of `length` (to minus the
// time, or exactly the length asked for when no landing cut it).
struct StepPlan {
  double to = 0.0;
  double length = 0.0;
  bool shortened = false; // cut short of the length asked for, to land on a time
};

class StepController {
public:
  // From `start` to `end`; times closer than `tiny` are the same time;
  // `landings` are the event times steps end on (any order; those outside
  // (start, end) are never reached).
  StepController(double start, double end, double tiny, std::vector<double> landings = {});

  // Outputs at the multiples of `interval`, which steps end on; every step
  // without an interval.
  void output_every(double interval);
  // Checkpoints at the multiples of `interval` (none without one).
  void checkpoint_every(double interval, PeriodicEvent::Landing landing);
  // The clock continues from `time` (a resumed run); the periodic events
  // are the first multiples after it.
  void resume(double time);

  double time() const { return time_; }
  double tiny() const { return tiny_; }
  bool finished() const { return time_ >= end_ - tiny_; }
  // Of the way from the start to the end (1 once finished), for progress.
  double fraction_done() const { return finished() ? 1.0 : (time_ - start_) / (end_ - start_); }
  // Of the steps of a run whose steps grow about geometrically from
  // `first_step` (creep, as it slows): log(1 + t / first_step) over
  // log(1 + T / first_step), t and T from the start; for progress estimates.
  double geometric_fraction_done(double first_step) const {
    if (finished()) return 1.0;
    return std::log1p((time_ - start_) / first_step) / std::log1p((end_ - start_) / first_step);
  }

  // The next attempt for a step of `asked` length: it ends on the first of
  // the end, the next landing and the next landing periodic event when that
  // comes within the step, or within 1e-3 of its length after it.
  StepPlan plan(double asked) const;

  // The plan's step was accepted: the clock is at its end. Whether that is
  // an output (every step without an output interval, and the last) or a
  // checkpoint is asked then; passing an event moves it past the time.
  void accept(const StepPlan& step) { time_ = step.to; }
  bool output_due() const { return !outputs_.periodic() || outputs_.reached(time_) || finished(); }
  bool checkpoint_due() const { return checkpoints_.reached(time_); }
  void pass_output() { outputs_.passed(time_); }
  void pass_checkpoint() { checkpoints_.passed(time_); }

private:
  double next_landing() const;

  double start_;
  double end_;
  double tiny_;
  double time_;
  std::vector<double> landings_; // sorted
  PeriodicEvent outputs_;
  PeriodicEvent checkpoints_;
};

} // namespace sartor
