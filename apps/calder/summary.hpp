// SPDX-License-Identifier: MIT
// calder command: the summary `calder run` prints without --trajectory.
#pragma once

#include <cstdint>
#include <ostream>

#include "calder/scene.hpp"

namespace calder::app {

// Prints, one per line, aligned: scene, frames, bodies, dt, seed, kinetic
// energy, potential energy of the world's fields ("n/a" with the reason when
// a field's law has no known potential), total energy, linear momentum,
// angular momentum about the origin and the state hash (16 hex digits).
// Numbers in shortest round-trip form.
void print_summary(std::ostream& out, const Simulation& simulation, std::uint32_t seed);

}  // namespace calder::app
