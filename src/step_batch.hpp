// SPDX-License-Identifier: MIT
// calder internals: what World::step hands a StepBatchBackend
// (calder/backends.hpp): the batch the kernels of calder::bulk and
// calder::gpu step.
#pragma once

#include <cstddef>
#include <deque>
#include <span>

#include "calder/body_columns.hpp"
#include "calder/fields.hpp"
#include "calder/world.hpp"

namespace calder {

// Everything a whole-world batch of steps reads and writes.
struct StepBatch {
  BodyColumnsOf<std::span<double>, std::span<const double>> bodies;
  const std::deque<Field>* fields = nullptr;
  Boundary boundary{};
  double width = 640.0;
  double height = 240.0;
  double dt = 1.0;
  double time = 0.0;  // of the first step; each next one adds dt
  int steps = 1;
  Arithmetic arithmetic = Arithmetic::book;
  int threads = 0;
  const Noise* noise = nullptr;
  // Before advancing them, the backend copies the state columns into saved
  // (kStateColumns n doubles: all x, then all y, ...), so that the world can
  // undo the batch; afterwards it sets *first_non_finite to the lowest index
  // of a body whose position or velocity is not finite (n if none). Done tile
  // by tile in the backend's threads, not serially by the world.
  double* saved = nullptr;
  std::size_t* first_non_finite = nullptr;
};

}  // namespace calder
