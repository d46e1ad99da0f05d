// SPDX-License-Identifier: MIT
// The n-body benchmarks' bodies and their yardstick: a uniform disk and a set
// of clumps, and the relative force error of an approximate sum (Barnes-Hut)
// against the direct float64 sum on a sample of bodies.
// One definition for bench_nbody, `calder bench` and their tests.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "calder/nbody.hpp"

namespace calder::peers {

struct NBodySystem {
  std::vector<double> x;
  std::vector<double> y;
  std::vector<double> m;
  std::size_t size() const { return x.size(); }
};

// N bodies uniform in a disk of radius 50 * sqrt(N / 1000) (the density of
// 1000 bodies in radius 50), masses in [0.5, 1.5).
NBodySystem disk(std::size_t n, std::uint64_t seed);

// N bodies in 8 Plummer-like clumps of scale 1 to 5 spread over 200 x 200.
NBodySystem clusters(std::size_t n, std::uint64_t seed);

// Plummer softening for the disks: half their mean spacing
// (sqrt(pi) 50 / sqrt(1000) / 2).
inline constexpr double kDiskSoftening = 1.4;

// The exact accelerations of some bodies of a system: all of them (direct
// float64 sum) when `sample` >= its size, else of `sample` bodies drawn at
// random (reference_acceleration, plain double loops; seed 7).
struct ExactSample {
  std::vector<std::size_t> bodies;  // where the error is measured
  std::vector<double> ax;           // their exact accelerations
  std::vector<double> ay;
};
ExactSample exact_sample(const NBodySystem& system, const nbody::Options& options,
                         std::size_t sample);

// Relative error |a - exact| / |exact| over the sampled bodies; and what
// the RMS is made of: the bodies of weak pull (|exact| below an eighth of the
// sample's median, e.g. near a disk's centre) divide an error of ordinary
// size by a small one.
struct ForceError {
  double rms = 0.0;
  double max = 0.0;
  double weak_share = 0.0;  // of the squared relative errors' sum, the weak bodies' part
  double abs_rms = 0.0;     // RMS of |a - exact| / the median |exact|
};
ForceError force_error(const ExactSample& exact, std::span<const double> ax,
                       std::span<const double> ay);

}  // namespace calder::peers
