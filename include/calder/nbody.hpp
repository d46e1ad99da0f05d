// SPDX-License-Identifier: MIT
// calder::nbody: fast mutual attraction (the n-body problem) over contiguous
// arrays, for worlds with thousands to millions of bodies.
//
// Everything here reads bodies as separate arrays (x, y, mass: the World's own
// layout) and ADDS the accelerations
//
//     a_i += sum_{j != i} F(i, j) / m_i  =  G sum_{j != i} m_j (p_j - p_i) w(|p_j - p_i|)
//
// to (ax, ay), for one of the laws of calder/forces.hpp:
//
//     Law::plummer                 |F| = G m_i m_j r / (r^2 + eps^2)^(3/2)
//     Law::clamp_distance          |F| = G m_i m_j / d^2,  d = clamp(r, min, max)  (the book)
//     Law::clamp_squared_distance  |F| = G m_i m_j / q,    q = clamp(r^2, min, max) (ex. 2.16)
//
// A body exerts no force on itself, nor on a body at exactly the same place
// (no direction), as calder::attraction does; with Plummer softening eps > 0
// that force is zero anyway.
//
// Three ways to sum: reference_accelerations (plain double loops, the
// specification), direct_accelerations (the same O(n^2) sum, vectorised and
// threaded, float64 or float32) and BarnesHut (O(n log n), approximate).
//
// Results are bit-identical for any number of threads. They differ in the
// last bits between instruction sets (kernel_name()) and from the reference:
// these kernels are for physics; reproducing p5.js bit for bit is the core's
// job (docs/DESIGN.md, "Fast paths beside the book path").
//
// Bad input (arrays of different sizes, a non-finite position, a mass that is
// not finite and > 0, a bad option) throws calder::Error and leaves ax, ay
// unchanged. ax and ay must not overlap x, y or mass.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "calder/backends.hpp"
#include "calder/fields.hpp"
#include "calder/forces.hpp"
#include "calder/vec2.hpp"

namespace calder::nbody {

enum class Precision {
  // Pair sums in float32, positions relative to the bodies' centre as two
  // floats: relative error against float64 RMS 6e-8 to 9e-7, max < 6e-5
  // (disks and clumps of 10^3 to 1.6 10^4 bodies).
  float32,
  // Pair sums in double: relative error ~1e-15 (RMS) against the reference.
  float64,
};

// The laws are the core's (calder/forces.hpp), by their kernel names:
// Law::plummer, Law::clamp_distance, Law::clamp_squared_distance.
using Law = DistanceClamp;

struct Options {
  double G = 1.0;
  Law law = Law::plummer;
  double softening = 0.0;      // Plummer epsilon (Law::plummer), >= 0
  double min_distance = 5.0;   // clamp bounds (the clamped laws): 0 < min <= max; for
  double max_distance = 25.0;  // clamp_squared_distance they bound the squared distance
  Precision precision = Precision::float64;
  // 0: OpenMP's default (all cores); n > 0: n threads. Small problems (direct
  // sums under 320 bodies, trees under 2000) run on one thread.
  int threads = 0;
};

// The work each thread of one parallel region did, in the region's unit
// (pairs, interactions, bodies, keys, nodes), counted by the share it
// belongs to: work goes to threads by rules of the thread count alone, so
// a 2-core machine running 16 threads sees the balance of a 16-core run
// (docs/DESIGN.md, "Fast paths beside the book path").
struct ThreadWork {
  const char* region = "";
  const char* unit = "";
  std::vector<std::uint64_t> per_thread;
  // max / mean - 1 (0: perfectly balanced; 0 when there is no work).
  double imbalance() const;
};

// What a direct_accelerations call did, when asked for.
struct DirectStats {
  std::size_t bodies = 0;
  bool pairs_once = false;  // each pair evaluated once for both bodies
  std::vector<ThreadWork> work;
};

// The options for a calder::AttractionLaw (its G, clamp, bounds, softening).
// Throws calder::Error for the laws without a kernel: a custom law, an
// exponent other than 2, a repulsive core. (MassProduct, the grouping of
// G M m that sets the book's last bits, does not apply.)
Options options_for(const AttractionLaw& law);

// O(n^2) direct summation, vectorised and threaded: (ax, ay) += accelerations.
// stats, when given, receives the per-thread work (pairs evaluated).
void direct_accelerations(std::span<const double> x, std::span<const double> y,
                          std::span<const double> mass, std::span<double> ax, std::span<double> ay,
                          const Options& options = {}, DirectStats* stats = nullptr);

// The specification: plain loops in double, one pair at a time, sources in
// index order (options.precision and options.threads are ignored).
void reference_accelerations(std::span<const double> x, std::span<const double> y,
                             std::span<const double> mass, std::span<double> ax,
                             std::span<double> ay, const Options& options = {});
// The reference acceleration of body `target` alone (O(n)), e.g. to check a
// sample of bodies of a large system.
Vec2 reference_acceleration(std::span<const double> x, std::span<const double> y,
                            std::span<const double> mass, std::size_t target,
                            const Options& options = {});

// --- Barnes-Hut -----------------------------------------------------------------

struct BarnesHutOptions : Options {
  // Opening angle, in [0, 1]: a node of side s whose centre of mass lies at
  // distance d from a group of bodies (from the group's bounding box) acts
  // on all of them through its multipole expansion when s / (d - delta) <
  // theta, delta the distance from the centre of mass to the cell's centre
  // (Barnes' modified criterion). Smaller is more accurate and slower; 0 is
  // the direct sum. RMS relative error at the default, 0.7: about 6.6e-4 on
  // uniform disks of 2000 to 10^6 bodies, falling about as theta^5; the
  // clamped laws (monopoles only) about 1e-2 (docs/PERFORMANCE.md).
  double theta = kDefaultTheta;
  int leaf_size = 32;    // a node with at most this many bodies is not split
  int group_size = 128;  // bodies of a node with at most this many share one tree walk
  // Float64, Plummer law: each run of this many of a group's targets takes
  // as multipoles the opened leaves its own box accepts (fewer pairs, a
  // little more error). -1: kernel_target_block(); 0: never. Float32 and
  // the clamped laws ignore it.
  int target_block = -1;
};

struct BarnesHutStats {
  std::size_t bodies = 0;
  std::size_t nodes = 0;
  std::size_t leaves = 0;
  std::size_t groups = 0;
  int depth = 0;                        // of the deepest node (root: 0)
  std::uint64_t interactions = 0;       // target-source pairs evaluated (nodes and bodies)
  std::uint64_t node_interactions = 0;  // of which with nodes (multipole expansions)
  double build_seconds = 0.0;           // bounding box, Morton sort, tree, moments
  double walk_seconds = 0.0;            // tree walks, pair sums, back to the caller's order
  // The build's phases in order, wall seconds each (the team waits for the
  // slowest thread at the end of each); a serial phase runs on one thread
  // while the others wait: what limits the build's speedup.
  struct Phase {
    const char* name = "";
    double seconds = 0.0;
    bool serial = false;
  };
  std::vector<Phase> build_phases;
  // Per parallel region of the build and the walk, each thread's work.
  std::vector<ThreadWork> work;
};

// A Barnes-Hut solver that keeps its tree and buffers between calls: once
// they have grown to the bodies' size, a call on one thread allocates
// nothing (about 180 bytes a body). The tree is a quadtree in Morton order,
// each node the smallest cell of its bodies, split while it has more than
// leaf_size; nodes act through multipole expansions to fourth order (Plummer
// law; monopoles for the clamped laws); each group of <= group_size bodies
// walks it once (docs/DESIGN.md). One solver serves one caller at a time.
class BarnesHut {
 public:
  BarnesHut();
  ~BarnesHut();
  BarnesHut(BarnesHut&&) noexcept;
  BarnesHut& operator=(BarnesHut&&) noexcept;
  BarnesHut(const BarnesHut&) = delete;
  BarnesHut& operator=(const BarnesHut&) = delete;

  // (ax, ay) += approximate accelerations.
  void accelerations(std::span<const double> x, std::span<const double> y,
                     std::span<const double> mass, std::span<double> ax, std::span<double> ay,
                     const BarnesHutOptions& options = {});

  // About the last call.
  const BarnesHutStats& stats() const;

 private:
  struct Workspace;
  std::unique_ptr<Workspace> workspace_;
};

// One-off Barnes-Hut evaluation (allocates a BarnesHut for the call).
void barnes_hut_accelerations(std::span<const double> x, std::span<const double> y,
                              std::span<const double> mass, std::span<double> ax,
                              std::span<double> ay, const BarnesHutOptions& options = {},
                              BarnesHutStats* stats = nullptr);

// --- the World's fast methods -----------------------------------------------------

// NBodyMethod::direct and barnes_hut for MutualAttraction fields, as a
// MutualAttractionBackend (calder/backends.hpp) for
// WorldDef::backends.mutual_attraction: the field's law goes through
// options_for (a custom law throws calder::Error at the step),
// single_precision selects float32, threads and theta pass through.
// Barnes-Hut keeps one solver per calling thread.
void mutual_attraction(const MutualAttraction& field, const FieldContext& context,
                       std::span<double> ax, std::span<double> ay);
// Linking calder::nbody makes it the process default of worlds that name
// none (src/nbody/install.cpp): no call needed.

// --- about the build --------------------------------------------------------------

// The instruction set of the kernels in use: "avx512", "avx2+fma", "sse2",
// "generic". A build with CALDER_PORTABLE=ON holds several and picks the
// best the CPU supports (the environment variable CALDER_KERNELS=
// avx512|avx2|baseline, read once, lowers the choice, for benchmarks).
const char* kernel_name();
// What BarnesHutOptions::target_block = -1 means with these kernels: 16
// with the 256-bit ones ("avx2+fma", "avx"), 0 with the others.
int kernel_target_block();
// The number of threads that threads = 0 means (1 without OpenMP).
int max_threads();

}  // namespace calder::nbody
