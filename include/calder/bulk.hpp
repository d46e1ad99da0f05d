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
// How: the fields are compiled once per batch into a list of ops (plan.cpp:
// one op per enabled field). The bodies are cut into tiles of kTile; one
// thread copies a tile's columns into an L1-resident chunk (in the batch's
// precision) and advances it through the whole batch of steps
// (World::kBatchSteps): each step is one pass over the chunk per op, the
// last op's pass fused with the update and the boundary, each pass a loop
// over vectors of bodies (AVX-512, AVX2 + FMA or SSE2, as calder::nbody's
// kernels; details in src/bulk/kernels_impl.hpp). Bodies don't interact,
// so no order between tiles matters: results are bit-identical for any
// number of threads, and there is no broad phase to pay for.
//
// Arithmetic (WorldDef::arithmetic):
//   book     the same operations in the same order as the plain loops (no
//            fused multiply-adds: that file is compiled with
//            -ffp-contract=off), so the same bits: p5.js sketches still
//            reproduce their references exactly;
//   float64  a / m as a * (1 / m), (g m) / m as g, drag as -c |v| v / m, fused
//            multiply-adds;
//   float32  the float64 formulas in float, state rounded to float for the
//            batch. Errors against book: docs/PERFORMANCE.md.
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
