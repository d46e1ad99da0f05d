// SPDX-License-Identifier: MIT
// The movers benchmark's worlds: the built-in scene "rain" (scenes/rain.toml)
// with N drops on a canvas grown with N so that the density stays that of
// the scene (1000 drops on 640 x 240), and Box2D running the same bodies.
// One definition for bench_bulk, `calder bench` and their tests.
#pragma once

#include <cstddef>

#include "calder/world.hpp"
#include "peers/box2d_rain.hpp"

namespace calder::peers {

// The rain scene with `drops` drops, its canvas scaled by sqrt(drops / 1000).
World rain_world(std::size_t drops, Arithmetic arithmetic = Arithmetic::book, int threads = 0);

// Box2D mirroring a rain world's bodies, canvas and fields.
Box2dRain box2d_rain(const World& world, Box2dBodies kind);

}  // namespace calder::peers
