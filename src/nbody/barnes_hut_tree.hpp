// SPDX-License-Identifier: MIT
// calder::nbody's Barnes-Hut internals, shared by its steps (one file each):
//   barnes_hut_build.cpp    bounding square, Morton sort, the tree and its
//                           moments (threads build subtrees of the Morton order)
//   build_kernels.cpp       the build's loops over every body (Morton codes,
//                           leaves' moments), compiled per instruction set
//   barnes_hut_moments.cpp  the moments as the multipole kernels read them
//   barnes_hut_walk.cpp     per group (or unit of sibling groups): the tree
//                           walk, the kernels' sums and the far field's
//                           interpolation
//   barnes_hut.cpp          the public entry points, which run the steps
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <new>
#include <span>
#include <utility>
#include <vector>

#include "../claims.hpp"
#include "build_kernels.hpp"
#include "calder/nbody.hpp"
#include "common.hpp"
#include "kernels.hpp"

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
// The first radix pass writes each bucket's records this many at a time
// (256 bytes: four cache lines; 64 KB of staging a thread, 256 KB with the
// wide first digit, in its L2).
inline constexpr std::size_t kStage = 8;
// Per node, as the multipole kernels read them (kernels.hpp): m, 3 Q (3),
// 1.5 tr Q, 7.5 O (4), 1.5 P (2), 17.5 H (5), 7.5 tr H (3), 1.875 tr tr H.
inline constexpr std::size_t kMoments = 20;
// From this many bodies every step (sort, tree, moments, walk) uses threads;
// below, waking them costs more than they save.
inline constexpr std::size_t kParallelFrom = 2000;
// About this many subtrees are built in parallel (at every size, so that the
// tree does not depend on the number of threads): enough that each of 16 or
// more threads gets several, of sizes that even out.
inline constexpr std::size_t kSubtrees = 256;

// The parallel regions of a step, whose per-thread work BarnesHutStats::work
// reports (ThreadWork's region and unit).
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

// What the build needs besides: mass, second, third and fourth moments about
// the centre of mass (qxx = sum m sx^2, ..., oxxy = sum m sx^2 sy, ...,
// hxxxy = sum m sx^3 sy, ...).
// No default values: Moments{} is all zeros, and a tree's moments are not
// zeroed as it grows (UnsetVector): the build writes each node's.
struct Moments {
  double mass;
  double qxx;
  double qxy;
  double qyy;
  double oxxx;
  double oxxy;
  double oxyy;
  double oyyy;
  double hxxxx;
  double hxxxy;
  double hxxyy;
  double hxyyy;
  double hyyyy;
};

// Columns of equal length that grow together (the interaction lists).
template <typename T, std::size_t K>
struct Columns {
  std::array<std::vector<T>, K> column;
  std::size_t size = 0;

  void clear() { size = 0; }
  // Room for `more` rows after size; returns the first free row.
  std::size_t make_room(std::size_t more) {
    if (size + more > column[0].size()) {
      const std::size_t capacity = std::max({size + more, 2 * column[0].size(), std::size_t{256}});
      for (auto& c : column) c.resize(capacity);
    }
    return size;
  }
  T* operator[](std::size_t k) { return column[k].data(); }
};

// Nodes as the multipole kernels read them: x, y, then the kMoments moments.
template <typename T>
using NodeColumns = Columns<T, detail::Nodes<T>::kColumns>;

// One group's interaction lists.
template <typename T>
struct Lists {
  Columns<T, 3> body;                 // x, y, m
  NodeColumns<T> node;                // accepted nodes
  NodeColumns<T> far;                 // the same, interpolated over the group
  std::vector<std::uint32_t> leaves;  // the leaves whose bodies are in body, in order
  Columns<T, 3> block_body;           // a block of targets' share of body
  NodeColumns<T> block_node;          // and the leaves its box accepts
  std::vector<T> tx;                  // float32 targets
  std::vector<T> ty;
};

// A tree, or a part of one built on its own (the parallel build). Parts are
// written by different threads side by side: each on its own cache lines.
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

// A group's bounding box and the origin of its float32 lists.
struct GroupFrame {
  double x0 = 0.0;
  double x1 = 0.0;
  double y0 = 0.0;
  double y1 = 0.0;
  double ox = 0.0;  // subtracted from positions, then scaled by `scale`
  double oy = 0.0;
  double scale = 1.0;
  // The interpolation square: centre and half side (0: no far list).
  double cx = 0.0;
  double cy = 0.0;
  double half = 0.0;
  double far2 = 0.0;  // nodes whose centre of mass is farther than sqrt(far2) from (cx, cy)
};

// The number of threads for a step over n bodies.
inline int team_for(std::size_t n, int threads) { return n < kParallelFrom ? 1 : threads; }

}  // namespace calder::nbody::bh

namespace calder::nbody {

struct BarnesHut::Workspace {
  BarnesHutStats stats;

  // Build.
  // Morton codes: in the caller's order during the first pass, then in the
  // sort's (a range that builds its subtree with its sort keeps its keys in its
  // thread's range_keys: here only its first and last, which the top reads).
  bh::UnsetVector<std::uint64_t> keys;
  bh::UnsetVector<std::uint32_t> order;  // order[r]: the body of Morton rank r
  bh::UnsetVector<bh::Record> records;   // the bodies as the radix passes move them
  bh::UnsetVector<bh::Record> records_tmp;
  std::vector<std::size_t> radix_counts;   // per thread (kFirstBuckets each) and bucket
  int first_bits = bh::kRadixBits;         // the first pass's digit
  std::vector<bh::SortRange> sort_large;   // ranges the team splits by their next digit
  std::vector<bh::SortRange> sort_small;   // ranges one thread sorts (all that are not split)
  std::size_t team_split_from = 0;         // ranges larger than this are split by the team
  struct alignas(64) SortScratch {         // a thread's buffers for its ranges
    std::vector<std::uint64_t> values[2];  // a range's keys and local indices, packed
    std::vector<bh::LeafLevel> leaf_levels = std::vector<bh::LeafLevel>(bh::kBits + 1);
    std::vector<bh::LeafBody> leaf_bodies;
    bh::UnsetVector<bh::Record> stage;     // the first pass's records on their way out
    std::uint8_t fill[bh::kFirstBuckets];  // how many of each bucket's are in stage
    std::uint8_t want[bh::kFirstBuckets];  // and how many it writes out next
    std::vector<std::uint32_t> leaf_node;  // a part's leaves (finish_part)
    std::vector<std::uint32_t> leaf_begin;
    std::vector<std::uint32_t> leaf_end;
    std::vector<double> leaf_sums;
    std::vector<std::uint64_t> sizes;  // assign_greedy's
    std::vector<std::uint32_t> by_size;
    std::vector<std::uint64_t> loads;
    // A range's sorted keys, while the thread builds its subtree.
    bh::UnsetVector<std::uint64_t> range_keys;
  };
  std::vector<SortScratch> sort_scratch;
  bh::UnsetVector<double> sx;  // bodies in Morton order, then kLeafPadding zeros
  bh::UnsetVector<double> sy;
  bh::UnsetVector<double> sm;
  bh::UnsetVector<float> sm32;  // scaled masses, float32
  bh::Tree tree;
  std::vector<bh::Tree> parts;          // the subtrees, in tree order
  std::vector<bh::Pending> pending;     // their roots
  std::vector<std::uint32_t> top;       // the nodes above them, in creation order
  std::vector<std::size_t> part_base;   // where each part's nodes go in the tree
  std::vector<std::size_t> group_base;  // and its groups in tree.groups
  // range_parts[r]: the subtree of sort_small[r] (when builds_with_sort),
  // built by the thread that sorted it, then swapped into parts; with_sort:
  // those ranges' (begin, r), by begin.
  std::vector<bh::Tree> range_parts;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> with_sort;
  // Every sort range's first body and key, by first body: the top of the
  // tree splits at these (its nodes hold whole ranges).
  std::vector<std::pair<std::uint32_t, std::uint64_t>> range_firsts;
  // Thread t's sort ranges and subtrees (assign_greedy), and its scratch.
  std::vector<std::vector<std::uint32_t>> own_ranges;
  std::vector<std::vector<std::uint32_t>> own_parts;
  std::vector<std::uint64_t> item_sizes;  // the subtrees' bodies
  // Per thread: bounding box (xmin, xmax, ymin, ymax) and heaviest body.
  std::vector<double> partial;
  // work[region * team + t]: thread t's work in a region (bh::Region).
  std::vector<std::uint64_t> work;
  // When each build phase ended (0: the start), on the steady clock, in seconds.
  double phase_end[bh::kBuildPhases + 1] = {};
  int team = 1;
  bool single = false;  // float32 sums
  detail::FloatFrame frame;
  bh::UnsetVector<double> node64;  // kMoments per node, as the float64 kernels read them
  bh::UnsetVector<float> node32;   // the same scaled for float32
  double x0 = 0.0;                 // the root square [x0, x0 + side) x [y0, y0 + side)
  double y0 = 0.0;
  double side = 1.0;
  double max_mass = 0.0;
  double inv_theta = 0.0;                         // 1 / theta, +inf for theta = 0
  std::array<double, bh::kBits + 1> cell_size{};  // side / 2^level, level 0 to kBits
  std::size_t leaf_size = 1;
  std::size_t group_size = 1;
  std::size_t target_block = 0;  // float64: targets that re-test the opened leaves (0: none)

  // Walk: sums in Morton order, and each thread's lists.
  bh::UnsetVector<double> sum_x;
  bh::UnsetVector<double> sum_y;
  struct alignas(64) Scratch {  // one a thread, on its own cache lines
    bh::Lists<double> lists64;
    bh::Lists<float> lists32;
    bh::Lists<double> unit64;  // a unit's far list
    bh::Lists<float> unit32;
    std::vector<std::uint32_t> unit_near;    // nodes a unit accepts, not in its far list
    std::vector<std::uint32_t> unit_leaves;  // leaves a unit opens
    std::vector<std::uint32_t> stack;
    std::vector<double> prefix;       // running costs of the units
    std::vector<std::size_t> bounds;  // the shares' first units (share_bounds)
    std::uint64_t interactions = 0;
    std::uint64_t node_interactions = 0;
  };
  std::vector<Scratch> scratch;
  // Runs of groups with one parent (first group, count), walked together.
  bh::UnsetVector<std::uint32_t> parent;  // each node's (filled by the build; root: ~0)
  std::vector<std::pair<std::uint32_t, std::uint32_t>> units;
  std::vector<double> unit_cost;  // estimated (walk)
  std::vector<float> body_cost;   // interactions per body of the last call, by caller's index
  calder::detail::Claims claims;  // on the chunks of the walk's shares
  std::vector<std::uint64_t> chunk_work;  // interactions of each chunk, by share

  // barnes_hut_build.cpp: the whole build in one parallel region.
  void build(std::span<const double> x, std::span<const double> y, std::span<const double> mass,
             int threads, double G);
  void size_buffers(std::size_t n);
  void bound(std::span<const double> x, std::span<const double> y, std::size_t t, std::size_t nt);
  bh::Square combine_bounds(std::size_t nt) const;
  double heaviest_mass(std::size_t nt) const;
  void first_pass(std::span<const double> x, std::span<const double> y,
                  std::span<const double> mass, const bh::MortonCoder& code, std::size_t t,
                  std::size_t nt);
  std::size_t bucket_offsets(std::size_t begin, std::size_t t, std::size_t nt, std::size_t buckets,
                             std::size_t* mine, std::size_t* ends) const;
  void sort_keys(const bh::MortonCoder& code, std::size_t t, std::size_t nt);
  void split_range(const bh::MortonCoder& code, const bh::SortRange& range, std::size_t t,
                   std::size_t nt);
  void list_ranges(const bh::SortRange& range, int width, const std::size_t* ends, bool skip);
  void sort_range(const bh::MortonCoder& code, const bh::SortRange& range, SortScratch& buffers);
  void sort_own_ranges(const bh::MortonCoder& code, std::size_t t);
  bool builds_with_sort(const bh::SortRange& range) const;
  void build_part(bh::Tree& part, std::uint32_t begin, std::uint32_t end, int depth,
                  const bh::SortedKeys& sorted, SortScratch& buffers, bool several_ranges);
  void leaves_in_index_order(const bh::Tree& part, std::vector<bh::LeafBody>& bodies);
  void plan_tree();
  void build_own_parts(std::size_t t);
  void place_parts();
  void copy_own_parts(std::size_t t);
  void finish_top();
  bh::SortedKeys all_keys() const { return bh::SortedKeys{keys.data(), 0}; }
  static int level_of(std::uint32_t begin, std::uint32_t end, const bh::SortedKeys& sorted);
  static int leaf_level(std::uint32_t begin, std::uint32_t end, const bh::SortedKeys& sorted);
  void quadrant_bounds(std::uint32_t begin, std::uint32_t end, int level, bool in_top,
                       const bh::SortedKeys& sorted, std::uint32_t (&bounds)[5]) const;
  std::uint32_t split(bh::Tree& t, std::uint32_t index, std::uint32_t begin, std::uint32_t end,
                      int level, bool in_top, const bh::SortedKeys& sorted,
                      std::uint32_t (&bounds)[5]) const;
  void plan(std::uint32_t index, std::uint32_t begin, std::uint32_t end, int tree_depth,
            std::size_t cutoff);
  std::uint32_t range_with_sort(std::uint32_t begin, std::uint32_t end, bool& inside) const;
  void build_node(bh::Tree& t, std::uint32_t index, std::uint32_t begin, std::uint32_t end,
                  int tree_depth, bool in_group, const bh::SortedKeys& sorted) const;
  void finish_node(bh::Tree& t, std::uint32_t index, const bh::SortedKeys& sorted) const;
  void finish_part(bh::Tree& t, const bh::SortedKeys& sorted, SortScratch& buffers) const;
  static void merge_moments(const bh::Tree& t, bh::Node& node, bh::Moments& mo);
  void set_opening_radius(bh::Node& node, const bh::SortedKeys& sorted) const;

  // barnes_hut_moments.cpp: node i's moments as the kernels read them
  // (node64, or node32 in the frame), and bodies' float32 masses.
  void kernel_moments(std::size_t i, const bh::Moments& moments);
  void float_masses(std::uint32_t begin, std::uint32_t end);

  // barnes_hut_walk.cpp
  // The walk and the scatter of factor * the sums to (ax, ay), one region.
  void walk(const detail::LawParams& p, double scale, int threads, double factor,
            std::span<double> ax, std::span<double> ay);
  void scatter_share(std::size_t t, std::size_t nt, double factor, std::span<double> ax,
                     std::span<double> ay);
  void estimate_costs(std::size_t first, std::size_t last, bool history);
  void share_bounds(std::size_t nt, Scratch& s) const;
  void walk_units(std::size_t first, std::size_t last, const detail::LawParams& p, double scale,
                  Scratch& s);
  template <typename T>
  void walk_group(std::uint32_t group, Scratch& s, const detail::KernelTable& k,
                  const detail::LawParams& p, double scale);
  // The bodies' box; a far list beyond far_ratio / theta of its half sides.
  bh::GroupFrame group_frame(const bh::Node& g, bool float32, double scale, double far_ratio) const;
  bh::GroupFrame bounding_box(std::uint32_t begin, std::uint32_t end) const;
  template <typename T>
  void collect(const bh::GroupFrame& f, bool multipoles, Scratch& s, bh::Lists<T>& lists);
  void plan_units();
  template <typename T>
  void walk_unit(std::uint32_t first, std::uint32_t count, Scratch& s, const detail::KernelTable& k,
                 const detail::LawParams& p, double scale);
  template <typename T>
  void add_node(const bh::GroupFrame& f, std::uint32_t index, bool multipoles,
                bh::Lists<T>& lists) const;
  template <typename T>
  void add_multipoles(const bh::GroupFrame& f, std::uint32_t index,
                      bh::NodeColumns<T>& nodes) const;
  template <typename T>
  void add_leaf(const bh::GroupFrame& f, std::uint32_t index, bh::Lists<T>& lists) const;
  template <typename T>
  void sum_far(const bh::Node& g, const bh::GroupFrame& f, const detail::KernelTable& k,
               const detail::LawParams& p, bh::Lists<T>& lists);
  template <typename T>
  void sum_leaves_by_block(const bh::Node& g, const bh::GroupFrame& f, const detail::KernelTable& k,
                           const detail::LawParams& p, Scratch& s, bh::Lists<T>& lists, const T* tx,
                           const T* ty);
  template <typename T>
  void sum_group(const bh::Node& g, const bh::GroupFrame& f, const detail::KernelTable& k,
                 const detail::LawParams& p, Scratch& s, bh::Lists<T>& lists);
};

}  // namespace calder::nbody
