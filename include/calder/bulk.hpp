// SPDX-License-Identifier: MIT
// calder::bulk: whole-world kernels for the per-body fields, for worlds of
// thousands to millions of movers that don't interact (rain, particles,
// crowds under wind and drag).
//
// A program linked with calder::bulk hands the large steps of its worlds,
// World::step(count), to these kernels instead of stepping body by body
// through the fields (the library registers them as the process default of
// calder/backends.hpp; a world may name other kernels in
// WorldDef::backends.step_batch):
//
//   calder::World world({.arithmetic = calder::Arithmetic::float32});
//   ... add 100000 bodies, Gravity, Drag, a bounce boundary ...
//   world.step(1000);                     // vectorised, threaded, cache-blocked
//
// What they run: semi-implicit Euler, the simultaneous update order, every
// field kind with a per-body law (an Attractor with the inverse-square laws:
// the book clamp, the squared clamp, Plummer), the bounce, wrap or no
// boundary: all kinds but MutualAttraction and CustomForce, which step body
// by body as before (unsupported() says why).
//
// How: each tile of kTile bodies stays in the L1 cache through a whole
// batch of World::kBatchSteps steps, a vector of bodies at a time; results
// are bit-identical for any number of threads (docs/DESIGN.md). With
// Arithmetic::book the bits are the plain loops' (p5.js sketches still
// reproduce their references exactly); float64 and float32 are the fast
// forms of the same physics (errors: docs/PERFORMANCE.md).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "calder/world.hpp"

namespace calder::bulk {

// Bodies per tile (one thread, one cache-resident block).
inline constexpr std::size_t kTile = 256;

// The kernels as a StepBatchBackend (calder/backends.hpp), for
// WorldDef::backends.step_batch.
bool step_batch(const StepBatch& batch, std::string* why_not);

// Whether the kernels can step this world: "" when they can, otherwise why
// not (e.g. "field custom_force has no kernel").
std::string unsupported(const World& world);

// The instruction set of the kernels in use ("avx512", "avx2+fma", "sse2",
// "wasm-simd128", "generic"; see calder::nbody::kernel_name()).
const char* kernel_name();

// The number of threads that threads = 0 means (1 without OpenMP).
int max_threads();

// The tiles of each thread's share in the calling thread's last step_batch,
// by thread (the team's size). Tiles go to threads in equal contiguous
// shares, decided by the thread count alone: the counts show the balance of
// any thread count on any machine. (A thread done with its share takes
// unstarted tiles of the others'; they still count for their share.)
std::vector<std::size_t> last_batch_tiles();

}  // namespace calder::bulk
