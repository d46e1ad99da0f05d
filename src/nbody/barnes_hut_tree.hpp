// SPDX-License-Identifier: MIT
// calder::nbody's Barnes-Hut internals: the tree that a build hands to the
// walk, and what both sides use. The pieces, one file each:
//   barnes_hut_builder.hpp   the fast build (TreeBuilder), in three files:
//     barnes_hut_sort.cpp      bounding square, Morton codes, their radix sort
//     barnes_hut_build.cpp     the tree over the sorted bodies, its parallel parts
//     barnes_hut_moments.cpp   moments and opening radii; the kernels' moments
//   build_kernels.cpp        the build's loops over every body, per instruction set
//   barnes_hut_reference.cpp the plain serial build: the same tree, for few
//                            bodies and as the tests' oracle
//   barnes_hut_walker.hpp    the walk (Walker, barnes_hut_walk.cpp): per group
//                            the tree walk, the kernels' sums, the far field
//   barnes_hut.cpp           the public entry points, which run the steps
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <new>
#include <span>
#include <utility>
#include <vector>

#include "build_kernels.hpp"
#include "calder/nbody.hpp"
#include "common.hpp"

namespace calder::nbody::bh {

// Per node, as the multipole kernels read them (kernels.hpp): m, 3 Q (3),
// 1.5 tr Q, 7.5 O (4), 1.5 P (2), 17.5 H (5), 7.5 tr H (3), 1.875 tr tr H.
inline constexpr std::size_t kMoments = 20;
// From this many bodies every step (sort, tree, moments, walk) uses threads;
// below, waking them costs more than they save, and the tree is built by the
// reference build (barnes_hut_reference.cpp).
inline constexpr std::size_t kParallelFrom = 2000;

// The number of threads for a step over n bodies.
inline int team_for(std::size_t n, int threads) { return n < kParallelFrom ? 1 : threads; }

// The parallel regions of a step, whose per-thread work BarnesHutStats::work
// reports (ThreadWork's region and unit): work[region * team + t].
enum Region : int {
  kRegionBodies,    // bounding box, Morton codes, the first radix pass: bodies
  kRegionSplit,     // the team's further radix passes: keys
  kRegionRanges,    // ranges sorted by one thread, bodies gathered: keys
  kRegionSubtrees,  // subtrees built, with their sort ranges or after: bodies
  kRegionNodes,     // subtrees' nodes placed, kernel moments: nodes
  kRegionWalk,      // tree walks and sums: interactions
  kRegionScatter,   // sums back to the caller's order: bodies
  kRegions,
};
inline constexpr const char* kRegionNames[kRegions][2] = {
    {"bounds, Morton codes, first radix pass", "bodies"},
    {"further radix passes", "keys"},
    {"sorted ranges, bodies in Morton order", "keys"},
    {"subtrees", "bodies"},
    {"subtree nodes and moments", "nodes"},
    {"walk", "interactions"},
    {"scatter", "bodies"},
};

// Memory for UnsetAllocator (buffers.cpp): a large block on transparent
// huge pages where the system has them.
void* allocate_buffer(std::size_t bytes, std::size_t align);
void free_buffer(void* block, std::size_t bytes, std::size_t align) noexcept;

// An allocator whose resize leaves new numbers unset: for arrays that a
// step writes in full, every call, in parallel (zeroing them first would be
// a serial pass over memory that each thread then writes again, and would
// put every page on the memory node of the thread that zeroed it). Large
// arrays go on huge pages (allocate_buffer).
template <typename T>
struct UnsetAllocator : std::allocator<T> {
  template <typename U>
  struct rebind {
    using other = UnsetAllocator<U>;
  };
  UnsetAllocator() = default;
  template <typename U>
  explicit UnsetAllocator(const UnsetAllocator<U>&) noexcept {}
  T* allocate(std::size_t count) {
    if (count > std::numeric_limits<std::size_t>::max() / sizeof(T))
      throw std::bad_array_new_length();
    return static_cast<T*>(allocate_buffer(count * sizeof(T), alignof(T)));
  }
  void deallocate(T* p, std::size_t count) noexcept {
    free_buffer(p, count * sizeof(T), alignof(T));
  }
  template <typename U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};
template <typename T>
using UnsetVector = std::vector<T, UnsetAllocator<T>>;

// The root square's lower corner and side.
struct Square {
  double x0 = 0.0;
  double y0 = 0.0;
  double side = 1.0;
};

// What the walk reads of a node.
// No default values: the build writes every field of every node (Node{}
// is all zeros), and a tree's nodes are not zeroed before (UnsetVector).
struct Node {
  double mx;  // centre of mass
  double my;
  double open2;         // accepted for a group farther than sqrt(open2) from (mx, my)
  std::uint32_t begin;  // bodies [begin, end) in Morton order
  std::uint32_t end;
  std::uint32_t child;     // first child (children are contiguous)
  std::uint32_t children;  // 0: a leaf
};

// What a build needs of the options.
struct BuildSettings {
  std::size_t leaf_size = 1;
  std::size_t group_size = 1;
  double inv_theta = 0.0;  // 1 / theta, +inf for theta = 0
  bool single = false;     // float32 sums: float32 masses and moments in the frame
  double G = 1.0;          // the float32 frame's factor
  int threads = 1;
};
BuildSettings build_settings(const BarnesHutOptions& options);

// A built tree: what crosses from the build to the walk.
//
// The tree's contract (which every build keeps, and the tests check against
// the reference build): bodies sorted by their 48-bit Morton code in the
// root square, leaves in Morton order and each leaf's bodies in index order;
// every node the smallest quadtree cell that holds its bodies, split into its
// non-empty quadrants (children contiguous, in quadrant order) while it holds
// more than leaf_size bodies of more than one code; the groups, in Morton
// order, the first node on each path from the root with at most group_size
// bodies (or a leaf); each node's mass, centre of mass, moments about it and
// opening radius from Barnes' modified criterion. Node numbers may differ
// between builds, not the tree.
struct BuiltTree {
  UnsetVector<Node> nodes;            // the root first
  std::vector<std::uint32_t> groups;  // nodes whose bodies share a walk, in Morton order
  UnsetVector<std::uint32_t> parent;  // each node's (root: ~0)
  int depth = 0;                      // of the deepest node (root: 0)
  std::size_t leaves = 0;
  Square square;                     // the root square
  UnsetVector<std::uint32_t> order;  // order[r]: the body of Morton rank r
  UnsetVector<double> sx;            // bodies in Morton order, then kLeafPadding zeros
  UnsetVector<double> sy;
  UnsetVector<double> sm;
  UnsetVector<float> sm32;     // float32 masses in the frame (single)
  UnsetVector<double> node64;  // kMoments per node, as the float64 kernels read them
  UnsetVector<float> node32;   // the same in the frame, for float32 (single)
  detail::FloatFrame frame;    // the float32 frame
  bool single = false;         // float32: node32 and sm32, else node64
};

}  // namespace calder::nbody::bh
