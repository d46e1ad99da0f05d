// SPDX-License-Identifier: MIT
// calder::nbody: Barnes-Hut on a quadtree of Morton-sorted bodies (see
// calder/nbody.hpp for the algorithm and its guarantees).
//
// Build: bounding square; 48-bit Morton codes (24 bits per axis); a stable
// LSD radix sort (6 passes of 8 bits, threads scatter their own slices, so
// the order is the same for any thread count); the tree, depth first, each
// node the smallest quadtree cell holding its bodies; mass, centre of mass
// and second moments bottom up (parallel axis theorem).
//
// Walk: per group (a node of <= group_size bodies), one walk from the root;
// an accepted node goes to the node list (centre of mass, mass, quadrupole
// moments; for the clamped laws a point mass: those laws are not harmonic, so
// their multipole expansion is not Newton's), the bodies of an opened leaf to
// the body list. The kernels then sum both lists for all the group's bodies,
// float32 lists being relative to the group's centre.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "calder/error.hpp"
#include "calder/nbody.hpp"
#include "common.hpp"
#include "kernels.hpp"

#if defined(_OPENMP)
#include <omp.h>
#endif

namespace calder::nbody {

namespace {

constexpr int kBits = 24;  // per axis: 48-bit Morton codes, at most 24 levels below the root
constexpr std::uint32_t kCells = std::uint32_t{1} << kBits;
constexpr int kRadixBits = 8;
constexpr std::size_t kRadixBuckets = std::size_t{1} << kRadixBits;
constexpr int kRadixPasses = 2 * kBits / kRadixBits;
// Per node, as the multipole kernels read them (kernels.hpp): m, 3 Q (3), 1.5 tr Q,
// 7.5 O (4), 1.5 P (2).
constexpr std::size_t kMoments = 11;
// From this many bodies the build (sort, tree) uses threads too.
constexpr std::size_t kParallelBuild = 16384;

// What the walk reads of a node.
struct Node {
  double mx = 0.0;  // centre of mass
  double my = 0.0;
  double open2 = 0.0;       // accepted for a group farther than sqrt(open2) from (mx, my)
  std::uint32_t begin = 0;  // bodies [begin, end) in Morton order
  std::uint32_t end = 0;
  std::uint32_t child = 0;     // first child (children are contiguous)
  std::uint32_t children = 0;  // 0: a leaf
};

// What the build needs besides: mass, second and third moments about the
// centre of mass (qxx = sum m sx^2, ..., oxxy = sum m sx^2 sy, ...).
struct Moments {
  double mass = 0.0;
  double qxx = 0.0;
  double qxy = 0.0;
  double qyy = 0.0;
  double oxxx = 0.0;
  double oxxy = 0.0;
  double oxyy = 0.0;
  double oyyy = 0.0;
};

// Interleaves the low 24 bits of v with zeros: bit k goes to bit 2k.
std::uint64_t spread(std::uint32_t v) {
  std::uint64_t x = v & (kCells - 1);
  x = (x | (x << 16)) & 0x0000FFFF0000FFFFull;
  x = (x | (x << 8)) & 0x00FF00FF00FF00FFull;
  x = (x | (x << 4)) & 0x0F0F0F0F0F0F0F0Full;
  x = (x | (x << 2)) & 0x3333333333333333ull;
  x = (x | (x << 1)) & 0x5555555555555555ull;
  return x;
}

// The inverse of spread: bits 0, 2, 4, ... of x.
std::uint32_t compact(std::uint64_t x) {
  x &= 0x5555555555555555ull;
  x = (x | (x >> 1)) & 0x3333333333333333ull;
  x = (x | (x >> 2)) & 0x0F0F0F0F0F0F0F0Full;
  x = (x | (x >> 4)) & 0x00FF00FF00FF00FFull;
  x = (x | (x >> 8)) & 0x0000FFFF0000FFFFull;
  x = (x | (x >> 16)) & 0x00000000FFFFFFFFull;
  return static_cast<std::uint32_t>(x);
}

int leading_zeros(std::uint64_t x) {  // x != 0
  int n = 0;
  for (int step = 32; step > 0; step /= 2) {
    if ((x >> (64 - step)) == 0) {
      n += step;
      x <<= step;
    }
  }
  return n;
}

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

template <typename T>
struct Lists {
  Columns<T, 3> body;                           // x, y, m
  Columns<T, detail::Nodes<T>::kColumns> node;  // x, y, then the kMoments moments
  std::vector<T> tx;                            // float32 targets
  std::vector<T> ty;
};

// A tree, or a part of one built on its own (the parallel build).
struct Tree {
  std::vector<Node> nodes;
  std::vector<Moments> moments;
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

// A subtree left for the parallel build: its root's index in the whole tree,
// its bodies and its depth.
struct Pending {
  std::uint32_t index = 0;
  std::uint32_t begin = 0;
  std::uint32_t end = 0;
  int depth = 0;
};

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace

struct BarnesHut::Workspace {
  BarnesHutStats stats;

  // Build.
  std::vector<std::uint64_t> keys;
  std::vector<std::uint64_t> keys_tmp;
  std::vector<std::uint32_t> order;  // order[r]: the body of Morton rank r
  std::vector<std::uint32_t> order_tmp;
  std::vector<std::size_t> radix_counts;  // per thread and bucket
  std::vector<double> sx;                 // bodies in Morton order
  std::vector<double> sy;
  std::vector<double> sm;
  std::vector<float> sm32;  // scaled masses, float32
  Tree tree;
  std::vector<Tree> parts;         // the subtrees, built in parallel
  std::vector<Pending> pending;    // their roots
  std::vector<std::uint32_t> top;  // the nodes above them, in creation order
  std::vector<double> node64;      // kMoments per node, as the float64 kernels read them
  std::vector<float> node32;       // the same scaled for float32
  double x0 = 0.0;                 // the root square [x0, x0 + side) x [y0, y0 + side)
  double y0 = 0.0;
  double side = 1.0;
  double max_mass = 0.0;
  double inv_theta = 0.0;  // 1 / theta, +inf for theta = 0
  std::size_t leaf_size = 1;
  std::size_t group_size = 1;

  // Walk: sums in Morton order, and each thread's lists.
  std::vector<double> sum_x;
  std::vector<double> sum_y;
  struct Scratch {
    Lists<double> lists64;
    Lists<float> lists32;
    std::vector<std::uint32_t> stack;
    std::uint64_t interactions = 0;
    std::uint64_t node_interactions = 0;
  };
  std::vector<Scratch> scratch;

  void sort_bodies(std::span<const double> x, std::span<const double> y,
                   std::span<const double> mass, int threads);
  void build_tree(int threads);
  int level_of(std::uint32_t begin, std::uint32_t end) const;
  std::uint32_t split(Tree& t, std::uint32_t index, std::uint32_t begin, std::uint32_t end,
                      int level, std::uint32_t (&bounds)[5]) const;
  void plan(std::uint32_t index, std::uint32_t begin, std::uint32_t end, int tree_depth,
            std::size_t cutoff);
  void build_node(Tree& t, std::uint32_t index, std::uint32_t begin, std::uint32_t end,
                  int tree_depth, bool in_group) const;
  void finish_node(Tree& t, std::uint32_t index) const;
  template <typename T>
  void walk_group(std::uint32_t group, Scratch& s, const detail::KernelTable& k,
                  const detail::LawParams& p, double scale);
};

void BarnesHut::Workspace::sort_bodies(std::span<const double> x, std::span<const double> y,
                                       std::span<const double> mass, int threads) {
  const std::size_t n = x.size();
  // Small inputs are not worth waking threads for.
  const int team = n < kParallelBuild ? 1 : threads;
  double xmin = x[0];
  double xmax = x[0];
  double ymin = y[0];
  double ymax = y[0];
  const auto count = static_cast<std::ptrdiff_t>(n);
#if defined(_OPENMP)
#pragma omp parallel for schedule(static) num_threads(team) reduction(min           \
                                                                      : xmin, ymin) \
    reduction(max                                                                   \
              : xmax, ymax)
#endif
  for (std::ptrdiff_t i = 0; i < count; ++i) {
    const auto u = static_cast<std::size_t>(i);
    xmin = std::min(xmin, x[u]);
    xmax = std::max(xmax, x[u]);
    ymin = std::min(ymin, y[u]);
    ymax = std::max(ymax, y[u]);
  }
  x0 = xmin;
  y0 = ymin;
  side = std::max(xmax - xmin, ymax - ymin);
  if (!(side > 0.0)) side = 1.0;  // one point (or one body)
  const double to_cell = static_cast<double>(kCells) / side;
  const auto quantise = [&](double v, double origin) {
    const double c = (v - origin) * to_cell;  // >= 0
    return c >= static_cast<double>(kCells - 1) ? kCells - 1 : static_cast<std::uint32_t>(c);
  };

  keys.resize(n);
  keys_tmp.resize(n);
  order.resize(n);
  order_tmp.resize(n);
  sx.resize(n);
  sy.resize(n);
  sm.resize(n);
  radix_counts.assign(static_cast<std::size_t>(team) * kRadixBuckets, 0);
  bool skip = false;
  double heaviest = 0.0;

#if defined(_OPENMP)
#pragma omp parallel num_threads(team) reduction(max : heaviest)
#endif
  {
#if defined(_OPENMP)
    const auto t = static_cast<std::size_t>(omp_get_thread_num());
    const auto nt = static_cast<std::size_t>(omp_get_num_threads());
#else
    const std::size_t t = 0;
    const std::size_t nt = 1;
#endif
    // This thread's slice, the same in every pass.
    const std::size_t lo = n * t / nt;
    const std::size_t hi = n * (t + 1) / nt;
    for (std::size_t i = lo; i < hi; ++i) {
      keys[i] = spread(quantise(x[i], x0)) | (spread(quantise(y[i], y0)) << 1);
      order[i] = static_cast<std::uint32_t>(i);
    }
    // LSD radix sort of (key, index): stable, so equal keys stay in index
    // order; slice t of the input goes, in order, after slices 0 .. t-1 of
    // each bucket, so the result does not depend on the number of threads.
    for (int pass = 0; pass < kRadixPasses; ++pass) {
      const int shift = pass * kRadixBits;
      std::size_t* counts = radix_counts.data() + t * kRadixBuckets;
      std::fill(counts, counts + kRadixBuckets, std::size_t{0});
      for (std::size_t i = lo; i < hi; ++i) ++counts[(keys[i] >> shift) & (kRadixBuckets - 1)];
#if defined(_OPENMP)
#pragma omp barrier
#pragma omp single
#endif
      {
        // Exclusive prefix sums, bucket-major then thread; skip a pass in
        // which every key has the same digit.
        std::size_t offset = 0;
        skip = false;
        for (std::size_t b = 0; b < kRadixBuckets; ++b) {
          std::size_t bucket = 0;
          for (std::size_t u = 0; u < nt; ++u) {
            std::size_t& c = radix_counts[u * kRadixBuckets + b];
            const std::size_t here = c;
            c = offset;
            offset += here;
            bucket += here;
          }
          if (bucket == n) skip = true;
        }
      }
      if (!skip) {
        for (std::size_t i = lo; i < hi; ++i) {
          const std::size_t to = counts[(keys[i] >> shift) & (kRadixBuckets - 1)]++;
          keys_tmp[to] = keys[i];
          order_tmp[to] = order[i];
        }
      }
#if defined(_OPENMP)
#pragma omp barrier
#pragma omp single
#endif
      if (!skip) {
        keys.swap(keys_tmp);
        order.swap(order_tmp);
      }
    }
    for (std::size_t r = lo; r < hi; ++r) {
      const std::uint32_t i = order[r];
      sx[r] = x[i];
      sy[r] = y[i];
      sm[r] = mass[i];
      heaviest = std::max(heaviest, mass[i]);
    }
  }
  max_mass = heaviest;
}

// The number of quadtree levels that the bodies [begin, end) share: their
// node's cell is the smallest one holding them all (chains of single
// children are skipped); kBits when they all share one Morton code.
int BarnesHut::Workspace::level_of(std::uint32_t begin, std::uint32_t end) const {
  const std::uint64_t first = keys[begin];
  const std::uint64_t last = keys[end - 1];
  return first == last ? kBits : (leading_zeros(first ^ last) - (64 - 2 * kBits)) / 2;
}

// Splits node `index` of t (bodies [begin, end), common prefix `level`) into
// its non-empty quadrants, appended to t as contiguous children; returns how
// many. bounds: the quadrants' body ranges.
std::uint32_t BarnesHut::Workspace::split(Tree& t, std::uint32_t index, std::uint32_t begin,
                                          std::uint32_t end, int level,
                                          std::uint32_t (&bounds)[5]) const {
  // The quadrant digit below the common prefix: bits 2 (kBits - 1 - level) + {0, 1}.
  const int shift = 2 * (kBits - 1 - level);
  bounds[0] = begin;
  for (std::uint64_t d = 1; d < 4; ++d) {
    bounds[d] = static_cast<std::uint32_t>(
        std::partition_point(keys.begin() + static_cast<std::ptrdiff_t>(bounds[d - 1]),
                             keys.begin() + static_cast<std::ptrdiff_t>(end),
                             [&](std::uint64_t key) { return ((key >> shift) & 3u) < d; }) -
        keys.begin());
  }
  bounds[4] = end;
  std::uint32_t children = 0;
  for (int q = 0; q < 4; ++q) children += bounds[q + 1] > bounds[q] ? 1 : 0;
  Node& node = t.nodes[index];
  node.begin = begin;
  node.end = end;
  node.child = static_cast<std::uint32_t>(t.nodes.size());
  node.children = children;
  t.nodes.resize(t.nodes.size() + children);
  t.moments.resize(t.nodes.size());
  return children;
}

// The top of the tree, serially: nodes with more than `cutoff` bodies are
// split here; the others are left in `pending` for the parallel build. The
// cutoff depends on the number of bodies only, so the tree does not depend
// on the number of threads.
void BarnesHut::Workspace::plan(std::uint32_t index, std::uint32_t begin, std::uint32_t end,
                                int tree_depth, std::size_t cutoff) {
  const int level = level_of(begin, end);
  if (end - begin <= cutoff || level == kBits) {
    pending.push_back(Pending{index, begin, end, tree_depth});
    return;
  }
  top.push_back(index);
  std::uint32_t bounds[5];
  split(tree, index, begin, end, level, bounds);
  std::uint32_t c = tree.nodes[index].child;
  for (int q = 0; q < 4; ++q) {
    if (bounds[q + 1] > bounds[q]) plan(c++, bounds[q], bounds[q + 1], tree_depth + 1, cutoff);
  }
}

// Builds node `index` of t over the bodies [begin, end) (end > begin) and its
// subtree: split unless it has at most leaf_size bodies or they all share one
// Morton code. The first node on each path with at most group_size bodies
// (or a leaf) is a group.
void BarnesHut::Workspace::build_node(Tree& t, std::uint32_t index, std::uint32_t begin,
                                      std::uint32_t end, int tree_depth, bool in_group) const {
  const int level = level_of(begin, end);
  t.depth = std::max(t.depth, tree_depth);
  const std::size_t count = end - begin;
  const bool leaf = count <= leaf_size || level == kBits;
  if (!in_group && (count <= group_size || leaf)) {
    t.groups.push_back(index);
    in_group = true;
  }
  if (leaf) {
    ++t.leaves;
    Node& node = t.nodes[index];
    node.begin = begin;
    node.end = end;
    node.child = 0;
    node.children = 0;
  } else {
    std::uint32_t bounds[5];
    split(t, index, begin, end, level, bounds);  // reserved capacity: no reallocation
    std::uint32_t c = t.nodes[index].child;
    for (int q = 0; q < 4; ++q) {
      if (bounds[q + 1] > bounds[q])
        build_node(t, c++, bounds[q], bounds[q + 1], tree_depth + 1, in_group);
    }
  }
  finish_node(t, index);
}

// Mass, centre of mass and moments of node `index` of t (from its bodies, or
// from its children, which must be finished), and its opening radius.
void BarnesHut::Workspace::finish_node(Tree& t, std::uint32_t index) const {
  Node& node = t.nodes[index];
  double mass = 0.0;
  double mx = 0.0;
  double my = 0.0;
  Moments mo;
  if (node.children == 0) {
    for (std::uint32_t b = node.begin; b < node.end; ++b) {
      mass += sm[b];
      mx += sm[b] * sx[b];
      my += sm[b] * sy[b];
    }
    mx /= mass;
    my /= mass;
    for (std::uint32_t b = node.begin; b < node.end; ++b) {
      const double dx = sx[b] - mx;
      const double dy = sy[b] - my;
      const double m = sm[b];
      mo.qxx += m * dx * dx;
      mo.qxy += m * dx * dy;
      mo.qyy += m * dy * dy;
      mo.oxxx += m * dx * dx * dx;
      mo.oxxy += m * dx * dx * dy;
      mo.oxyy += m * dx * dy * dy;
      mo.oyyy += m * dy * dy * dy;
    }
  } else {
    const std::uint32_t first = node.child;
    const std::uint32_t last = node.child + node.children;
    for (std::uint32_t c = first; c < last; ++c) {
      mass += t.moments[c].mass;
      mx += t.moments[c].mass * t.nodes[c].mx;
      my += t.moments[c].mass * t.nodes[c].my;
    }
    mx /= mass;
    my /= mass;
    for (std::uint32_t c = first; c < last; ++c) {
      // The child's moments about this centre of mass, the child's centre at
      // offset (dx, dy): s = d + s', sum m s' = 0.
      const Moments& m = t.moments[c];
      const double dx = t.nodes[c].mx - mx;
      const double dy = t.nodes[c].my - my;
      mo.qxx += m.qxx + m.mass * dx * dx;
      mo.qxy += m.qxy + m.mass * dx * dy;
      mo.qyy += m.qyy + m.mass * dy * dy;
      mo.oxxx += m.oxxx + 3.0 * dx * m.qxx + m.mass * dx * dx * dx;
      mo.oxxy += m.oxxy + 2.0 * dx * m.qxy + dy * m.qxx + m.mass * dx * dx * dy;
      mo.oxyy += m.oxyy + 2.0 * dy * m.qxy + dx * m.qyy + m.mass * dx * dy * dy;
      mo.oyyy += m.oyyy + 3.0 * dy * m.qyy + m.mass * dy * dy * dy;
    }
  }
  mo.mass = mass;
  t.moments[index] = mo;

  // The cell: level `level` of the root square, found from the common prefix.
  const int level = level_of(node.begin, node.end);
  const std::uint64_t key = keys[node.begin];
  const double size = std::ldexp(side, -level);
  const double cx = x0 + (static_cast<double>(compact(key) >> (kBits - level)) + 0.5) * size;
  const double cy = y0 + (static_cast<double>(compact(key >> 1) >> (kBits - level)) + 0.5) * size;
  const double delta = std::sqrt((mx - cx) * (mx - cx) + (my - cy) * (my - cy));
  const double open = size * inv_theta + delta;
  node.mx = mx;
  node.my = my;
  node.open2 = open * open;
}

// The whole tree: its top serially (plan), the subtrees below in parallel
// (each in its own Tree, numbered from 0), then the subtrees' nodes appended
// in a fixed order and the top finished bottom up.
void BarnesHut::Workspace::build_tree(int threads) {
  const auto n = static_cast<std::uint32_t>(keys.size());
  tree.reset();
  tree.nodes.reserve(2 * std::size_t{n});  // every inner node has >= 2 children: < 2n nodes
  tree.moments.reserve(2 * std::size_t{n});
  pending.clear();
  top.clear();
  // About 64 subtrees for large inputs, and never a group or a leaf above them.
  const std::size_t cutoff =
      n < kParallelBuild ? n : std::max({std::size_t{n} / 64, group_size, leaf_size});
  plan(0, 0, n, 0, cutoff);
  [[maybe_unused]] const int team = n < kParallelBuild ? 1 : threads;

  if (parts.size() < pending.size()) parts.resize(pending.size());
  const auto count = static_cast<std::ptrdiff_t>(pending.size());
#if defined(_OPENMP)
#pragma omp parallel for schedule(dynamic, 1) num_threads(team)
#endif
  for (std::ptrdiff_t k = 0; k < count; ++k) {
    const Pending& p = pending[static_cast<std::size_t>(k)];
    Tree& part = parts[static_cast<std::size_t>(k)];
    part.reset();
    part.nodes.reserve(2 * std::size_t{p.end - p.begin});
    part.moments.reserve(2 * std::size_t{p.end - p.begin});
    build_node(part, 0, p.begin, p.end, p.depth, false);
  }

  // Part k's node c goes to its root's slot (c = 0) or to offset[k] + c - 1.
  std::vector<std::size_t> offset(pending.size() + 1);
  offset[0] = tree.nodes.size();
  for (std::size_t k = 0; k < pending.size(); ++k) {
    offset[k + 1] = offset[k] + parts[k].nodes.size() - 1;
    tree.depth = std::max(tree.depth, parts[k].depth);
    tree.leaves += parts[k].leaves;
  }
  tree.nodes.resize(offset.back());
  tree.moments.resize(offset.back());
#if defined(_OPENMP)
#pragma omp parallel for schedule(dynamic, 1) num_threads(team)
#endif
  for (std::ptrdiff_t k = 0; k < count; ++k) {
    const auto u = static_cast<std::size_t>(k);
    const Tree& part = parts[u];
    const std::uint32_t root = pending[u].index;
    const auto base = static_cast<std::uint32_t>(offset[u]);
    for (std::size_t c = 0; c < part.nodes.size(); ++c) {
      Node node = part.nodes[c];
      if (node.children > 0) node.child = base + node.child - 1;
      const std::size_t to = c == 0 ? root : base + c - 1;
      tree.nodes[to] = node;
      tree.moments[to] = part.moments[c];
    }
  }
  for (std::size_t k = 0; k < pending.size(); ++k) {
    const auto base = static_cast<std::uint32_t>(offset[k]);
    for (const std::uint32_t g : parts[k].groups) {
      tree.groups.push_back(g == 0 ? pending[k].index : base + g - 1);
    }
  }
  for (auto it = top.rbegin(); it != top.rend(); ++it) finish_node(tree, *it);
}

template <typename T>
void BarnesHut::Workspace::walk_group(std::uint32_t group, Scratch& s, const detail::KernelTable& k,
                                      const detail::LawParams& p, double scale) {
  constexpr bool kFloat = sizeof(T) == 4;
  const Node& g = tree.nodes[group];
  const std::uint32_t begin = g.begin;
  const std::uint32_t end = g.end;
  double gx0 = sx[begin];
  double gx1 = gx0;
  double gy0 = sy[begin];
  double gy1 = gy0;
  for (std::uint32_t b = begin + 1; b < end; ++b) {
    gx0 = std::min(gx0, sx[b]);
    gx1 = std::max(gx1, sx[b]);
    gy0 = std::min(gy0, sy[b]);
    gy1 = std::max(gy1, sy[b]);
  }
  // float32 lists: relative to the group's centre, in the frame's scale.
  const double ox = kFloat ? gx0 + (gx1 - gx0) * 0.5 : 0.0;
  const double oy = kFloat ? gy0 + (gy1 - gy0) * 0.5 : 0.0;
  const double s_len = kFloat ? scale : 1.0;
  const T* node_moments;
  const T* body_mass;
  Lists<T>* lists;
  if constexpr (kFloat) {
    node_moments = node32.data();
    body_mass = sm32.data();
    lists = &s.lists32;
  } else {
    node_moments = node64.data();
    body_mass = sm.data();
    lists = &s.lists64;
  }
  Columns<T, 3>& body = lists->body;
  Columns<T, detail::Nodes<T>::kColumns>& accepted = lists->node;
  body.clear();
  accepted.clear();
  const bool multipoles = p.law == Law::plummer;

  s.stack.clear();
  s.stack.push_back(0);
  while (!s.stack.empty()) {
    const std::uint32_t index = s.stack.back();
    s.stack.pop_back();
    const Node& n = tree.nodes[index];
    const double dx = std::max(std::max(gx0 - n.mx, n.mx - gx1), 0.0);
    const double dy = std::max(std::max(gy0 - n.my, n.my - gy1), 0.0);
    if (dx * dx + dy * dy > n.open2) {
      const T* m = node_moments + std::size_t{index} * kMoments;
      const T x = static_cast<T>((n.mx - ox) * s_len);
      const T y = static_cast<T>((n.my - oy) * s_len);
      if (multipoles) {
        const std::size_t r = accepted.make_room(1);
        accepted[0][r] = x;
        accepted[1][r] = y;
        for (std::size_t a = 0; a < kMoments; ++a) accepted[2 + a][r] = m[a];
        accepted.size = r + 1;
      } else {
        const std::size_t r = body.make_room(1);
        body[0][r] = x;
        body[1][r] = y;
        body[2][r] = m[0];
        body.size = r + 1;
      }
    } else if (n.children == 0) {
      const std::size_t count = n.end - n.begin;
      const std::size_t r = body.make_room(count);
      if constexpr (kFloat) {
        for (std::size_t b = 0; b < count; ++b) {
          body[0][r + b] = static_cast<T>((sx[n.begin + b] - ox) * s_len);
          body[1][r + b] = static_cast<T>((sy[n.begin + b] - oy) * s_len);
        }
      } else {
        std::memcpy(body[0] + r, sx.data() + n.begin, count * sizeof(T));
        std::memcpy(body[1] + r, sy.data() + n.begin, count * sizeof(T));
      }
      std::memcpy(body[2] + r, body_mass + n.begin, count * sizeof(T));
      body.size = r + count;
    } else {
      for (std::uint32_t c = n.child + n.children; c-- > n.child;) s.stack.push_back(c);
    }
  }

  // Each target: the accepted nodes (in walk order), then the bodies.
  const std::size_t count = end - begin;
  s.interactions += static_cast<std::uint64_t>(count) * (body.size + accepted.size);
  s.node_interactions += static_cast<std::uint64_t>(count) * accepted.size;
  const T* tx;
  const T* ty;
  if constexpr (kFloat) {
    lists->tx.resize(count);
    lists->ty.resize(count);
    for (std::size_t t = 0; t < count; ++t) {
      lists->tx[t] = static_cast<T>((sx[begin + t] - ox) * s_len);
      lists->ty[t] = static_cast<T>((sy[begin + t] - oy) * s_len);
    }
    tx = lists->tx.data();
    ty = lists->ty.data();
  } else {
    tx = sx.data() + begin;
    ty = sy.data() + begin;
  }
  double* out_x = sum_x.data() + begin;
  double* out_y = sum_y.data() + begin;
  std::fill(out_x, out_x + count, 0.0);
  std::fill(out_y, out_y + count, 0.0);
  detail::Nodes<T> node_list;
  for (std::size_t c = 0; c < detail::Nodes<T>::kColumns; ++c) node_list.column[c] = accepted[c];
  node_list.n = accepted.size;
  const detail::Bodies<T> body_list{body[0], body[1], body[2], body.size};
  if constexpr (kFloat) {
    if (node_list.n > 0) k.multipole32(tx, ty, count, node_list, p, out_x, out_y);
    k.group32(tx, ty, nullptr, nullptr, count, body_list, p, out_x, out_y);
  } else {
    if (node_list.n > 0) k.multipole64(tx, ty, count, node_list, p, out_x, out_y);
    k.group64(tx, ty, count, body_list, p, out_x, out_y);
  }
}

BarnesHut::BarnesHut() : workspace_(std::make_unique<Workspace>()) {}
BarnesHut::~BarnesHut() = default;
BarnesHut::BarnesHut(BarnesHut&&) noexcept = default;
BarnesHut& BarnesHut::operator=(BarnesHut&&) noexcept = default;

const BarnesHutStats& BarnesHut::stats() const {
  static const BarnesHutStats empty;
  return workspace_ ? workspace_->stats : empty;
}

void BarnesHut::accelerations(std::span<const double> x, std::span<const double> y,
                              std::span<const double> mass, std::span<double> ax,
                              std::span<double> ay, const BarnesHutOptions& options) {
  const char* where = "nbody::BarnesHut::accelerations";
  detail::validate(where, x, y, mass, ax, ay, options);
  if (!(options.theta >= 0.0 && options.theta <= 1.0)) {
    throw Error(std::string(where) + ": options.theta must be in [0, 1] (got " +
                calder::detail::format_number(options.theta) + ")");
  }
  if (options.leaf_size < 1 || options.group_size < 1) {
    throw Error(
        std::string(where) + ": options.leaf_size and options.group_size must be >= 1 (got " +
        std::to_string(options.leaf_size) + " and " + std::to_string(options.group_size) + ")");
  }
  if (x.size() >= std::size_t{std::numeric_limits<std::uint32_t>::max()}) {
    throw Error(std::string(where) + ": too many bodies (at most 2^32 - 2)");
  }
  if (!workspace_) workspace_ = std::make_unique<Workspace>();
  Workspace& w = *workspace_;
  const std::size_t n = x.size();
  w.stats = BarnesHutStats{};
  w.stats.bodies = n;
  if (n < 2) return;
  const int threads = detail::thread_count(options);

  // Build.
  const Clock::time_point t0 = Clock::now();
  w.leaf_size = static_cast<std::size_t>(options.leaf_size);
  w.group_size = static_cast<std::size_t>(options.group_size);
  w.inv_theta = options.theta > 0.0 ? 1.0 / options.theta : std::numeric_limits<double>::infinity();
  w.sort_bodies(x, y, mass, threads);
  w.build_tree(threads);

  // The kernels' inputs: per-node moments and per-body masses in the precision used.
  const detail::FloatFrame frame = detail::float_frame(w.x0 + w.side * 0.5, w.y0 + w.side * 0.5,
                                                       w.side * 0.5, w.max_mass, options.G);
  detail::LawParams p = detail::law_params(options, frame);
  p.float_range = detail::float_range_of(w.side, p.eps2);
  const bool f32 = options.precision == Precision::float32;
  const std::size_t node_count = w.tree.nodes.size();
  const double q_scale = f32 ? frame.scale * frame.scale * frame.mass_scale : 1.0;
  const double m_scale = f32 ? frame.mass_scale : 1.0;
  const double o_scale = q_scale * (f32 ? frame.scale : 1.0);
  // Small trees: not worth waking threads (unused without OpenMP).
  [[maybe_unused]] const int team = n < 2000 ? 1 : threads;
  const auto fill_moments = [&](auto* out) {
    using T = std::remove_pointer_t<decltype(out)>;
#if defined(_OPENMP)
#pragma omp parallel for schedule(static) num_threads(team)
#endif
    for (std::ptrdiff_t node = 0; node < static_cast<std::ptrdiff_t>(node_count); ++node) {
      const auto i = static_cast<std::size_t>(node);
      const Moments& m = w.tree.moments[i];
      T* o = out + i * kMoments;
      o[0] = static_cast<T>(m.mass * m_scale);
      o[1] = static_cast<T>(3.0 * m.qxx * q_scale);
      o[2] = static_cast<T>(3.0 * m.qxy * q_scale);
      o[3] = static_cast<T>(3.0 * m.qyy * q_scale);
      o[4] = static_cast<T>(1.5 * (m.qxx + m.qyy) * q_scale);
      o[5] = static_cast<T>(7.5 * m.oxxx * o_scale);
      o[6] = static_cast<T>(7.5 * m.oxxy * o_scale);
      o[7] = static_cast<T>(7.5 * m.oxyy * o_scale);
      o[8] = static_cast<T>(7.5 * m.oyyy * o_scale);
      o[9] = static_cast<T>(1.5 * (m.oxxx + m.oxyy) * o_scale);  // P = sum m s |s|^2
      o[10] = static_cast<T>(1.5 * (m.oxxy + m.oyyy) * o_scale);
    }
  };
  if (f32) {
    w.node32.resize(node_count * kMoments);
    fill_moments(w.node32.data());
    w.sm32.resize(n);
#if defined(_OPENMP)
#pragma omp parallel for schedule(static) num_threads(team)
#endif
    for (std::ptrdiff_t r = 0; r < static_cast<std::ptrdiff_t>(n); ++r) {
      const auto u = static_cast<std::size_t>(r);
      w.sm32[u] = static_cast<float>(w.sm[u] * m_scale);
    }
  } else {
    w.node64.resize(node_count * kMoments);
    fill_moments(w.node64.data());
  }
  w.stats.build_seconds = seconds_since(t0);

  // Walk.
  const Clock::time_point t1 = Clock::now();
  const detail::KernelTable& k = detail::kernels();
  w.sum_x.resize(n);  // zeroed group by group in the walk
  w.sum_y.resize(n);
  w.scratch.resize(static_cast<std::size_t>(threads));
  for (auto& s : w.scratch) s.interactions = s.node_interactions = 0;
  const auto groups = static_cast<std::ptrdiff_t>(w.tree.groups.size());
  const double factor = f32 ? frame.factor : options.G;
#if defined(_OPENMP)
#pragma omp parallel num_threads(team)
#endif
  {
#if defined(_OPENMP)
    Workspace::Scratch& s = w.scratch[static_cast<std::size_t>(omp_get_thread_num())];
#pragma omp for schedule(dynamic, 1)
#else
    Workspace::Scratch& s = w.scratch[0];
#endif
    for (std::ptrdiff_t g = 0; g < groups; ++g) {
      const std::uint32_t group = w.tree.groups[static_cast<std::size_t>(g)];
      if (f32) {
        w.walk_group<float>(group, s, k, p, frame.scale);
      } else {
        w.walk_group<double>(group, s, k, p, frame.scale);
      }
    }
    // Back to the caller's order (a permutation: no two ranks write one body).
#if defined(_OPENMP)
#pragma omp for schedule(static)
#endif
    for (std::ptrdiff_t r = 0; r < static_cast<std::ptrdiff_t>(n); ++r) {
      const auto u = static_cast<std::size_t>(r);
      ax[w.order[u]] += factor * w.sum_x[u];
      ay[w.order[u]] += factor * w.sum_y[u];
    }
  }
  w.stats.walk_seconds = seconds_since(t1);

  w.stats.nodes = node_count;
  w.stats.groups = w.tree.groups.size();
  w.stats.depth = w.tree.depth;
  w.stats.leaves = w.tree.leaves;
  for (const auto& s : w.scratch) {
    w.stats.interactions += s.interactions;
    w.stats.node_interactions += s.node_interactions;
  }
}

void barnes_hut_accelerations(std::span<const double> x, std::span<const double> y,
                              std::span<const double> mass, std::span<double> ax,
                              std::span<double> ay, const BarnesHutOptions& options,
                              BarnesHutStats* stats) {
  BarnesHut solver;
  solver.accelerations(x, y, mass, ax, ay, options);
  if (stats != nullptr) *stats = solver.stats();
}

}  // namespace calder::nbody
