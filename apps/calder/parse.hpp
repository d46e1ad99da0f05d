// SPDX-License-Identifier: MIT
// calder command: strict parsing of the numbers and ranges given as flags.
//
// Each function throws InputError with one line naming the flag, what was
// expected and what was given, e.g.
//   --frames: expected an integer from 0 to 10000000, got '-1'
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "calder/scene.hpp"
#include "calder/vec2.hpp"

namespace calder::app {

// The whole text as a decimal integer (optional sign), or nullopt.
std::optional<std::int64_t> to_int64(std::string_view text);
// The whole text as a double (as strtod reads it: "0.1", "1e-3"), or nullopt.
// "nan" and "inf" are numbers here (callers decide whether they are
// allowed); out of range ("1e400") is not.
std::optional<double> to_double(std::string_view text);

// --frames: an integer in 0..calder::max_frames.
std::int64_t parse_frames(const std::string& flag, const std::string& text);
// --dt: a finite number > 0.
double parse_dt(const std::string& flag, const std::string& text);
// An integrator by its scene-file name (semi_implicit_euler, ..., ias15).
Integrator parse_integrator(const std::string& flag, const std::string& text);
// --seed: an integer in 0..2^32-1.
std::uint32_t parse_seed(const std::string& flag, const std::string& text);
// --mouse-pressed: "FIRST-LAST" (1 <= FIRST <= LAST <= max_frames), or "none"
// (an empty result).
std::vector<FrameRange> parse_frame_range(const std::string& flag, const std::string& text);
// --mouse: "X,Y", both finite.
Vec2 parse_point(const std::string& flag, const std::string& text);

}  // namespace calder::app
