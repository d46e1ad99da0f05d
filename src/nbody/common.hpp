// SPDX-License-Identifier: MIT
// calder::nbody internals shared by direct.cpp and barnes_hut.cpp:
// validation, threads, the law's parameters, the float32 frame.
#pragma once

#include <cstddef>
#include <span>

#include "calder/nbody.hpp"
#include "kernels.hpp"

namespace calder::nbody::detail {

// Throws calder::Error (naming `where`) unless the arrays have one size, the
// positions are finite, the masses finite and > 0, (ax, ay) do not overlap
// the inputs, and the options are valid.
void validate(const char* where, std::span<const double> x, std::span<const double> y,
              std::span<const double> mass, std::span<double> ax, std::span<double> ay,
              const Options& options);

// The number of threads to use for `options.threads` (>= 1).
int thread_count(const Options& options);

// Bodies in float32: p' = (p - centre) * scale and m' = m * mass_scale, with
// scale and mass_scale powers of two (exact), chosen so that |p'| <= 1 and
// m' <= 1. A sum S' of the float32 kernel is G * S in the caller's units
// with factor = G * scale^2 / mass_scale.
struct FloatFrame {
  double cx = 0.0;
  double cy = 0.0;
  double scale = 1.0;
  double mass_scale = 1.0;
  double factor = 1.0;
};
FloatFrame float_frame(std::span<const double> x, std::span<const double> y,
                       std::span<const double> mass, double G);
// The same from the bounding box's centre, its largest half side and the
// largest mass.
FloatFrame float_frame(double cx, double cy, double half, double max_mass, double G);

// The kernels' law parameters for the options, in both precisions (the
// float ones in the frame's units).
LawParams law_params(const Options& options, const FloatFrame& frame);

}  // namespace calder::nbody::detail
