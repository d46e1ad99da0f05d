// SPDX-License-Identifier: MIT
// Internal: the book's update for one body, shared by World::update, the
// whole-world semi-implicit Euler step and calder::bulk's kernels so that
// all give the same bits; and the periodic wrap of a coordinate.
#pragma once

#include <cmath>

#include "calder/vec2.hpp"

namespace calder::detail {

// Internal linkage: calder::bulk's kernels include this file in translation
// units built with other flags (-march, -ffp-contract=fast); an inline
// function shared across them could be merged by the linker into the core's
// calls and change its bits, or its instruction set.
namespace {

// velocity += acceleration * dt; position += velocity * dt; acceleration = 0.
// With dt = 1 the products are exact, so this is p5's vel.add(acc); pos.add(vel).
// (A template so that calder::bulk's float32 kernels share it.)
template <class Real>
inline void kick_drift(Real& x, Real& y, Real& vx, Real& vy, Real& ax, Real& ay, Real dt) {
  vx += ax * dt;
  vy += ay * dt;
  x += vx * dt;
  y += vy * dt;
  ax = Real{};  // zero (also for calder::bulk's vector types)
  ay = Real{};
}

// kick_drift with, when top_speed > 0, p5's vel.limit(topSpeed) between the
// kick and the drift (the book's Mover with a top speed); the World's update.
inline void book_update(double& x, double& y, double& vx, double& vy, double& ax, double& ay,
                        double dt, double top_speed) {
  if (top_speed <= 0.0) return kick_drift(x, y, vx, vy, ax, ay, dt);
  Vec2 v{vx + ax * dt, vy + ay * dt};
  v.limit(top_speed);
  vx = v.x;
  vy = v.y;
  x += vx * dt;
  y += vy * dt;
  ax = 0.0;
  ay = 0.0;
}

// Moves a coordinate that left [lo, hi] back in from the other side.
template <class Real>
inline Real wrap_coordinate(Real v, Real lo, Real hi) {
  const Real span = hi - lo;
  if (span <= Real(0)) return v;
  if (v > hi) {
    v -= span;
    if (v > hi) v = lo + std::fmod(v - lo, span);
  } else if (v < lo) {
    v += span;
    if (v < lo) v = hi - std::fmod(hi - v, span);
  }
  return v;
}

}  // namespace

}  // namespace calder::detail
