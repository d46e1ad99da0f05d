// SPDX-License-Identifier: MIT
// calder: the plug-in points for whole-world kernels, chosen per world.
//
// The core has no kernels of its own and no dependencies; calder::bulk
// (whole-world steps) and calder::nbody (fast mutual attraction) plug in
// here. A world takes them from its WorldDef::backends:
//
//   calder::World world({.backends = {.step_batch = calder::bulk::step_batch,
//                                     .mutual_attraction = calder::nbody::mutual_attraction}});
//
// A backend left null there is the process default: the kernels of the
// component libraries linked into the program. Linking calder::bulk or
// calder::nbody is all it takes; each registers itself before main (see
// docs/DESIGN.md, "Fast paths beside the book path").
#pragma once

#include <span>
#include <string>

namespace calder {

struct StepBatch;  // what World::step hands the kernels (src/step_batch.hpp)
struct MutualAttraction;
struct FieldContext;

// Runs batch.steps simultaneous semi-implicit Euler steps and returns true,
// or returns false, changing nothing, when it has no kernel for one of the
// fields (then *why_not, if given, names it). It may throw only before it
// changes anything. (calder::bulk::step_batch.)
using StepBatchBackend = bool (*)(const StepBatch& batch, std::string* why_not);

// Adds the pair accelerations of all bodies for a MutualAttraction field of
// method direct or barnes_hut (calder::nbody::mutual_attraction); the core
// has added the central body's pulls.
using MutualAttractionBackend = void (*)(const MutualAttraction& field, const FieldContext& context,
                                         std::span<double> ax, std::span<double> ay);

// A world's kernels; null: the process default (the linked component's).
struct Backends {
  StepBatchBackend step_batch = nullptr;
  MutualAttractionBackend mutual_attraction = nullptr;

  // Each one set here, or else the process default.
  [[nodiscard]] Backends or_defaults() const;
};

// The process defaults. A linked component sets its own while the program
// starts (its registration object, kept in by the component's link options);
// nothing else needs to. A program may replace one (null: none, the plain
// loops; a fast method or arithmetic then throws calder::Error at the step),
// as the tests do to compare the kernels with the plain loops.
void set_step_batch_backend(StepBatchBackend backend);
void set_mutual_attraction_backend(MutualAttractionBackend backend);

}  // namespace calder
