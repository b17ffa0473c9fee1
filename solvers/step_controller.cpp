#include "solvers/step_controller.hpp"

#include <algorithm>
#include <utility>

namespace sartor {

StepController::StepController(double start, double end, double tiny, std::vector<double> landings)
    : start_(start), end_(end), tiny_(tiny), time_(start), landings_(std::move(landings)) {
  std::sort(landings_.begin(), landings_.end());
}

void StepController::output_every(double interval) {
  outputs_ = PeriodicEvent(interval, tiny_, PeriodicEvent::Landing::steps_end_on_it);
  outputs_.passed(time_);
}

void StepController::checkpoint_every(double interval, PeriodicEvent::Landing landing) {
  checkpoints_ = PeriodicEvent(interval, tiny_, landing);
  checkpoints_.passed(time_);
}

void StepController::resume(double time) {
  time_ = time;
  outputs_.passed(time_);
  checkpoints_.passed(time_);
}

double StepController::next_landing() const {
  const auto after = std::upper_bound(landings_.begin(), landings_.end(), time_ + tiny_);
  return after == landings_.end() ? INFINITY : *after;
}

StepPlan StepController::plan(double asked) const {
  double target = std::min(end_, next_landing());
  for (const PeriodicEvent* event : {&outputs_, &checkpoints_})
    if (event->lands_steps()) target = std::min(target, event->next());
  StepPlan step;
  step.length = std::min(asked, target - time_);
  // No sliver is left before a landing: the step reaches it.
  if (target - time_ - step.length < 1e-3 * step.length) step.length = target - time_;
  step.shortened = step.length < asked;
  step.to = step.length == target - time_ ? target : time_ + step.length;
  return step;
}

} // namespace sartor
