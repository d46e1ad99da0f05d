// SPDX-License-Identifier: MIT
#include "calder/fixed_step.hpp"

#include <string>

#include "calder/error.hpp"
#include "calder/world.hpp"

namespace calder {

FixedStep::FixedStep(double steps_per_second, int max_steps)
    : steps_per_second_(steps_per_second), max_steps_(max_steps) {
  detail::require_positive(steps_per_second, "FixedStep", "steps_per_second");
  if (max_steps < 1) {
    throw Error("FixedStep: max_steps must be >= 1 (got " + std::to_string(max_steps) + ")");
  }
}

void FixedStep::set_steps_per_second(double steps_per_second) {
  detail::require_positive(steps_per_second, "FixedStep::set_steps_per_second", "steps_per_second");
  steps_per_second_ = steps_per_second;
}

int FixedStep::advance(World& world, double elapsed_seconds) {
  return advance(elapsed_seconds, [&world] { world.step(); });
}

int FixedStep::advance(double elapsed_seconds, const std::function<void()>& step) {
  detail::require_non_negative(elapsed_seconds, "FixedStep::advance", "elapsed_seconds");
  const double step_seconds = 1.0 / steps_per_second_;
  accumulator_ += elapsed_seconds;
  int steps = 0;
  while (accumulator_ >= step_seconds && steps < max_steps_) {
    step();
    accumulator_ -= step_seconds;
    ++steps;
  }
  if (steps == max_steps_ && accumulator_ >= step_seconds) {
    accumulator_ = 0.0;  // behind by more than max_steps: drop the backlog
  }
  return steps;
}

}  // namespace calder
