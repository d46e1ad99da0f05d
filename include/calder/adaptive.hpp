// SPDX-License-Identifier: MIT
// calder: what the adaptive integrator (Integrator::ias15) counts and what
// it carries from one World::step() to the next.
//
// IAS15 (Rein & Spiegel 2015; docs/DESIGN.md, "Integrators") is 15th order,
// so its error for smooth forces stays at the rounding of doubles. A
// World::step() of dt takes as many internal steps as it needs, the last
// ending exactly on the frame; a frame that would need more than 100,000
// throws calder::RunError (use a smaller dt).
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace calder {

// Counted since the world was made or restored (saved by snapshots).
struct AdaptiveStats {
  std::int64_t steps = 0;              // internal steps accepted
  std::int64_t rejected = 0;           // internal steps tried again shorter
  std::int64_t force_evaluations = 0;  // whole-world evaluations of the forces
  std::int64_t iterations = 0;         // predictor-corrector iterations
  double smallest_step = std::numeric_limits<double>::infinity();  // of the accepted steps
  // The smallest distance between two bodies at the end of an internal step,
  // and when: measured while the world has at most kClosestApproachBodies
  // bodies (pairs cost n^2 / 2 a step); infinity when never measured.
  double closest_approach = std::numeric_limits<double>::infinity();
  double closest_approach_time = 0.0;
};

// Worlds with more bodies than this don't measure the closest approach.
inline constexpr std::size_t kClosestApproachBodies = 256;

// What an adaptive world carries between steps. Coordinates are numbered
// x of every body, then y of every body (2n); the polynomial's 7
// coefficients are 7 blocks of 2n. Empty arrays: nothing carried yet (a
// fresh start, as after a change of the bodies).
struct AdaptiveState {
  double next_step = 0.0;           // the internal step to try next; 0: the frame's dt
  double last_step = 0.0;           // the last accepted internal step; 0: none (no prediction)
  double clock_compensation = 0.0;  // the world clock's Kahan term
  std::vector<double> position_compensation;  // 2n Kahan terms
  std::vector<double> velocity_compensation;  // 2n
  std::vector<double> coefficients;           // 7 x 2n: the last step's b
  std::vector<double> correction;             // 7 x 2n: b minus its prediction
  AdaptiveStats stats{};
};

}  // namespace calder
