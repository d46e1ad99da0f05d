// SPDX-License-Identifier: MIT
// Barnes-Hut, the fast build (TreeBuilder): the tree of BuiltTree's contract,
// built in one parallel region whose result does not depend on the number
// of threads. Three files, one concern each:
//   barnes_hut_sort.cpp     bounding square, Morton codes, their radix sort
//                           down to the leaves (threads split the bodies by
//                           their top digits, then order ranges on their own)
//   barnes_hut_build.cpp    the region's phases; the tree: a sort range of
//                           more than group_size bodies is a subtree that its
//                           sorting thread builds at once, the top above is
//                           split serially, the subtrees left are built by
//                           threads and all are placed in a fixed order
//   barnes_hut_moments.cpp  the moments and opening radii (shared with the
//                           reference build)
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "barnes_hut_moments.hpp"
#include "barnes_hut_tree.hpp"
#include "build_kernels.hpp"

namespace calder::nbody::bh {

inline constexpr int kRadixBits = 8;  // a radix pass's digit (the last may be narrower)
inline constexpr std::size_t kRadixBuckets = std::size_t{1} << kRadixBits;
// The first pass's digit: kRadixBits, or from kWideFirstFrom bodies on
// kWideFirstBits, so that the ranges it leaves stay small enough to sort in a
// core's cache (a wider digit spreads the pass's writes over more places).
// The order is the same whatever the digits.
inline constexpr int kWideFirstBits = 10;
inline constexpr std::size_t kWideFirstFrom = std::size_t{1} << 21;
inline constexpr std::size_t kFirstBuckets = std::size_t{1} << kWideFirstBits;  // at most
// Ranges of the sort up to this many bodies are ordered by one thread: their
// keys packed with their places (8 bytes a body, two arrays, and the
// counts: about 1.1 MB, in a core's cache) and the bodies then read in that
// order; larger ones are split by the team. So that the ranges share out
// evenly, a range is also split by the team while it holds more than
// 1 / kRangesPerThread of a thread's share of the bodies (but not below
// kMinTeamSplit bodies).
inline constexpr std::size_t kSortInCache = 65536;
inline constexpr std::size_t kRangesPerThread = 8;
inline constexpr std::size_t kMinTeamSplit = 256;
// The leaf order's counting pass (leaf_order): at most 2^14 cells (a
// pyramid of 87 KB of counts); a cell of more than leaf_size bodies is
// ordered again by the bits below, at most kBits levels deep.
inline constexpr int kMaxLeafBits = 14;
// The first radix pass writes each bucket's records this many at a time
// (256 bytes: four cache lines; 64 KB of staging a thread, 256 KB with the
// wide first digit, in its L2).
inline constexpr std::size_t kStage = 8;
// About this many subtrees are built in parallel (at every size, so that the
// tree does not depend on the number of threads): enough that each of 16 or
// more threads gets several, of sizes that even out.
inline constexpr std::size_t kSubtrees = 256;

// The build's phases (BarnesHutStats::build_phases): name, and whether one
// thread runs it while the others wait.
inline constexpr int kBuildPhases = 8;
struct BuildPhaseName {
  const char* name;
  bool serial;
};
inline constexpr BuildPhaseName kBuildPhaseNames[kBuildPhases] = {
    {"bounding square", false},
    {"Morton codes, first radix pass", false},
    {"sort's ranges, bodies in Morton order, their subtrees", false},
    {"top of the tree", true},
    {"subtrees left", false},
    {"subtrees placed", true},
    {"nodes and kernel moments", false},
    {"top moments", true},
};

// Items of the given sizes to nt threads: largest first (lower index on
// ties), each to the thread with the least so far (lower thread on ties).
// Depends on the sizes and nt only. mine: thread t's items, in index order.
void assign_greedy(const std::vector<std::uint64_t>& sizes, std::size_t nt, std::size_t t,
                   std::vector<std::uint32_t>& mine, std::vector<std::uint32_t>& by_size,
                   std::vector<std::uint64_t>& load);

// A body of a leaf being put in index order (leaves_in_index_order).
struct LeafBody {
  std::uint64_t key;
  double x;
  double y;
  double m;
  std::uint32_t index;
};

// leaf_order's scratch for one level of its recursion.
struct LeafLevel {
  std::vector<std::uint32_t> counts;  // the pyramid, coarsest level first
  std::vector<std::uint32_t> slot;    // each cell of the pass: its leaf's cursor
  std::vector<std::uint32_t> cursor;  // each leaf's next place
  std::vector<std::pair<std::uint32_t, std::uint32_t>> dense;  // cells to order again
  std::vector<std::pair<int, std::uint32_t>> stack;            // cells to visit
};

// A subtree built on its own (the parallel build), numbered from 0. Parts
// are written by different threads side by side: each on its own cache lines.
struct alignas(64) Tree {
  UnsetVector<Node> nodes;
  UnsetVector<Moments> moments;
  std::vector<std::uint32_t> groups;  // nodes whose bodies share a walk
  int depth = 0;
  std::size_t leaves = 0;

  void reset() {
    nodes.assign(1, Node{});
    moments.assign(1, Moments{});
    groups.clear();
    depth = 0;
    leaves = 0;
  }
};

inline constexpr std::uint32_t kNoRange = ~std::uint32_t{0};

// The Morton codes of the bodies a build step reads, in the sort's order
// (by leaf), by body rank: the whole array (first = 0), or a thread's copy
// of one sort range's (first = the range's begin), which stays in its cache
// while it builds the range's subtree and is never written out.
struct SortedKeys {
  const std::uint64_t* codes;
  std::uint32_t first;
  std::uint64_t operator[](std::uint32_t rank) const { return codes[rank - first]; }
};

// A subtree of the whole tree: its root's index there, its bodies and its
// depth, and the sort range whose thread built it as it sorted it
// (kNoRange: left for the parallel build).
struct Pending {
  std::uint32_t index = 0;
  std::uint32_t begin = 0;
  std::uint32_t end = 0;
  int depth = 0;
  std::uint32_t range = kNoRange;
};

// Keys [begin, end) of the sort, which share their bits above the lowest
// `bits`; their records in records_tmp or in records.
struct SortRange {
  std::uint32_t begin = 0;
  std::uint32_t end = 0;
  int bits = 0;
  bool in_tmp = false;
};

// A thread's buffers, on its own cache lines.
struct alignas(64) BuildScratch {
  std::vector<std::uint64_t> values[2];  // a sort range's keys and local indices, packed
  std::vector<LeafLevel> leaf_levels = std::vector<LeafLevel>(kBits + 1);
  std::vector<LeafBody> leaf_bodies;
  UnsetVector<Record> stage;             // the first pass's records on their way out
  std::uint8_t fill[kFirstBuckets];      // how many of each bucket's are in stage
  std::uint8_t want[kFirstBuckets];      // and how many it writes out next
  std::vector<std::uint32_t> leaf_node;  // a part's leaves (finish_part)
  std::vector<std::uint32_t> leaf_begin;
  std::vector<std::uint32_t> leaf_end;
  std::vector<double> leaf_sums;
  std::vector<std::uint64_t> sizes;  // assign_greedy's
  std::vector<std::uint32_t> by_size;
  std::vector<std::uint64_t> loads;
  UnsetVector<std::uint64_t> range_keys;  // a range's sorted keys, while its subtree is built
  std::vector<std::uint32_t> own_ranges;  // the thread's sort ranges (assign_greedy)
  std::vector<std::uint32_t> own_parts;   // and its subtrees
};

// The radix sort's state: the bodies as records, moved pass by pass, and the
// ranges the passes leave.
struct SortState {
  UnsetVector<Record> records;
  UnsetVector<Record> records_tmp;
  std::vector<std::size_t> radix_counts;  // per thread (kFirstBuckets each) and bucket
  int first_bits = kRadixBits;            // the first pass's digit
  std::vector<SortRange> large;           // ranges the team splits by their next digit
  std::vector<SortRange> small;           // ranges one thread sorts (all that are not split)
  std::size_t team_split_from = 0;        // ranges larger than this are split by the team
  std::vector<double> partial;            // per thread: bounding box and heaviest body
};

class TreeBuilder {
 public:
  // Builds `out` for the bodies, with settings.threads threads (from
  // kParallelFrom bodies); work[region * team + t] += thread t's work in the
  // build's regions (team: team_for(n, settings.threads)).
  void build(std::span<const double> x, std::span<const double> y, std::span<const double> mass,
             const BuildSettings& settings, BuiltTree& out, std::uint64_t* work);
  // When each build phase of the last build ended (0: its start), in seconds.
  const double* phase_end() const { return phase_end_; }

 private:
  // Morton codes: in the caller's order during the first pass, then in the
  // sort's (a range that builds its subtree with its sort keeps its keys in its
  // thread's range_keys: here only its first and last, which the top reads).
  UnsetVector<std::uint64_t> keys_;
  SortState sort_;
  std::vector<BuildScratch> scratch_;
  std::vector<Tree> parts_;              // the subtrees, in tree order
  std::vector<Pending> pending_;         // their roots
  std::vector<std::uint32_t> top_;       // the nodes above them, in creation order
  UnsetVector<Moments> top_moments_;     // the top's moments (and the parts' roots')
  std::vector<std::size_t> part_base_;   // where each part's nodes go in the tree
  std::vector<std::size_t> group_base_;  // and its groups in tree.groups
  // range_parts_[r]: the subtree of sort_.small[r] (when builds_with_sort),
  // built by the thread that sorted it, then swapped into parts_; with_sort_:
  // those ranges' (begin, r), by begin.
  std::vector<Tree> range_parts_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> with_sort_;
  // Every sort range's first body and key, by first body: the top of the
  // tree splits at these (its nodes hold whole ranges).
  std::vector<std::pair<std::uint32_t, std::uint64_t>> range_firsts_;
  std::vector<std::uint64_t> item_sizes_;  // the subtrees' bodies
  double phase_end_[kBuildPhases + 1] = {};
  int team_ = 1;
  BuildSettings settings_;
  CellGeometry cells_;
  BuiltTree* out_ = nullptr;       // the tree being built (during build)
  std::uint64_t* work_ = nullptr;  // and the work counts

  // barnes_hut_sort.cpp
  void size_buffers(std::size_t n);
  void bound(std::span<const double> x, std::span<const double> y, std::size_t t, std::size_t nt);
  Square combine_bounds(std::size_t nt) const;
  double heaviest_mass(std::size_t nt) const;
  void first_pass(std::span<const double> x, std::span<const double> y,
                  std::span<const double> mass, const MortonCoder& code, std::size_t t,
                  std::size_t nt);
  std::size_t bucket_offsets(std::size_t begin, std::size_t t, std::size_t nt, std::size_t buckets,
                             std::size_t* mine, std::size_t* ends) const;
  void sort_keys(const MortonCoder& code, std::size_t t, std::size_t nt);
  void split_range(const MortonCoder& code, const SortRange& range, std::size_t t, std::size_t nt);
  void list_ranges(const SortRange& range, int width, const std::size_t* ends, bool skip);
  void sort_range(const MortonCoder& code, const SortRange& range, BuildScratch& buffers);
  void sort_own_ranges(const MortonCoder& code, std::size_t t);
  bool builds_with_sort(const SortRange& range) const;

  // barnes_hut_build.cpp
  void build_part(Tree& part, std::uint32_t begin, std::uint32_t end, int depth,
                  const SortedKeys& sorted, BuildScratch& buffers, bool several_ranges);
  void leaves_in_index_order(const Tree& part, std::vector<LeafBody>& bodies);
  void plan_tree();
  void build_own_parts(std::size_t t);
  void place_parts();
  void copy_own_parts(std::size_t t);
  void finish_top();
  SortedKeys all_keys() const { return SortedKeys{keys_.data(), 0}; }
  void quadrant_bounds(std::uint32_t begin, std::uint32_t end, int level, bool in_top,
                       const SortedKeys& sorted, std::uint32_t (&bounds)[5]) const;
  std::uint32_t split(UnsetVector<Node>& nodes, UnsetVector<Moments>& moments, std::uint32_t index,
                      std::uint32_t begin, std::uint32_t end, int level, bool in_top,
                      const SortedKeys& sorted, std::uint32_t (&bounds)[5]) const;
  void plan(std::uint32_t index, std::uint32_t begin, std::uint32_t end, int tree_depth,
            std::size_t cutoff);
  std::uint32_t range_with_sort(std::uint32_t begin, std::uint32_t end, bool& inside) const;
  void build_node(Tree& t, std::uint32_t index, std::uint32_t begin, std::uint32_t end,
                  int tree_depth, bool in_group, const SortedKeys& sorted) const;

  // barnes_hut_moments.cpp's parts of the build
  void finish_node(Node* nodes, Moments* moments, std::uint32_t index,
                   const SortedKeys& sorted) const;
  void finish_part(Tree& t, const SortedKeys& sorted, BuildScratch& buffers) const;
  void opening_radius(Node& node, const SortedKeys& sorted) const;
};

// The number of quadtree levels that the bodies [begin, end) share: their
// node's cell is the smallest one holding them all (chains of single
// children are skipped); kBits when they all share one Morton code.
inline int level_of(std::uint32_t begin, std::uint32_t end, const SortedKeys& sorted) {
  return shared_levels(sorted[begin] ^ sorted[end - 1]);
}

// The same for a leaf, whose bodies are in index order, not by key
// (leaf_order): every key counts.
inline int leaf_level(std::uint32_t begin, std::uint32_t end, const SortedKeys& sorted) {
  const std::uint64_t first = sorted[begin];
  std::uint64_t differ = 0;
  for (std::uint32_t r = begin + 1; r < end; ++r) differ |= sorted[r] ^ first;
  return shared_levels(differ);
}

}  // namespace calder::nbody::bh
