// SPDX-License-Identifier: MIT
// calder command: the summary `calder run` prints without --trajectory.
#pragma once

#include <cstdint>
#include <functional>
#include <ostream>
#include <string>

#include "calder/diagnostics.hpp"
#include "calder/scene.hpp"

namespace calder::app {

// Prints, one per line, aligned: scene, frames, bodies, dt, seed, kinetic
// energy, potential energy of the world's fields ("n/a" with the reason when
// a field's law has no known potential), total energy, linear momentum,
// angular momentum about the origin and the state hash (16 hex digits).
// Numbers in shortest round-trip form. The potential energy sums at most
// summary_potential_pairs pairs of each mutual attraction; past that it is a
// sampled estimate, printed with "~" and how many pairs it drew. A value that
// overflows (inf, nan) is a failed run: throws RunError naming `source` and
// the frame, and prints nothing. `before_printing` (e.g. a check for a
// signal that came during the sums) runs between the sums and the printing.
// With `energy`, also the relative energy error since the start (and the
// worst, and the frame it passed the threshold); with ias15, its internal
// steps, force evaluations, smallest step and closest approach.
void print_summary(std::ostream& out, const Simulation& simulation, std::uint32_t seed,
                   const std::string& source,
                   const std::function<void()>& before_printing = nullptr,
                   const EnergyWatch* energy_watch = nullptr);

// At most this many pairs (about half a second) are summed exactly.
constexpr std::uint64_t summary_potential_pairs = std::uint64_t{1} << 25;

// The pair and body terms the summary's potential energy evaluates (for the
// work budget).
std::uint64_t summary_potential_cost(const World& world);

}  // namespace calder::app
