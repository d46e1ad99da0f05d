// SPDX-License-Identifier: MIT
// calder: forces in 2D, after chapter 2 of The Nature of Code.
// One include for the core, everything a book-style program or a sketch
// uses: vectors, worlds and movers, force laws, fields, randomness,
// diagnostics, real time, trajectories and built-in scenes. Snapshots
// (calder/snapshot.hpp) and the components (calder/sketch.hpp, render.hpp,
// scene_file.hpp, nbody.hpp, bulk.hpp, gpu.hpp) have their own headers.
#pragma once

#include "calder/detmath.hpp"
#include "calder/diagnostics.hpp"
#include "calder/error.hpp"
#include "calder/fields.hpp"
#include "calder/fixed_step.hpp"
#include "calder/forces.hpp"
#include "calder/random.hpp"
#include "calder/scene.hpp"
#include "calder/trajectory.hpp"
#include "calder/vec2.hpp"
#include "calder/version.hpp"
#include "calder/world.hpp"
