// SPDX-License-Identifier: MIT
// calder: a fixed time step for real-time use.
//
// A window redraws at the display's rate, which varies; physics stays
// reproducible when it always advances in the same step. FixedStep collects
// real elapsed time and runs as many whole world steps as fit, carrying the
// remainder ("fix your timestep", Glenn Fiedler, 2004). alpha() tells how far
// the leftover time is into the next step, for drawing in between.
#pragma once

#include <functional>

namespace calder {

class World;

class FixedStep {
 public:
  // steps_per_second: world steps per second of real time (60 runs the book's
  // sketches at their frame rate). max_steps: most steps one advance() runs;
  // time beyond that is dropped, so a slow frame cannot snowball.
  explicit FixedStep(double steps_per_second = 60.0, int max_steps = 8);

  // Adds elapsed_seconds (>= 0) of real time and steps the world; returns the
  // number of steps taken.
  int advance(World& world, double elapsed_seconds);
  // The same for anything that steps: calls step() once per step due (a
  // Simulation, so that its mouse bindings run every step).
  int advance(double elapsed_seconds, const std::function<void()>& step);

  // Fraction of a step in the carried-over time, in [0, 1).
  [[nodiscard]] double alpha() const { return accumulator_ * steps_per_second_; }
  [[nodiscard]] double steps_per_second() const { return steps_per_second_; }
  // Speeds the simulation up or down (the window's + and - keys).
  void set_steps_per_second(double steps_per_second);
  // Drops carried-over time (e.g. after a pause).
  void reset() { accumulator_ = 0.0; }

 private:
  double steps_per_second_;
  int max_steps_;
  double accumulator_ = 0.0;
};

}  // namespace calder
