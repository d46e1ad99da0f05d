// SPDX-License-Identifier: MIT
// Barnes-Hut, the build: bounding square; 48-bit Morton codes (24 bits per
// axis); their radix sort (8-bit digits, the first 10 bits wide for many
// bodies: the threads split the bodies, each carried as a 32-byte record, by
// their top digits until the ranges fit in cache, then order ranges on
// their own down to the leaves and write them out: leaves in Morton order, a
// leaf's bodies in index order; that order depends on the bodies alone, so
// it is the same for any thread count); the tree, depth first, each node
// the smallest quadtree cell holding its bodies; mass, centre of mass and
// second to fourth moments bottom up (parallel axis theorem). A sort range
// of more than group_size bodies is a subtree, which the thread that sorted
// it builds at once, from keys and bodies still in its cache; the top of the
// tree is then split serially down to those and to about kSubtrees
// subtrees for what is left, which threads build on their own; all are
// appended in a fixed order. The tree is unique, so the same for any number
// of threads, however its building was split.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "barnes_hut_tree.hpp"

#if defined(_OPENMP)
#include <omp.h>
#endif
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace calder::nbody {

using bh::kBits;
using bh::kCells;

namespace {

double now_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
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

int leading_zeros(std::uint64_t x) {  // x != 0 (no <bit>: Emscripten's libc++ 13 lacks it)
#if defined(__GNUC__) || defined(__clang__)
  return __builtin_clzll(x);
#else
  int n = 0;
  for (int step = 32; step > 0; step /= 2) {
    if ((x >> (64 - step)) == 0) {
      n += step;
      x <<= step;
    }
  }
  return n;
#endif
}

// The quadtree levels that Morton codes share, from the bits in which they
// differ: kBits where they are all one code.
int shared_levels(std::uint64_t differ) {
  return differ == 0 ? kBits : (leading_zeros(differ) - (64 - 2 * kBits)) / 2;
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

// Whether a record starts a cache line (records are 32-byte aligned).
inline bool starts_line(const bh::Record* r) {
  return (reinterpret_cast<std::uintptr_t>(r) & 63u) == 0;
}

// kStage records to `to` (64-byte aligned) with non-temporal stores where
// the processor has them; end_streams orders them before what follows.
inline void stream_stage(const bh::Record* from, bh::Record* to) {
#if defined(__SSE2__)
  const auto* f = reinterpret_cast<const __m128i*>(from);
  auto* d = reinterpret_cast<__m128i*>(to);
  for (std::size_t k = 0; k < bh::kStage * sizeof(bh::Record) / 16; ++k) {
    _mm_stream_si128(d + k, _mm_load_si128(f + k));
  }
#else
  std::copy(from, from + bh::kStage, to);
#endif
}
inline void end_streams() {
#if defined(__SSE2__)
  _mm_sfence();
#endif
}

// Orders in[0, length) into out by leaf. The values are packed keys: `bits`
// key bits (even: whole levels, below a cell that holds them all and more
// than leaf_size of them), then place_bits of their place in `in`. A value's
// leaf cell is the largest cell below that one that holds it and at most
// leaf_size values; leaves go in Morton order and each keeps its values in
// their order in `in` (for a sort range, index order). That order depends on
// the bodies alone, not on how the sort was split into ranges, and the tree
// reads no finer order: its nodes are cells of more than leaf_size bodies,
// split by quadrant. One counting pass by the next b bits (cells of about
// four values), the counts summed up level by level into a pyramid; the
// leaves found from its top; then one stable pass into out, the cells of one
// leaf writing through one cursor. A cell of the pass that holds more than
// leaf_size values is ordered the same way by the bits below (`in` is spare
// by then). levels: the thread's scratch, one entry a level of recursion.
void leaf_order(std::uint64_t* in, std::uint64_t* out, std::size_t length, int bits, int place_bits,
                std::size_t leaf_size, bh::LeafLevel* levels) {
  int b = 2;
  while (b + 2 <= bits && b + 2 <= bh::kMaxLeafBits && (std::size_t{4} << (b + 2)) <= length) {
    b += 2;
  }
  const int top = b / 2;  // the pyramid's levels below its root: 0 to top
  const int shift = place_bits + bits - b;
  const std::uint64_t mask = (std::uint64_t{1} << b) - 1;
  const auto level_at = [](int h) { return ((std::size_t{1} << (2 * h)) - 1) / 3; };
  bh::LeafLevel& s = levels[0];
  s.counts.assign(level_at(top + 1), 0u);
  std::uint32_t* finest = s.counts.data() + level_at(top);
  const auto cell = [&](std::uint64_t v) { return static_cast<std::size_t>((v >> shift) & mask); };
  for (std::size_t i = 0; i < length; ++i) ++finest[cell(in[i])];
  for (int h = top - 1; h >= 0; --h) {
    std::uint32_t* cells = s.counts.data() + level_at(h);
    const std::uint32_t* below = s.counts.data() + level_at(h + 1);
    for (std::size_t c = 0; c < (std::size_t{1} << (2 * h)); ++c) {
      cells[c] = below[4 * c] + below[4 * c + 1] + below[4 * c + 2] + below[4 * c + 3];
    }
  }
  // The leaves, depth first in Morton order: each gets a cursor, and its
  // cells of the pass the cursor's number.
  s.slot.resize(std::size_t{1} << b);
  s.cursor.clear();
  s.dense.clear();
  s.stack.assign(1, std::pair<int, std::uint32_t>{0, 0u});
  std::uint32_t offset = 0;
  while (!s.stack.empty()) {
    const auto [h, c] = s.stack.back();
    s.stack.pop_back();
    const std::uint32_t count = s.counts[level_at(h) + c];
    if (count == 0) continue;
    if (count > leaf_size && h < top) {
      for (std::uint32_t q = 4; q-- > 0;) s.stack.emplace_back(h + 1, 4 * c + q);
      continue;
    }
    if (count > leaf_size) s.dense.emplace_back(offset, count);
    const int below = 2 * (top - h);
    std::fill_n(s.slot.data() + (std::size_t{c} << below), std::size_t{1} << below,
                static_cast<std::uint32_t>(s.cursor.size()));
    s.cursor.push_back(offset);
    offset += count;
  }
  for (std::size_t i = 0; i < length; ++i) {
    const std::uint64_t v = in[i];
    out[s.cursor[s.slot[cell(v)]]++] = v;
  }
  if (bits == b) return;  // a dense cell's values share their key: in place order
  for (const auto& [first, count] : s.dense) {
    leaf_order(out + first, in + first, count, bits - b, place_bits, leaf_size, levels + 1);
    std::copy(in + first, in + first + count, out + first);
  }
}

}  // namespace

// The whole build, one parallel region: the bounding square; Morton codes
// and the team's radix passes over static slices; the sort's ranges, each
// sorted and gathered by one thread, which then builds its subtree; the
// top of the tree (serially, small); the subtrees left by their threads;
// their nodes placed and their kernel moments written by the same threads;
// the top finished. Ranges and subtrees go to threads by assign_greedy,
// which depends on sizes and the thread count only.
void BarnesHut::Workspace::build(std::span<const double> x, std::span<const double> y,
                                 std::span<const double> mass, int threads, double G) {
  const std::size_t n = x.size();
  team = bh::team_for(n, threads);
  phase_end[0] = now_seconds();
  size_buffers(n);
#if defined(_OPENMP)
#pragma omp parallel num_threads(team)
#endif
  {
    const Slice s = my_slice(n);
    // Thread 0 notes when each phase ends (after the wait that ends it).
    const auto mark = [&](int phase) {
      if (s.t == 0) phase_end[phase] = now_seconds();
    };
    bound(x, y, s.t, s.nt);
#if defined(_OPENMP)
#pragma omp barrier
#endif
    mark(1);
    const bh::Square square = combine_bounds(s.nt);
    if (s.t == 0) {  // read after the sort's barriers
      x0 = square.x0;
      y0 = square.y0;
      side = square.side;
      for (int level = 0; level <= kBits; ++level) {
        cell_size[static_cast<std::size_t>(level)] = std::ldexp(side, -level);
      }
    }
    const bh::MortonCoder code(square.x0, square.y0, square.side);
    first_pass(x, y, mass, code, s.t, s.nt);
#if defined(_OPENMP)
#pragma omp single
#endif
    {  // the float32 masses of subtrees built with their sort range need it
      max_mass = heaviest_mass(s.nt);
      frame = detail::float_frame(x0 + side * 0.5, y0 + side * 0.5, side * 0.5, max_mass, G);
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
}

// The buffers' sizes for n bodies and the team (grown, never shrunk in
// capacity: a solver called every step allocates once).
void BarnesHut::Workspace::size_buffers(std::size_t n) {
  const auto nt = static_cast<std::size_t>(team);
  keys.resize(n);
  order.resize(n);
  records.resize(n);
  records_tmp.resize(n);
  // The leaf kernel reads a few elements past a leaf: readable and set.
  for (auto* column : {&sx, &sy, &sm}) {
    column->resize(n + bh::kLeafPadding);
    std::fill(column->begin() + static_cast<std::ptrdiff_t>(n), column->end(), 0.0);
  }
  if (single) sm32.resize(n);
  first_bits = n >= bh::kWideFirstFrom ? bh::kWideFirstBits : bh::kRadixBits;
  radix_counts.resize(nt * bh::kFirstBuckets);
  if (sort_scratch.size() < nt) sort_scratch.resize(nt);
  for (std::size_t t = 0; t < nt; ++t) sort_scratch[t].stage.resize(bh::kFirstBuckets * bh::kStage);
  own_ranges.resize(nt);
  own_parts.resize(nt);
  partial.assign(5 * nt, 0.0);
  work.assign(bh::kRegions * nt, 0);
  team_split_from =
      std::min(bh::kSortInCache, std::max(n / (nt * bh::kRangesPerThread), bh::kMinTeamSplit));
  sort_large.clear();
  sort_small.clear();
}

// Thread t's share of the bounding box (the heaviest mass: first_pass,
// which reads the masses anyway).
void BarnesHut::Workspace::bound(std::span<const double> x, std::span<const double> y,
                                 std::size_t t, std::size_t nt) {
  const std::size_t n = x.size();
  const std::size_t lo = n * t / nt;
  const std::size_t hi = n * (t + 1) / nt;
  double xmin = x[lo];
  double xmax = x[lo];
  double ymin = y[lo];
  double ymax = y[lo];
  for (std::size_t i = lo; i < hi; ++i) {
    xmin = std::min(xmin, x[i]);
    xmax = std::max(xmax, x[i]);
    ymin = std::min(ymin, y[i]);
    ymax = std::max(ymax, y[i]);
  }
  double* p = partial.data() + 5 * t;
  p[0] = xmin;
  p[1] = xmax;
  p[2] = ymin;
  p[3] = ymax;
}

// The root square from the threads' boxes: the lower corner and the larger
// side (min and max are exact: the same for any split). Every thread works
// it out for itself.
bh::Square BarnesHut::Workspace::combine_bounds(std::size_t nt) const {
  double xmin = partial[0];
  double xmax = partial[1];
  double ymin = partial[2];
  double ymax = partial[3];
  for (std::size_t t = 1; t < nt; ++t) {
    const double* p = partial.data() + 5 * t;
    xmin = std::min(xmin, p[0]);
    xmax = std::max(xmax, p[1]);
    ymin = std::min(ymin, p[2]);
    ymax = std::max(ymax, p[3]);
  }
  double larger = std::max(xmax - xmin, ymax - ymin);
  if (!(larger > 0.0)) larger = 1.0;  // one point (or one body)
  return bh::Square{xmin, ymin, larger};
}

// The heaviest mass, from the threads' shares (first_pass).
double BarnesHut::Workspace::heaviest_mass(std::size_t nt) const {
  double most = partial[4];
  for (std::size_t t = 1; t < nt; ++t) most = std::max(most, partial[5 * t + 4]);
  return most;
}

// The first radix pass, by the keys' top digit, after the Morton codes:
// thread t codes and counts its slice (keys, in the caller's order until the
// sort writes them over), then (the team's offsets known) writes its bodies
// as records to their buckets in `records`. Stable: equal digits stay in
// index order.
void BarnesHut::Workspace::first_pass(std::span<const double> x, std::span<const double> y,
                                      std::span<const double> mass, const bh::MortonCoder& code,
                                      std::size_t t, std::size_t nt) {
  const int shift = 2 * kBits - first_bits;
  const std::size_t buckets = std::size_t{1} << first_bits;
  const std::size_t n = x.size();
  const std::size_t lo = n * t / nt;
  const std::size_t hi = n * (t + 1) / nt;
  std::size_t* counts = radix_counts.data() + t * bh::kFirstBuckets;
  std::fill(counts, counts + buckets, std::size_t{0});
  // The keys in the caller's order, until sort_range writes them over: coded
  // once, read by the count and by the writes.
  std::uint64_t* key = keys.data();
  bh::build_kernels().morton_keys(x.data() + lo, y.data() + lo, hi - lo, code, key + lo);
  for (std::size_t i = lo; i < hi; ++i) ++counts[key[i] >> shift];
#if defined(_OPENMP)
#pragma omp barrier
#endif
  std::size_t mine[bh::kFirstBuckets];
  std::size_t ends[bh::kFirstBuckets];
  bucket_offsets(0, t, nt, buckets, mine, ends);
  if (t == 0) {  // the whole range, as if it came from records_tmp: now in records
    list_ranges(bh::SortRange{0, static_cast<std::uint32_t>(n), 2 * kBits, true}, first_bits, ends,
                false);
  }
  // Each bucket's records gather in the thread's stage (in its L2) and go
  // out kStage at a time: whole cache lines, one page at a time, instead of
  // one store in 256 (or more) far places a body.
  bh::Record* out = records.data();
  bh::Record* stage = sort_scratch[t].stage.data();
  std::uint8_t* fill = sort_scratch[t].fill;
  // A full stage starts a cache line and goes out past the caches (no read
  // of lines about to be written whole); a bucket that starts a line's
  // second half writes its first record on its own.
  std::uint8_t* want = sort_scratch[t].want;
  for (std::size_t b = 0; b < buckets; ++b) {
    fill[b] = 0;
    want[b] = starts_line(out + mine[b]) ? bh::kStage : 1;
  }
  double heaviest = 0.0;
  for (std::size_t i = lo; i < hi; ++i) {
    const auto b = static_cast<std::size_t>(key[i] >> shift);
    bh::Record* slot = stage + b * bh::kStage;
    heaviest = std::max(heaviest, mass[i]);
    slot[fill[b]] = bh::Record{x[i], y[i], mass[i], static_cast<std::uint32_t>(i)};
    if (++fill[b] == want[b]) {
      if (want[b] == bh::kStage) {
        stream_stage(slot, out + mine[b]);
      } else {
        out[mine[b]] = slot[0];
      }
      mine[b] += want[b];
      fill[b] = 0;
      want[b] = bh::kStage;
    }
  }
  for (std::size_t b = 0; b < buckets; ++b) {
    const bh::Record* slot = stage + b * bh::kStage;
    for (std::size_t k = 0; k < fill[b]; ++k) out[mine[b] + k] = slot[k];
  }
  end_streams();
  partial[5 * t + 4] = heaviest;
  work[bh::kRegionBodies * nt + t] += hi - lo;
#if defined(_OPENMP)
#pragma omp barrier
#endif
}

// Thread t's offsets into each bucket of a pass over a range starting at
// `begin` (exclusive prefix sums of the team's counts, bucket-major then
// thread) and each bucket's end; returns the largest bucket's size.
std::size_t BarnesHut::Workspace::bucket_offsets(std::size_t begin, std::size_t t, std::size_t nt,
                                                 std::size_t buckets, std::size_t* mine,
                                                 std::size_t* ends) const {
  std::size_t offset = begin;
  std::size_t largest = 0;
  for (std::size_t b = 0; b < buckets; ++b) {
    const std::size_t first = offset;
    for (std::size_t u = 0; u < nt; ++u) {
      if (u == t) mine[b] = offset;
      offset += radix_counts[u * bh::kFirstBuckets + b];
    }
    ends[b] = offset;
    largest = std::max(largest, offset - first);
  }
  return largest;
}

// Thread t's ranges: each sorted, and its bodies written out in Morton order
// (keys, order, sx, sy, sm).
void BarnesHut::Workspace::sort_own_ranges(const bh::MortonCoder& code, std::size_t t) {
  std::uint64_t done = 0;
  std::uint64_t built = 0;
  for (const std::uint32_t r : own_ranges[t]) {
    const bh::SortRange& range = sort_small[r];
    SortScratch& mine = sort_scratch[t];
    sort_range(code, range, mine);
    done += range.end - range.begin;
    if (builds_with_sort(range)) {
      build_part(range_parts[r], range.begin, range.end, 0,
                 bh::SortedKeys{mine.range_keys.data(), range.begin}, mine, false);
      built += range.end - range.begin;
    }
  }
  const auto nt = static_cast<std::size_t>(team);
  work[bh::kRegionRanges * nt + t] = done;
  work[bh::kRegionSubtrees * nt + t] = built;
}

// Whether the thread that sorts `range` builds its subtree straight after,
// from the keys and bodies it has just written: the range is a quadtree
// cell's bodies (its digits are whole levels), so with more than
// group_size of them they are one node's, every node above it split and
// none of them a group, whatever else the tree holds.
bool BarnesHut::Workspace::builds_with_sort(const bh::SortRange& range) const {
  return range.end - range.begin > std::max(group_size, leaf_size);
}

// The subtree of bodies [begin, end) into `part` (numbered from 0, its root
// at `depth`): nodes, moments and opening radii, and float32 masses.
void BarnesHut::Workspace::build_part(bh::Tree& part, std::uint32_t begin, std::uint32_t end,
                                      int depth, const bh::SortedKeys& sorted, SortScratch& buffers,
                                      bool several_ranges) {
  part.reset();
  // Room for twice the nodes of a uniform spread (one for every 15 bodies
  // with leaves of 32): the arrays grow past that if they must, up to
  // 2 (end - begin) nodes (every inner node has >= 2 children), which most
  // trees are far from.
  const std::size_t bodies = end - begin;
  const std::size_t expected = std::min(2 * bodies, 4 * bodies / leaf_size + 8);
  part.nodes.reserve(expected);
  part.moments.reserve(expected);
  build_node(part, 0, begin, end, depth, false, sorted);
  if (several_ranges) leaves_in_index_order(part, buffers.leaf_bodies);
  finish_part(part, sorted, buffers);
  if (single) float_masses(begin, end);
}

// Each leaf's bodies in index order, as leaf_order leaves a leaf inside
// one sort range: a leaf of a part built after the sort may hold the bodies
// of several small ranges, each in index order on its own (the arrays are
// the whole sort's; `bodies`: the thread's scratch).
void BarnesHut::Workspace::leaves_in_index_order(const bh::Tree& part,
                                                 std::vector<bh::LeafBody>& bodies) {
  for (const bh::Node& node : part.nodes) {
    if (node.children != 0 || std::is_sorted(order.data() + node.begin, order.data() + node.end)) {
      continue;
    }
    bodies.clear();
    for (std::uint32_t r = node.begin; r < node.end; ++r) {
      bodies.push_back(bh::LeafBody{keys[r], sx[r], sy[r], sm[r], order[r]});
    }
    std::sort(bodies.begin(), bodies.end(),
              [](const bh::LeafBody& a, const bh::LeafBody& b) { return a.index < b.index; });
    for (std::uint32_t r = node.begin; r < node.end; ++r) {
      const bh::LeafBody& body = bodies[r - node.begin];
      keys[r] = body.key;
      sx[r] = body.x;
      sy[r] = body.y;
      sm[r] = body.m;
      order[r] = body.index;
    }
  }
}

// Sorts the bodies by key down to the leaves (leaf_order), called by every
// thread t of a team of nt after first_pass. A most significant digit first
// radix sort: the team splits a range by its next digit (a stable counting
// pass, thread slices in order) while it is larger than team_split_from,
// then the ranges go to threads (assign_greedy), each ordered on its own by
// its remaining bits (sort_own_ranges, sort_range). The order depends on the
// bodies alone, not on the number of threads or on how the work was split.
void BarnesHut::Workspace::sort_keys(const bh::MortonCoder& code, std::size_t t, std::size_t nt) {
  for (std::size_t r = 0; r < sort_large.size(); ++r) {
    const bh::SortRange range = sort_large[r];  // a copy: the single below may grow the list
    split_range(code, range, t, nt);
    work[bh::kRegionSplit * nt + t] +=
        (range.end - range.begin) * (t + 1) / nt - (range.end - range.begin) * t / nt;
  }
  // Each thread works out the assignment itself (the same for all): no wait.
  SortScratch& mine = sort_scratch[t];
  mine.sizes.resize(sort_small.size());
  for (std::size_t r = 0; r < sort_small.size(); ++r) {
    mine.sizes[r] = sort_small[r].end - sort_small[r].begin;
  }
  bh::assign_greedy(mine.sizes, nt, t, own_ranges[t], mine.by_size, mine.loads);
}

// The team's pass over `range` by its top remaining digit: into the other
// buffer, each sub-range then listed as large (split again), small (sorted
// by one thread) or done.
void BarnesHut::Workspace::split_range(const bh::MortonCoder& code, const bh::SortRange& range,
                                       std::size_t t, std::size_t nt) {
  const int width = std::min(bh::kRadixBits, range.bits);
  const int shift = range.bits - width;
  const std::size_t buckets = std::size_t{1} << width;
  const std::size_t mask = buckets - 1;
  const std::size_t length = range.end - range.begin;
  const std::size_t lo = range.begin + length * t / nt;
  const std::size_t hi = range.begin + length * (t + 1) / nt;
  const bh::Record* from = range.in_tmp ? records_tmp.data() : records.data();
  bh::Record* to = range.in_tmp ? records.data() : records_tmp.data();
  std::size_t* counts = radix_counts.data() + t * bh::kFirstBuckets;
  std::fill(counts, counts + buckets, std::size_t{0});
  const auto digit = [&](const bh::Record& r) { return (code(r.x, r.y) >> shift) & mask; };
  for (std::size_t i = lo; i < hi; ++i) ++counts[digit(from[i])];
#if defined(_OPENMP)
#pragma omp barrier
#endif
  std::size_t mine[bh::kRadixBuckets];
  std::size_t ends[bh::kRadixBuckets];
  const bool skip =
      bucket_offsets(range.begin, t, nt, buckets, mine, ends) == length;  // nothing moves
  if (t == 0) list_ranges(range, width, ends, skip);
  if (!skip) {
    for (std::size_t i = lo; i < hi; ++i) to[mine[digit(from[i])]++] = from[i];
  }
#if defined(_OPENMP)
#pragma omp barrier
#endif
}

// The sub-ranges of `range` after a pass by a digit of `width` bits (bucket
// b ends at ends[b]), as large (split again) or small (sorted, or left in
// place, by one thread, which then writes its bodies out): every key ends in
// one small range.
void BarnesHut::Workspace::list_ranges(const bh::SortRange& range, int width,
                                       const std::size_t* ends, bool skip) {
  const bool moved_to_tmp = skip ? range.in_tmp : !range.in_tmp;
  std::size_t offset = range.begin;
  for (std::size_t b = 0; b < std::size_t{1} << width; ++b) {
    const bh::SortRange sub{static_cast<std::uint32_t>(offset), static_cast<std::uint32_t>(ends[b]),
                            range.bits - width, moved_to_tmp};
    offset = ends[b];
    if (sub.end == sub.begin) continue;
    const bool large = sub.end - sub.begin > team_split_from && sub.bits > 0;
    (large ? sort_large : sort_small).push_back(sub);
  }
  if (range_parts.size() < sort_small.size()) range_parts.resize(sort_small.size());
}

// One thread orders `range` by its remaining bits down to the leaves
// (leaf_order) and writes its bodies out in that order. Each key's remaining
// bits and the record's place in the range (index order: the passes are
// stable) are packed in one integer, ordered in the thread's buffers; the
// records are then read in that order, from cache, and each key put
// together again from the range's shared bits and its packed ones. A range
// of at most leaf_size bodies (or of one key) is one leaf at most, or part
// of one: its bodies stay in index order. The keys of a range that builds
// its subtree with its sort stay in the thread's range_keys: of them, only
// the first and the last are read after (the top of the tree).
void BarnesHut::Workspace::sort_range(const bh::MortonCoder& code, const bh::SortRange& range,
                                      SortScratch& buffers) {
  const std::size_t length = range.end - range.begin;
  const bh::Record* from = (range.in_tmp ? records_tmp.data() : records.data()) + range.begin;
  std::uint64_t* key_to = keys.data() + range.begin;
  if (builds_with_sort(range)) {
    buffers.range_keys.resize(length);
    key_to = buffers.range_keys.data();
  }
  // The range's places in the outputs, taken once: a store through order
  // could change range.begin, for all the compiler knows.
  std::uint32_t* const order_to = order.data() + range.begin;
  double* const x_to = sx.data() + range.begin;
  double* const y_to = sy.data() + range.begin;
  double* const m_to = sm.data() + range.begin;
  const auto put = [=](std::size_t k, std::uint64_t key, const bh::Record& r) {
    key_to[k] = key;
    order_to[k] = r.index;
    x_to[k] = r.x;
    y_to[k] = r.y;
    m_to[k] = r.m;
  };
  const auto keep_ends = [&] {
    keys[range.begin] = key_to[0];
    keys[range.end - 1] = key_to[length - 1];
  };
  if (range.bits == 0 || length <= leaf_size) {  // one key, or one leaf at most: index order
    for (std::size_t k = 0; k < length; ++k) put(k, code(from[k].x, from[k].y), from[k]);
    keep_ends();
    return;
  }
  // Key bits + place bits <= 40 + 16: a range here has at most
  // kSortInCache bodies (or no key bits left).
  const int place_bits = 64 - leading_zeros(length - 1);  // length >= 2
  const std::uint64_t key_mask = (std::uint64_t{1} << range.bits) - 1;
  const std::uint64_t shared = code(from[0].x, from[0].y) & ~key_mask;
  std::vector<std::uint64_t>& packed = buffers.values[0];
  std::vector<std::uint64_t>& spare = buffers.values[1];
  packed.resize(length);
  spare.resize(length);
  bh::build_kernels().packed_keys(from, length, code, key_mask, place_bits, packed.data());
  leaf_order(packed.data(), spare.data(), length, range.bits, place_bits, leaf_size,
             buffers.leaf_levels.data());
  const std::uint64_t place_mask = (std::uint64_t{1} << place_bits) - 1;
  for (std::size_t k = 0; k < length; ++k) {
    const std::uint64_t p = spare[k];
    put(k, shared | (p >> place_bits), from[p & place_mask]);
  }
  keep_ends();
}

// The number of quadtree levels that the bodies [begin, end) share: their
// node's cell is the smallest one holding them all (chains of single
// children are skipped); kBits when they all share one Morton code.
int BarnesHut::Workspace::level_of(std::uint32_t begin, std::uint32_t end,
                                   const bh::SortedKeys& sorted) {
  return shared_levels(sorted[begin] ^ sorted[end - 1]);
}

// The same for a leaf, whose bodies are in index order, not by key
// (leaf_order): every key counts.
int BarnesHut::Workspace::leaf_level(std::uint32_t begin, std::uint32_t end,
                                     const bh::SortedKeys& sorted) {
  const std::uint64_t first = sorted[begin];
  std::uint64_t differ = 0;
  for (std::uint32_t r = begin + 1; r < end; ++r) differ |= sorted[r] ^ first;
  return shared_levels(differ);
}

// Where the quadrants of the bodies [begin, end) (common prefix `level`,
// end - begin >= 2) start: bounds[q] for digit q, bounds[4] = end. A node
// of the top of the tree (in_top) holds whole sort ranges, each inside one of
// its quadrants: a search over the ranges' first keys (range_firsts, in the
// cache), not over keys that are not. Below: three binary searches over the
// keys side by side, each step a conditional move, not a branch.
void BarnesHut::Workspace::quadrant_bounds(std::uint32_t begin, std::uint32_t end, int level,
                                           bool in_top, const bh::SortedKeys& sorted,
                                           std::uint32_t (&bounds)[5]) const {
  // The quadrant digit below the common prefix: bits 2 (kBits - 1 - level) + {0, 1}.
  const int shift = 2 * (kBits - 1 - level);
  const auto digit = [&](std::uint64_t key) { return (key >> shift) & 3u; };
  bounds[0] = begin;
  bounds[4] = end;
  if (in_top) {
    using First = std::pair<std::uint32_t, std::uint64_t>;
    const auto by_body = [](const First& r, std::uint32_t body) { return r.first < body; };
    auto from = std::lower_bound(range_firsts.begin(), range_firsts.end(), begin, by_body);
    const auto to = std::lower_bound(from, range_firsts.end(), end, by_body);
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

// Splits node `index` of t (bodies [begin, end), common prefix `level`) into
// its non-empty quadrants, appended to t as contiguous children; returns how
// many. bounds: the quadrants' body ranges; in_top: see quadrant_bounds.
std::uint32_t BarnesHut::Workspace::split(bh::Tree& t, std::uint32_t index, std::uint32_t begin,
                                          std::uint32_t end, int level, bool in_top,
                                          const bh::SortedKeys& sorted,
                                          std::uint32_t (&bounds)[5]) const {
  quadrant_bounds(begin, end, level, in_top, sorted, bounds);
  std::uint32_t children = 0;
  for (int q = 0; q < 4; ++q) children += bounds[q + 1] > bounds[q] ? 1 : 0;
  bh::Node& node = t.nodes[index];
  node.begin = begin;
  node.end = end;
  node.child = static_cast<std::uint32_t>(t.nodes.size());
  node.children = children;
  t.nodes.resize(t.nodes.size() + children);
  t.moments.resize(t.nodes.size());
  return children;
}

// The top of the tree (serially, plan), the subtrees built with their sort
// ranges swapped in, and the sizes of those left to build. Where the top
// ends depends on the sort's ranges, and so on the number of threads, but
// not the tree: each node is the smallest cell holding its bodies, split
// while it has more than leaf_size, wherever it was built; and there is
// never a group or a leaf above the subtrees.
void BarnesHut::Workspace::plan_tree() {
  with_sort.clear();
  range_firsts.clear();
  for (std::size_t r = 0; r < sort_small.size(); ++r) {
    const bh::SortRange& range = sort_small[r];
    range_firsts.emplace_back(range.begin, keys[range.begin]);
    if (builds_with_sort(range)) with_sort.emplace_back(range.begin, static_cast<std::uint32_t>(r));
  }
  std::sort(with_sort.begin(), with_sort.end());
  std::sort(range_firsts.begin(), range_firsts.end());
  const auto n = static_cast<std::uint32_t>(keys.size());
  tree.reset();
  pending.clear();
  top.clear();
  const std::size_t cutoff = std::max({std::size_t{n} / bh::kSubtrees, group_size, leaf_size});
  plan(0, 0, n, 0, cutoff);
  if (parts.size() < pending.size()) parts.resize(pending.size());
  item_sizes.resize(pending.size());
  for (std::size_t k = 0; k < pending.size(); ++k) {
    const bh::Pending& p = pending[k];
    if (p.range == bh::kNoRange) {
      item_sizes[k] = p.end - p.begin;
      continue;
    }
    item_sizes[k] = 0;  // built: its storage swapped in, its depth from here
    std::swap(parts[k], range_parts[p.range]);
    parts[k].depth += p.depth;
  }
}

// Thread t's subtrees, each in its own Tree (numbered from 0), and their
// bodies' float32 masses.
void BarnesHut::Workspace::build_own_parts(std::size_t t) {
  SortScratch& mine = sort_scratch[t];
  bh::assign_greedy(item_sizes, static_cast<std::size_t>(team), t, own_parts[t], mine.by_size,
                    mine.loads);
  std::uint64_t bodies = 0;
  for (const std::uint32_t k : own_parts[t]) {
    const bh::Pending& p = pending[k];
    if (p.range != bh::kNoRange) continue;  // built with its sort range
    // The splits' binary searches read the keys at scattered places, one
    // miss after another: fetch the part's keys first, all at once.
    for (std::uint32_t b = p.begin; b < p.end; b += 8) __builtin_prefetch(keys.data() + b);
    build_part(parts[k], p.begin, p.end, p.depth, all_keys(), mine, true);
    bodies += p.end - p.begin;
  }
  // With the subtrees this thread built with its sort ranges.
  work[bh::kRegionSubtrees * static_cast<std::size_t>(team) + t] += bodies;
}

// Where the parts' nodes go: part k's node c to its root's slot (c = 0) or
// to part_base[k] + c - 1; and its groups: from group_base[k] on (the groups
// in part order).
void BarnesHut::Workspace::place_parts() {
  part_base.resize(pending.size() + 1);
  group_base.resize(pending.size() + 1);
  part_base[0] = tree.nodes.size();
  group_base[0] = 0;  // no group above the parts
  for (std::size_t k = 0; k < pending.size(); ++k) {
    part_base[k + 1] = part_base[k] + parts[k].nodes.size() - 1;
    group_base[k + 1] = group_base[k] + parts[k].groups.size();
    tree.depth = std::max(tree.depth, parts[k].depth);
    tree.leaves += parts[k].leaves;
  }
  const std::size_t nodes = part_base.back();
  tree.nodes.resize(nodes);  // tree.moments: the top and the parts' roots only (finish_top)
  parent.resize(nodes);
  (single ? node32.resize(nodes * bh::kMoments) : node64.resize(nodes * bh::kMoments));
  tree.groups.resize(group_base.back());  // written by copy_own_parts
}

// The parts' nodes into the tree, with their parents, kernel moments and
// groups: thread t takes its slice of all the parts' nodes, one after the
// other (part k's start among them: part_base[k] - part_base[0] + k).
void BarnesHut::Workspace::copy_own_parts(std::size_t t) {
  const std::size_t parts_n = pending.size();
  const std::size_t total = part_base[parts_n] - part_base[0] + parts_n;
  const auto nt = static_cast<std::size_t>(team);
  const std::size_t lo = total * t / nt;
  const std::size_t hi = total * (t + 1) / nt;
  const auto start = [&](std::size_t k) { return part_base[k] - part_base[0] + k; };
  // The part holding item lo: the last k with start(k) <= lo.
  std::size_t lo_k = 0;
  std::size_t hi_k = parts_n;
  while (hi_k - lo_k > 1) {
    const std::size_t mid = (lo_k + hi_k) / 2;
    (start(mid) <= lo ? lo_k : hi_k) = mid;
  }
  for (std::size_t k = lo_k, item = lo; item < hi; ++k) {
    const bh::Tree& part = parts[k];
    const std::uint32_t root = pending[k].index;
    const auto base = static_cast<std::uint32_t>(part_base[k]);
    for (std::size_t c = item - start(k); c < part.nodes.size() && item < hi; ++c, ++item) {
      bh::Node node = part.nodes[c];
      const auto to = static_cast<std::uint32_t>(c == 0 ? root : base + c - 1);
      if (node.children > 0) {
        node.child = base + node.child - 1;
        for (std::uint32_t d = node.child; d < node.child + node.children; ++d) parent[d] = to;
      }
      tree.nodes[to] = node;
      if (c == 0) {  // with the part's groups, by the thread that has its root
        tree.moments[to] = part.moments[c];
        std::uint32_t* groups = tree.groups.data() + group_base[k];
        for (const std::uint32_t g : part.groups) *groups++ = g == 0 ? root : base + g - 1;
      }
      kernel_moments(to, part.moments[c]);
    }
  }
  work[bh::kRegionNodes * nt + t] = hi - lo;
}

// The nodes above the subtrees, bottom up (children first), with their
// kernel moments and their children's parent.
void BarnesHut::Workspace::finish_top() {
  parent[0] = ~std::uint32_t{0};
  for (auto it = top.rbegin(); it != top.rend(); ++it) {
    finish_node(tree, *it, all_keys());
    kernel_moments(*it, tree.moments[*it]);
    const bh::Node& node = tree.nodes[*it];
    for (std::uint32_t c = node.child; c < node.child + node.children; ++c) parent[c] = *it;
  }
}

// Splits the top of the tree, serially, down to the subtrees built with
// their sort ranges and to nodes of at most `cutoff` bodies (or of one
// Morton code) that hold none of those, which all go to `pending`.
void BarnesHut::Workspace::plan(std::uint32_t index, std::uint32_t begin, std::uint32_t end,
                                int tree_depth, std::size_t cutoff) {
  bool inside = false;
  const std::uint32_t range = range_with_sort(begin, end, inside);
  if (range != bh::kNoRange) {
    pending.push_back(bh::Pending{index, begin, end, tree_depth, range});
    return;
  }
  const int level = level_of(begin, end, all_keys());
  if ((end - begin <= cutoff && !inside) || level == kBits) {
    pending.push_back(bh::Pending{index, begin, end, tree_depth, bh::kNoRange});
    return;
  }
  top.push_back(index);
  std::uint32_t bounds[5];
  split(tree, index, begin, end, level, true, all_keys(), bounds);
  std::uint32_t c = tree.nodes[index].child;
  for (int q = 0; q < 4; ++q) {
    if (bounds[q + 1] > bounds[q]) plan(c++, bounds[q], bounds[q + 1], tree_depth + 1, cutoff);
  }
}

// The range of with_sort whose bodies are [begin, end), or kNoRange; inside:
// whether one lies within [begin, end) (ranges and nodes are cells' bodies:
// nested or apart).
std::uint32_t BarnesHut::Workspace::range_with_sort(std::uint32_t begin, std::uint32_t end,
                                                    bool& inside) const {
  const auto it = std::lower_bound(with_sort.begin(), with_sort.end(),
                                   std::pair<std::uint32_t, std::uint32_t>{begin, 0});
  inside = it != with_sort.end() && it->first < end;
  if (!inside || it->first != begin) return bh::kNoRange;
  const bh::SortRange& range = sort_small[it->second];
  return range.end == end ? it->second : bh::kNoRange;
}

// Builds node `index` of t over the bodies [begin, end) (end > begin) and its
// subtree, their moments left to finish_part: split unless it has at most
// leaf_size bodies or they all share one Morton code. The first node on each
// path with at most group_size bodies (or a leaf) is a group.
void BarnesHut::Workspace::build_node(bh::Tree& t, std::uint32_t index, std::uint32_t begin,
                                      std::uint32_t end, int tree_depth, bool in_group,
                                      const bh::SortedKeys& sorted) const {
  const int level = level_of(begin, end, sorted);
  t.depth = std::max(t.depth, tree_depth);
  const std::size_t count = end - begin;
  const bool leaf = count <= leaf_size || level == kBits;
  if (!in_group && (count <= group_size || leaf)) {
    t.groups.push_back(index);
    in_group = true;
  }
  if (leaf) {
    ++t.leaves;
    bh::Node& node = t.nodes[index];
    node.begin = begin;
    node.end = end;
    node.child = 0;
    node.children = 0;
  } else {
    std::uint32_t bounds[5];
    split(t, index, begin, end, level, false, sorted, bounds);
    std::uint32_t c = t.nodes[index].child;
    for (int q = 0; q < 4; ++q) {
      if (bounds[q + 1] > bounds[q])
        build_node(t, c++, bounds[q], bounds[q + 1], tree_depth + 1, in_group, sorted);
    }
  }
}

// Mass, centre of mass and moments of inner node `index` of t from its
// children's (which must be finished), and its opening radius.
void BarnesHut::Workspace::finish_node(bh::Tree& t, std::uint32_t index,
                                       const bh::SortedKeys& sorted) const {
  bh::Node& node = t.nodes[index];
  bh::Moments mo{};
  merge_moments(t, node, mo);
  t.moments[index] = mo;
  set_opening_radius(node, sorted);
}

// The moments and opening radii of a part that build_node made: its leaves'
// from their bodies (the build kernels), then its inner nodes' from their
// children, last node first (a node's children come after it).
void BarnesHut::Workspace::finish_part(bh::Tree& t, const bh::SortedKeys& sorted,
                                       SortScratch& buffers) const {
  buffers.leaf_node.clear();
  buffers.leaf_begin.clear();
  buffers.leaf_end.clear();
  for (std::size_t i = 0; i < t.nodes.size(); ++i) {
    if (t.nodes[i].children != 0) continue;
    buffers.leaf_node.push_back(static_cast<std::uint32_t>(i));
    buffers.leaf_begin.push_back(t.nodes[i].begin);
    buffers.leaf_end.push_back(t.nodes[i].end);
  }
  const std::size_t leaves = buffers.leaf_node.size();
  buffers.leaf_sums.resize(leaves * bh::kLeafSums);
  bh::build_kernels().leaf_moments(sx.data(), sy.data(), sm.data(), buffers.leaf_begin.data(),
                                   buffers.leaf_end.data(), leaves, buffers.leaf_sums.data());
  for (std::size_t k = 0; k < leaves; ++k) {
    const double* sums = buffers.leaf_sums.data() + bh::kLeafSums * k;
    bh::Node& node = t.nodes[buffers.leaf_node[k]];
    bh::Moments& mo = t.moments[buffers.leaf_node[k]];
    mo.mass = sums[bh::kLeafMass];
    mo.qxx = sums[bh::kLeafQxx];
    mo.qxy = sums[bh::kLeafQxy];
    mo.qyy = sums[bh::kLeafQyy];
    mo.oxxx = sums[bh::kLeafOxxx];
    mo.oxxy = sums[bh::kLeafOxxy];
    mo.oxyy = sums[bh::kLeafOxyy];
    mo.oyyy = sums[bh::kLeafOyyy];
    mo.hxxxx = sums[bh::kLeafHxxxx];
    mo.hxxxy = sums[bh::kLeafHxxxy];
    mo.hxxyy = sums[bh::kLeafHxxyy];
    mo.hxyyy = sums[bh::kLeafHxyyy];
    mo.hyyyy = sums[bh::kLeafHyyyy];
    node.mx = sums[bh::kLeafMx];
    node.my = sums[bh::kLeafMy];
    set_opening_radius(node, sorted);
  }
  for (std::size_t i = t.nodes.size(); i-- > 0;) {
    if (t.nodes[i].children != 0) finish_node(t, static_cast<std::uint32_t>(i), sorted);
  }
}

// An inner node: its centre of mass and moments from its children's.
void BarnesHut::Workspace::merge_moments(const bh::Tree& t, bh::Node& node, bh::Moments& mo) {
  double mass = 0.0;
  double mx = 0.0;
  double my = 0.0;
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
    const bh::Moments& m = t.moments[c];
    const double dx = t.nodes[c].mx - mx;
    const double dy = t.nodes[c].my - my;
    mo.qxx += m.qxx + m.mass * dx * dx;
    mo.qxy += m.qxy + m.mass * dx * dy;
    mo.qyy += m.qyy + m.mass * dy * dy;
    mo.oxxx += m.oxxx + 3.0 * dx * m.qxx + m.mass * dx * dx * dx;
    mo.oxxy += m.oxxy + 2.0 * dx * m.qxy + dy * m.qxx + m.mass * dx * dx * dy;
    mo.oxyy += m.oxyy + 2.0 * dy * m.qxy + dx * m.qyy + m.mass * dx * dy * dy;
    mo.oyyy += m.oyyy + 3.0 * dy * m.qyy + m.mass * dy * dy * dy;
    const double xx = dx * dx;
    const double xy = dx * dy;
    const double yy = dy * dy;
    mo.hxxxx += m.hxxxx + 4.0 * dx * m.oxxx + 6.0 * xx * m.qxx + m.mass * xx * xx;
    mo.hxxxy += m.hxxxy + 3.0 * dx * m.oxxy + dy * m.oxxx + 3.0 * (xx * m.qxy + xy * m.qxx) +
                m.mass * xx * xy;
    mo.hxxyy += m.hxxyy + 2.0 * (dx * m.oxyy + dy * m.oxxy) + xx * m.qyy + 4.0 * xy * m.qxy +
                yy * m.qxx + m.mass * xx * yy;
    mo.hxyyy += m.hxyyy + 3.0 * dy * m.oxyy + dx * m.oyyy + 3.0 * (yy * m.qxy + xy * m.qyy) +
                m.mass * xy * yy;
    mo.hyyyy += m.hyyyy + 4.0 * dy * m.oyyy + 6.0 * yy * m.qyy + m.mass * yy * yy;
  }
  mo.mass = mass;
  node.mx = mx;
  node.my = my;
}

// Barnes' modified criterion: accepted beyond size / theta + delta from the
// centre of mass, delta its distance to the cell's centre. The cell: level
// `level` of the root square, found from the common prefix.
void BarnesHut::Workspace::set_opening_radius(bh::Node& node, const bh::SortedKeys& sorted) const {
  const int level = node.children == 0 ? leaf_level(node.begin, node.end, sorted)
                                       : level_of(node.begin, node.end, sorted);
  const std::uint64_t key = sorted[node.begin];
  const double size = cell_size[static_cast<std::size_t>(level)];
  const double cx = x0 + (static_cast<double>(compact(key) >> (kBits - level)) + 0.5) * size;
  const double cy = y0 + (static_cast<double>(compact(key >> 1) >> (kBits - level)) + 0.5) * size;
  const double delta = std::sqrt((node.mx - cx) * (node.mx - cx) + (node.my - cy) * (node.my - cy));
  const double open = size * inv_theta + delta;
  node.open2 = open * open;
}

namespace bh {

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

}  // namespace bh

}  // namespace calder::nbody
