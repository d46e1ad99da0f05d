// SPDX-License-Identifier: MIT
// Barnes-Hut, the fast build's tree: the tree of BuiltTree's contract, depth
// first, each node the smallest quadtree cell holding its bodies. A sort
// range of more than group_size bodies is a subtree, which the thread that
// sorted it builds at once, from keys and bodies still in its cache
// (barnes_hut_sort.cpp); the top of the tree is then split serially down to
// those and to about kSubtrees subtrees for what is left, which threads
// build on their own; all are appended in a fixed order. The tree is unique,
// so the same for any number of threads, however its building was split.
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "barnes_hut_builder.hpp"

#if defined(_OPENMP)
#include <omp.h>
#endif

namespace calder::nbody::bh {

namespace {

double now_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// This thread's share [lo, hi) of n items, the same in every pass.
struct Slice {
  std::size_t t = 0;
  std::size_t nt = 1;
  std::size_t lo = 0;
  std::size_t hi = 0;
};
Slice my_slice(std::size_t n) {
#if defined(_OPENMP)
  const auto t = static_cast<std::size_t>(omp_get_thread_num());
  const auto nt = static_cast<std::size_t>(omp_get_num_threads());
#else
  const std::size_t t = 0;
  const std::size_t nt = 1;
#endif
  return Slice{t, nt, n * t / nt, n * (t + 1) / nt};
}

}  // namespace

// The whole build, one parallel region: the bounding square; Morton codes
// and the team's radix passes over static slices; the sort's ranges, each
// sorted and gathered by one thread, which then builds its subtree; the
// top of the tree (serially, small); the subtrees left by their threads;
// their nodes placed and their kernel moments written by the same threads;
// the top finished. Ranges and subtrees go to threads by assign_greedy,
// which depends on sizes and the thread count only.
void TreeBuilder::build(std::span<const double> x, std::span<const double> y,
                        std::span<const double> mass, const BuildSettings& settings, BuiltTree& out,
                        std::uint64_t* work) {
  const std::size_t n = x.size();
  settings_ = settings;
  out_ = &out;
  work_ = work;
  out.single = settings.single;
  team_ = team_for(n, settings.threads);
  phase_end_[0] = now_seconds();
  size_buffers(n);
#if defined(_OPENMP)
#pragma omp parallel num_threads(team_)
#endif
  {
    const Slice s = my_slice(n);
    // Thread 0 notes when each phase ends (after the wait that ends it).
    const auto mark = [&](int phase) {
      if (s.t == 0) phase_end_[phase] = now_seconds();
    };
    bound(x, y, s.t, s.nt);
#if defined(_OPENMP)
#pragma omp barrier
#endif
    mark(1);
    const Square square = combine_bounds(s.nt);
    if (s.t == 0) {  // read after the sort's barriers
      out.square = square;
      cells_ = CellGeometry(square, settings.inv_theta);
    }
    const MortonCoder code(square.x0, square.y0, square.side);
    first_pass(x, y, mass, code, s.t, s.nt);
#if defined(_OPENMP)
#pragma omp single
#endif
    {  // the float32 masses of subtrees built with their sort range need it
      const double half = square.side * 0.5;
      out.frame = detail::float_frame(square.x0 + half, square.y0 + half, half, heaviest_mass(s.nt),
                                      settings.G);
    }
    mark(2);
    sort_keys(code, s.t, s.nt);
    sort_own_ranges(code, s.t);
#if defined(_OPENMP)
#pragma omp barrier
#endif
    mark(3);
#if defined(_OPENMP)
#pragma omp single
#endif
    plan_tree();
    mark(4);
    build_own_parts(s.t);
#if defined(_OPENMP)
#pragma omp barrier
#endif
    mark(5);
#if defined(_OPENMP)
#pragma omp single
#endif
    place_parts();
    mark(6);
    copy_own_parts(s.t);
#if defined(_OPENMP)
#pragma omp barrier
#endif
    mark(7);
#if defined(_OPENMP)
#pragma omp single
#endif
    finish_top();
    mark(8);
  }
  out_ = nullptr;
  work_ = nullptr;
}

// The subtree of bodies [begin, end) into `part` (numbered from 0, its root
// at `depth`): nodes, moments and opening radii, and float32 masses.
void TreeBuilder::build_part(Tree& part, std::uint32_t begin, std::uint32_t end, int depth,
                             const SortedKeys& sorted, BuildScratch& buffers, bool several_ranges) {
  part.reset();
  // Room for twice the nodes of a uniform spread (one for every 15 bodies
  // with leaves of 32): the arrays grow past that if they must, up to
  // 2 (end - begin) nodes (every inner node has >= 2 children), which most
  // trees are far from.
  const std::size_t bodies = end - begin;
  const std::size_t expected = std::min(2 * bodies, 4 * bodies / settings_.leaf_size + 8);
  part.nodes.reserve(expected);
  part.moments.reserve(expected);
  build_node(part, 0, begin, end, depth, false, sorted);
  if (several_ranges) leaves_in_index_order(part, buffers.leaf_bodies);
  finish_part(part, sorted, buffers);
  if (out_->single) float_masses(*out_, begin, end);
}

// Each leaf's bodies in index order, as leaf_order leaves a leaf inside
// one sort range: a leaf of a part built after the sort may hold the bodies
// of several small ranges, each in index order on its own (the arrays are
// the whole sort's; `bodies`: the thread's scratch).
void TreeBuilder::leaves_in_index_order(const Tree& part, std::vector<LeafBody>& bodies) {
  for (const Node& node : part.nodes) {
    if (node.children != 0 ||
        std::is_sorted(out_->order.data() + node.begin, out_->order.data() + node.end)) {
      continue;
    }
    bodies.clear();
    for (std::uint32_t r = node.begin; r < node.end; ++r) {
      bodies.push_back(LeafBody{keys_[r], out_->sx[r], out_->sy[r], out_->sm[r], out_->order[r]});
    }
    std::sort(bodies.begin(), bodies.end(),
              [](const LeafBody& a, const LeafBody& b) { return a.index < b.index; });
    for (std::uint32_t r = node.begin; r < node.end; ++r) {
      const LeafBody& body = bodies[r - node.begin];
      keys_[r] = body.key;
      out_->sx[r] = body.x;
      out_->sy[r] = body.y;
      out_->sm[r] = body.m;
      out_->order[r] = body.index;
    }
  }
}

// Where the quadrants of the bodies [begin, end) (common prefix `level`,
// end - begin >= 2) start: bounds[q] for digit q, bounds[4] = end. A node
// of the top of the tree (in_top) holds whole sort ranges, each inside one of
// its quadrants: a search over the ranges' first keys (range_firsts, in the
// cache), not over keys that are not. Below: three binary searches over the
// keys side by side, each step a conditional move, not a branch.
void TreeBuilder::quadrant_bounds(std::uint32_t begin, std::uint32_t end, int level, bool in_top,
                                  const SortedKeys& sorted, std::uint32_t (&bounds)[5]) const {
  // The quadrant digit below the common prefix: bits 2 (kBits - 1 - level) + {0, 1}.
  const int shift = 2 * (kBits - 1 - level);
  const auto digit = [&](std::uint64_t key) { return (key >> shift) & 3u; };
  bounds[0] = begin;
  bounds[4] = end;
  if (in_top) {
    using First = std::pair<std::uint32_t, std::uint64_t>;
    const auto by_body = [](const First& r, std::uint32_t body) { return r.first < body; };
    auto from = std::lower_bound(range_firsts_.begin(), range_firsts_.end(), begin, by_body);
    const auto to = std::lower_bound(from, range_firsts_.end(), end, by_body);
    for (std::uint64_t d = 1; d < 4; ++d) {
      from = std::partition_point(from, to, [&](const First& r) { return digit(r.second) < d; });
      bounds[d] = from == to ? end : from->first;
    }
    return;
  }
  std::uint32_t first[3] = {begin, begin, begin};
  std::uint32_t length = end - begin;
  while (length > 1) {
    const std::uint32_t half = length / 2;
    for (std::uint32_t d = 0; d < 3; ++d) {
      first[d] = digit(sorted[first[d] + half - 1]) <= d ? first[d] + half : first[d];
    }
    length -= half;
  }
  for (std::uint32_t d = 0; d < 3; ++d) {
    bounds[d + 1] = first[d] + (digit(sorted[first[d]]) <= d ? 1u : 0u);
  }
}

// Splits node `index` (bodies [begin, end), common prefix `level`) into its
// non-empty quadrants, appended to nodes (and moments) as contiguous
// children; returns how many. bounds: the quadrants' body ranges; in_top:
// see quadrant_bounds.
std::uint32_t TreeBuilder::split(UnsetVector<Node>& nodes, UnsetVector<Moments>& moments,
                                 std::uint32_t index, std::uint32_t begin, std::uint32_t end,
                                 int level, bool in_top, const SortedKeys& sorted,
                                 std::uint32_t (&bounds)[5]) const {
  quadrant_bounds(begin, end, level, in_top, sorted, bounds);
  std::uint32_t children = 0;
  for (int q = 0; q < 4; ++q) children += bounds[q + 1] > bounds[q] ? 1 : 0;
  Node& node = nodes[index];
  node.begin = begin;
  node.end = end;
  node.child = static_cast<std::uint32_t>(nodes.size());
  node.children = children;
  nodes.resize(nodes.size() + children);
  moments.resize(nodes.size());
  return children;
}

// The top of the tree (serially, plan), the subtrees built with their sort
// ranges swapped in, and the sizes of those left to build. Where the top
// ends depends on the sort's ranges, and so on the number of threads, but
// not the tree: each node is the smallest cell holding its bodies, split
// while it has more than leaf_size, wherever it was built; and there is
// never a group or a leaf above the subtrees.
void TreeBuilder::plan_tree() {
  with_sort_.clear();
  range_firsts_.clear();
  for (std::size_t r = 0; r < sort_.small.size(); ++r) {
    const SortRange& range = sort_.small[r];
    range_firsts_.emplace_back(range.begin, keys_[range.begin]);
    if (builds_with_sort(range))
      with_sort_.emplace_back(range.begin, static_cast<std::uint32_t>(r));
  }
  std::sort(with_sort_.begin(), with_sort_.end());
  std::sort(range_firsts_.begin(), range_firsts_.end());
  const auto n = static_cast<std::uint32_t>(keys_.size());
  out_->nodes.assign(1, Node{});
  out_->groups.clear();
  out_->depth = 0;
  out_->leaves = 0;
  top_moments_.assign(1, Moments{});
  pending_.clear();
  top_.clear();
  const std::size_t cutoff =
      std::max({std::size_t{n} / kSubtrees, settings_.group_size, settings_.leaf_size});
  plan(0, 0, n, 0, cutoff);
  if (parts_.size() < pending_.size()) parts_.resize(pending_.size());
  item_sizes_.resize(pending_.size());
  for (std::size_t k = 0; k < pending_.size(); ++k) {
    const Pending& p = pending_[k];
    if (p.range == kNoRange) {
      item_sizes_[k] = p.end - p.begin;
      continue;
    }
    item_sizes_[k] = 0;  // built: its storage swapped in, its depth from here
    std::swap(parts_[k], range_parts_[p.range]);
    parts_[k].depth += p.depth;
  }
}

// Thread t's subtrees, each in its own Tree (numbered from 0), and their
// bodies' float32 masses.
void TreeBuilder::build_own_parts(std::size_t t) {
  BuildScratch& mine = scratch_[t];
  assign_greedy(item_sizes_, static_cast<std::size_t>(team_), t, scratch_[t].own_parts,
                mine.by_size, mine.loads);
  std::uint64_t bodies = 0;
  for (const std::uint32_t k : scratch_[t].own_parts) {
    const Pending& p = pending_[k];
    if (p.range != kNoRange) continue;  // built with its sort range
    // The splits' binary searches read the keys at scattered places, one
    // miss after another: fetch the part's keys first, all at once.
    for (std::uint32_t b = p.begin; b < p.end; b += 8) __builtin_prefetch(keys_.data() + b);
    build_part(parts_[k], p.begin, p.end, p.depth, all_keys(), mine, true);
    bodies += p.end - p.begin;
  }
  // With the subtrees this thread built with its sort ranges.
  work_[kRegionSubtrees * static_cast<std::size_t>(team_) + t] += bodies;
}

// Where the parts' nodes go: part k's node c to its root's slot (c = 0) or
// to part_base[k] + c - 1; and its groups: from group_base[k] on (the groups
// in part order).
void TreeBuilder::place_parts() {
  part_base_.resize(pending_.size() + 1);
  group_base_.resize(pending_.size() + 1);
  part_base_[0] = out_->nodes.size();
  group_base_[0] = 0;  // no group above the parts
  for (std::size_t k = 0; k < pending_.size(); ++k) {
    part_base_[k + 1] = part_base_[k] + parts_[k].nodes.size() - 1;
    group_base_[k + 1] = group_base_[k] + parts_[k].groups.size();
    out_->depth = std::max(out_->depth, parts_[k].depth);
    out_->leaves += parts_[k].leaves;
  }
  const std::size_t nodes = part_base_.back();
  out_->nodes.resize(nodes);  // top_moments_: the top and the parts' roots only (finish_top)
  out_->parent.resize(nodes);
  (out_->single ? out_->node32.resize(nodes * kMoments) : out_->node64.resize(nodes * kMoments));
  out_->groups.resize(group_base_.back());  // written by copy_own_parts
}

// The parts' nodes into the tree, with their parents, kernel moments and
// groups: thread t takes its slice of all the parts' nodes, one after the
// other (part k's start among them: part_base[k] - part_base[0] + k).
void TreeBuilder::copy_own_parts(std::size_t t) {
  const std::size_t parts_n = pending_.size();
  const std::size_t total = part_base_[parts_n] - part_base_[0] + parts_n;
  const auto nt = static_cast<std::size_t>(team_);
  const std::size_t lo = total * t / nt;
  const std::size_t hi = total * (t + 1) / nt;
  const auto start = [&](std::size_t k) { return part_base_[k] - part_base_[0] + k; };
  // The part holding item lo: the last k with start(k) <= lo.
  std::size_t lo_k = 0;
  std::size_t hi_k = parts_n;
  while (hi_k - lo_k > 1) {
    const std::size_t mid = (lo_k + hi_k) / 2;
    (start(mid) <= lo ? lo_k : hi_k) = mid;
  }
  for (std::size_t k = lo_k, item = lo; item < hi; ++k) {
    const Tree& part = parts_[k];
    const std::uint32_t root = pending_[k].index;
    const auto base = static_cast<std::uint32_t>(part_base_[k]);
    for (std::size_t c = item - start(k); c < part.nodes.size() && item < hi; ++c, ++item) {
      Node node = part.nodes[c];
      const auto to = static_cast<std::uint32_t>(c == 0 ? root : base + c - 1);
      if (node.children > 0) {
        node.child = base + node.child - 1;
        for (std::uint32_t d = node.child; d < node.child + node.children; ++d)
          out_->parent[d] = to;
      }
      out_->nodes[to] = node;
      if (c == 0) {  // with the part's groups, by the thread that has its root
        top_moments_[to] = part.moments[c];
        std::uint32_t* groups = out_->groups.data() + group_base_[k];
        for (const std::uint32_t g : part.groups) *groups++ = g == 0 ? root : base + g - 1;
      }
      kernel_moments(*out_, to, part.moments[c]);
    }
  }
  work_[kRegionNodes * nt + t] = hi - lo;
}

// The nodes above the subtrees, bottom up (children first), with their
// kernel moments and their children's parent.
void TreeBuilder::finish_top() {
  out_->parent[0] = ~std::uint32_t{0};
  for (auto it = top_.rbegin(); it != top_.rend(); ++it) {
    finish_node(out_->nodes.data(), top_moments_.data(), *it, all_keys());
    kernel_moments(*out_, *it, top_moments_[*it]);
    const Node& node = out_->nodes[*it];
    for (std::uint32_t c = node.child; c < node.child + node.children; ++c) out_->parent[c] = *it;
  }
}

// Splits the top of the tree, serially, down to the subtrees built with
// their sort ranges and to nodes of at most `cutoff` bodies (or of one
// Morton code) that hold none of those, which all go to `pending`.
void TreeBuilder::plan(std::uint32_t index, std::uint32_t begin, std::uint32_t end, int tree_depth,
                       std::size_t cutoff) {
  bool inside = false;
  const std::uint32_t range = range_with_sort(begin, end, inside);
  if (range != kNoRange) {
    pending_.push_back(Pending{index, begin, end, tree_depth, range});
    return;
  }
  const int level = level_of(begin, end, all_keys());
  if ((end - begin <= cutoff && !inside) || level == kBits) {
    pending_.push_back(Pending{index, begin, end, tree_depth, kNoRange});
    return;
  }
  top_.push_back(index);
  std::uint32_t bounds[5];
  split(out_->nodes, top_moments_, index, begin, end, level, true, all_keys(), bounds);
  std::uint32_t c = out_->nodes[index].child;
  for (int q = 0; q < 4; ++q) {
    if (bounds[q + 1] > bounds[q]) plan(c++, bounds[q], bounds[q + 1], tree_depth + 1, cutoff);
  }
}

// The range of with_sort whose bodies are [begin, end), or kNoRange; inside:
// whether one lies within [begin, end) (ranges and nodes are cells' bodies:
// nested or apart).
std::uint32_t TreeBuilder::range_with_sort(std::uint32_t begin, std::uint32_t end,
                                           bool& inside) const {
  const auto it = std::lower_bound(with_sort_.begin(), with_sort_.end(),
                                   std::pair<std::uint32_t, std::uint32_t>{begin, 0});
  inside = it != with_sort_.end() && it->first < end;
  if (!inside || it->first != begin) return kNoRange;
  const SortRange& range = sort_.small[it->second];
  return range.end == end ? it->second : kNoRange;
}

// Builds node `index` of t over the bodies [begin, end) (end > begin) and its
// subtree, their moments left to finish_part: split unless it has at most
// leaf_size bodies or they all share one Morton code. The first node on each
// path with at most group_size bodies (or a leaf) is a group.
void TreeBuilder::build_node(Tree& t, std::uint32_t index, std::uint32_t begin, std::uint32_t end,
                             int tree_depth, bool in_group, const SortedKeys& sorted) const {
  const int level = level_of(begin, end, sorted);
  t.depth = std::max(t.depth, tree_depth);
  const std::size_t count = end - begin;
  const bool leaf = count <= settings_.leaf_size || level == kBits;
  if (!in_group && (count <= settings_.group_size || leaf)) {
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
    split(t.nodes, t.moments, index, begin, end, level, false, sorted, bounds);
    std::uint32_t c = t.nodes[index].child;
    for (int q = 0; q < 4; ++q) {
      if (bounds[q + 1] > bounds[q])
        build_node(t, c++, bounds[q], bounds[q + 1], tree_depth + 1, in_group, sorted);
    }
  }
}

void assign_greedy(const std::vector<std::uint64_t>& sizes, std::size_t nt, std::size_t t,
                   std::vector<std::uint32_t>& mine, std::vector<std::uint32_t>& by_size,
                   std::vector<std::uint64_t>& load) {
  mine.clear();
  by_size.resize(sizes.size());
  for (std::size_t i = 0; i < sizes.size(); ++i) by_size[i] = static_cast<std::uint32_t>(i);
  if (nt <= 1) {
    mine = by_size;
    return;
  }
  std::sort(by_size.begin(), by_size.end(), [&](std::uint32_t a, std::uint32_t b) {
    return sizes[a] != sizes[b] ? sizes[a] > sizes[b] : a < b;
  });
  load.assign(nt, 0);
  for (const std::uint32_t item : by_size) {
    const auto least =
        static_cast<std::size_t>(std::min_element(load.begin(), load.end()) - load.begin());
    if (least == t) mine.push_back(item);
    load[least] += sizes[item];
  }
  std::sort(mine.begin(), mine.end());  // in memory order
}

}  // namespace calder::nbody::bh
