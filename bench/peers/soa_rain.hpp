// SPDX-License-Identifier: MIT
// The movers' floor: the rain scene's physics (gravity scaled by mass,
// quadratic drag, a bounce on the radius off the walls and the floor) as the
// plain structure-of-arrays loop anyone would write for it, one pass over the
// arrays per step, branch-free, compiled with -O3 -march=native -ffast-math
// (soa_rain_loop.cpp; a second copy with -mavx2 -mfma for the AVX2 column).
// Not calder code: what calder::bulk must at least match.
// One definition for bench_bulk, `calder bench` and their tests.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "calder/world.hpp"

namespace calder::peers {

// The loop's arrays and constants in one precision.
template <class R>
struct SoaRainState {
  std::vector<R> x, y, vx, vy, mass, radius;
  R width = 0, height = 0, gravity = 0, drag = 0, restitution = 0, dt = 1;
};

class SoaRain {
 public:
  // The rain world's bodies, canvas and fields, in float (float32) or double.
  // avx2: the copy compiled for AVX2 + FMA alone (16 vector registers), when
  // this build has it and the CPU runs it; else the -march=native one.
  // threads: each runs every step on its own slice of the arrays (OpenMP).
  SoaRain(const World& world, bool float32, bool avx2, int threads = 1);

  // `steps` steps of every body.
  void step(int steps);

  // "-O3 -march=native -ffast-math" or "-O3 -mavx2 -mfma -ffast-math".
  [[nodiscard]] const std::string& flags() const { return flags_; }

  // Positions and velocities, widened to double (tests compare with World).
  [[nodiscard]] std::vector<double> x() const;
  [[nodiscard]] std::vector<double> y() const;
  [[nodiscard]] std::vector<double> vx() const;
  [[nodiscard]] std::vector<double> vy() const;

 private:
  bool float32_;
  bool avx2_ = false;
  int threads_ = 1;
  std::string flags_;
  SoaRainState<float> f_;
  SoaRainState<double> d_;
};

// Whether this build has the AVX2 copy and the CPU can run it.
bool soa_rain_has_avx2();

}  // namespace calder::peers
