// SPDX-License-Identifier: MIT
// Barnes-Hut, the Morton sort: bounding square; 48-bit Morton codes (24 bits
// per axis); their radix sort (8-bit digits, the first 10 bits wide for many
// bodies: the threads split the bodies, each carried as a 32-byte record, by
// their top digits until the ranges fit in cache, then order ranges on
// their own down to the leaves and write them out: leaves in Morton order, a
// leaf's bodies in index order; that order depends on the bodies alone, so
// it is the same for any thread count). A range of more than group_size
// bodies is a subtree, which its thread builds at once (barnes_hut_build.cpp).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "barnes_hut_builder.hpp"

#if defined(_OPENMP)
#include <omp.h>
#endif
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace calder::nbody::bh {

namespace {

// Whether a record starts a cache line (records are 32-byte aligned).
inline bool starts_line(const Record* r) {
  return (reinterpret_cast<std::uintptr_t>(r) & 63u) == 0;
}

// kStage records to `to` (64-byte aligned) with non-temporal stores where
// the processor has them; end_streams orders them before what follows.
inline void stream_stage(const Record* from, Record* to) {
#if defined(__SSE2__)
  const auto* f = reinterpret_cast<const __m128i*>(from);
  auto* d = reinterpret_cast<__m128i*>(to);
  for (std::size_t k = 0; k < kStage * sizeof(Record) / 16; ++k) {
    _mm_stream_si128(d + k, _mm_load_si128(f + k));
  }
#else
  std::copy(from, from + kStage, to);
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
                std::size_t leaf_size, LeafLevel* levels) {
  int b = 2;
  while (b + 2 <= bits && b + 2 <= kMaxLeafBits && (std::size_t{4} << (b + 2)) <= length) {
    b += 2;
  }
  const int top = b / 2;  // the pyramid's levels below its root: 0 to top
  const int shift = place_bits + bits - b;
  const std::uint64_t mask = (std::uint64_t{1} << b) - 1;
  const auto level_at = [](int h) { return ((std::size_t{1} << (2 * h)) - 1) / 3; };
  LeafLevel& s = levels[0];
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

// The buffers' sizes for n bodies and the team (grown, never shrunk in
// capacity: a solver called every step allocates once).
void TreeBuilder::size_buffers(std::size_t n) {
  const auto nt = static_cast<std::size_t>(team_);
  keys_.resize(n);
  out_->order.resize(n);
  sort_.records.resize(n);
  sort_.records_tmp.resize(n);
  // The leaf kernel reads a few elements past a leaf: readable and set.
  for (auto* column : {&out_->sx, &out_->sy, &out_->sm}) {
    column->resize(n + kLeafPadding);
    std::fill(column->begin() + static_cast<std::ptrdiff_t>(n), column->end(), 0.0);
  }
  if (out_->single) out_->sm32.resize(n);
  sort_.first_bits = n >= kWideFirstFrom ? kWideFirstBits : kRadixBits;
  sort_.radix_counts.resize(nt * kFirstBuckets);
  if (scratch_.size() < nt) scratch_.resize(nt);
  for (std::size_t t = 0; t < nt; ++t) scratch_[t].stage.resize(kFirstBuckets * kStage);
  sort_.partial.assign(5 * nt, 0.0);
  sort_.team_split_from =
      std::min(kSortInCache, std::max(n / (nt * kRangesPerThread), kMinTeamSplit));
  sort_.large.clear();
  sort_.small.clear();
}

// Thread t's share of the bounding box (the heaviest mass: first_pass,
// which reads the masses anyway).
void TreeBuilder::bound(std::span<const double> x, std::span<const double> y, std::size_t t,
                        std::size_t nt) {
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
  double* p = sort_.partial.data() + 5 * t;
  p[0] = xmin;
  p[1] = xmax;
  p[2] = ymin;
  p[3] = ymax;
}

// The root square from the threads' boxes: the lower corner and the larger
// side (min and max are exact: the same for any split). Every thread works
// it out for itself.
Square TreeBuilder::combine_bounds(std::size_t nt) const {
  double xmin = sort_.partial[0];
  double xmax = sort_.partial[1];
  double ymin = sort_.partial[2];
  double ymax = sort_.partial[3];
  for (std::size_t t = 1; t < nt; ++t) {
    const double* p = sort_.partial.data() + 5 * t;
    xmin = std::min(xmin, p[0]);
    xmax = std::max(xmax, p[1]);
    ymin = std::min(ymin, p[2]);
    ymax = std::max(ymax, p[3]);
  }
  double larger = std::max(xmax - xmin, ymax - ymin);
  if (!(larger > 0.0)) larger = 1.0;  // one point (or one body)
  return Square{xmin, ymin, larger};
}

// The heaviest mass, from the threads' shares (first_pass).
double TreeBuilder::heaviest_mass(std::size_t nt) const {
  double most = sort_.partial[4];
  for (std::size_t t = 1; t < nt; ++t) most = std::max(most, sort_.partial[5 * t + 4]);
  return most;
}

// The first radix pass, by the keys' top digit, after the Morton codes:
// thread t codes and counts its slice (keys, in the caller's order until the
// sort writes them over), then (the team's offsets known) writes its bodies
// as records to their buckets in `records`. Stable: equal digits stay in
// index order.
void TreeBuilder::first_pass(std::span<const double> x, std::span<const double> y,
                             std::span<const double> mass, const MortonCoder& code, std::size_t t,
                             std::size_t nt) {
  const int shift = 2 * kBits - sort_.first_bits;
  const std::size_t buckets = std::size_t{1} << sort_.first_bits;
  const std::size_t n = x.size();
  const std::size_t lo = n * t / nt;
  const std::size_t hi = n * (t + 1) / nt;
  std::size_t* counts = sort_.radix_counts.data() + t * kFirstBuckets;
  std::fill(counts, counts + buckets, std::size_t{0});
  // The keys in the caller's order, until sort_range writes them over: coded
  // once, read by the count and by the writes.
  std::uint64_t* key = keys_.data();
  build_kernels().morton_keys(x.data() + lo, y.data() + lo, hi - lo, code, key + lo);
  for (std::size_t i = lo; i < hi; ++i) ++counts[key[i] >> shift];
#if defined(_OPENMP)
#pragma omp barrier
#endif
  std::size_t mine[kFirstBuckets];
  std::size_t ends[kFirstBuckets];
  bucket_offsets(0, t, nt, buckets, mine, ends);
  if (t == 0) {  // the whole range, as if it came from records_tmp: now in records
    list_ranges(SortRange{0, static_cast<std::uint32_t>(n), 2 * kBits, true}, sort_.first_bits,
                ends, false);
  }
  // Each bucket's records gather in the thread's stage (in its L2) and go
  // out kStage at a time: whole cache lines, one page at a time, instead of
  // one store in 256 (or more) far places a body.
  Record* out = sort_.records.data();
  Record* stage = scratch_[t].stage.data();
  std::uint8_t* fill = scratch_[t].fill;
  // A full stage starts a cache line and goes out past the caches (no read
  // of lines about to be written whole); a bucket that starts a line's
  // second half writes its first record on its own.
  std::uint8_t* want = scratch_[t].want;
  for (std::size_t b = 0; b < buckets; ++b) {
    fill[b] = 0;
    want[b] = starts_line(out + mine[b]) ? kStage : 1;
  }
  double heaviest = 0.0;
  for (std::size_t i = lo; i < hi; ++i) {
    const auto b = static_cast<std::size_t>(key[i] >> shift);
    Record* slot = stage + b * kStage;
    heaviest = std::max(heaviest, mass[i]);
    slot[fill[b]] = Record{x[i], y[i], mass[i], static_cast<std::uint32_t>(i)};
    if (++fill[b] == want[b]) {
      if (want[b] == kStage) {
        stream_stage(slot, out + mine[b]);
      } else {
        out[mine[b]] = slot[0];
      }
      mine[b] += want[b];
      fill[b] = 0;
      want[b] = kStage;
    }
  }
  for (std::size_t b = 0; b < buckets; ++b) {
    const Record* slot = stage + b * kStage;
    for (std::size_t k = 0; k < fill[b]; ++k) out[mine[b] + k] = slot[k];
  }
  end_streams();
  sort_.partial[5 * t + 4] = heaviest;
  work_[kRegionBodies * nt + t] += hi - lo;
#if defined(_OPENMP)
#pragma omp barrier
#endif
}

// Thread t's offsets into each bucket of a pass over a range starting at
// `begin` (exclusive prefix sums of the team's counts, bucket-major then
// thread) and each bucket's end; returns the largest bucket's size.
std::size_t TreeBuilder::bucket_offsets(std::size_t begin, std::size_t t, std::size_t nt,
                                        std::size_t buckets, std::size_t* mine,
                                        std::size_t* ends) const {
  std::size_t offset = begin;
  std::size_t largest = 0;
  for (std::size_t b = 0; b < buckets; ++b) {
    const std::size_t first = offset;
    for (std::size_t u = 0; u < nt; ++u) {
      if (u == t) mine[b] = offset;
      offset += sort_.radix_counts[u * kFirstBuckets + b];
    }
    ends[b] = offset;
    largest = std::max(largest, offset - first);
  }
  return largest;
}

// Thread t's ranges: each sorted, and its bodies written out in Morton order
// (keys, order, sx, sy, sm).
void TreeBuilder::sort_own_ranges(const MortonCoder& code, std::size_t t) {
  std::uint64_t done = 0;
  std::uint64_t built = 0;
  for (const std::uint32_t r : scratch_[t].own_ranges) {
    const SortRange& range = sort_.small[r];
    BuildScratch& mine = scratch_[t];
    sort_range(code, range, mine);
    done += range.end - range.begin;
    if (builds_with_sort(range)) {
      build_part(range_parts_[r], range.begin, range.end, 0,
                 SortedKeys{mine.range_keys.data(), range.begin}, mine, false);
      built += range.end - range.begin;
    }
  }
  const auto nt = static_cast<std::size_t>(team_);
  work_[kRegionRanges * nt + t] = done;
  work_[kRegionSubtrees * nt + t] = built;
}

// Whether the thread that sorts `range` builds its subtree straight after,
// from the keys and bodies it has just written: the range is a quadtree
// cell's bodies (its digits are whole levels), so with more than
// group_size of them they are one node's, every node above it split and
// none of them a group, whatever else the tree holds.
bool TreeBuilder::builds_with_sort(const SortRange& range) const {
  return range.end - range.begin > std::max(settings_.group_size, settings_.leaf_size);
}

// Sorts the bodies by key down to the leaves (leaf_order), called by every
// thread t of a team of nt after first_pass. A most significant digit first
// radix sort: the team splits a range by its next digit (a stable counting
// pass, thread slices in order) while it is larger than team_split_from,
// then the ranges go to threads (assign_greedy), each ordered on its own by
// its remaining bits (sort_own_ranges, sort_range). The order depends on the
// bodies alone, not on the number of threads or on how the work was split.
void TreeBuilder::sort_keys(const MortonCoder& code, std::size_t t, std::size_t nt) {
  for (std::size_t r = 0; r < sort_.large.size(); ++r) {
    const SortRange range = sort_.large[r];  // a copy: the single below may grow the list
    split_range(code, range, t, nt);
    work_[kRegionSplit * nt + t] +=
        (range.end - range.begin) * (t + 1) / nt - (range.end - range.begin) * t / nt;
  }
  // Each thread works out the assignment itself (the same for all): no wait.
  BuildScratch& mine = scratch_[t];
  mine.sizes.resize(sort_.small.size());
  for (std::size_t r = 0; r < sort_.small.size(); ++r) {
    mine.sizes[r] = sort_.small[r].end - sort_.small[r].begin;
  }
  assign_greedy(mine.sizes, nt, t, scratch_[t].own_ranges, mine.by_size, mine.loads);
}

// The team's pass over `range` by its top remaining digit: into the other
// buffer, each sub-range then listed as large (split again), small (sorted
// by one thread) or done.
void TreeBuilder::split_range(const MortonCoder& code, const SortRange& range, std::size_t t,
                              std::size_t nt) {
  const int width = std::min(kRadixBits, range.bits);
  const int shift = range.bits - width;
  const std::size_t buckets = std::size_t{1} << width;
  const std::size_t mask = buckets - 1;
  const std::size_t length = range.end - range.begin;
  const std::size_t lo = range.begin + length * t / nt;
  const std::size_t hi = range.begin + length * (t + 1) / nt;
  const Record* from = range.in_tmp ? sort_.records_tmp.data() : sort_.records.data();
  Record* to = range.in_tmp ? sort_.records.data() : sort_.records_tmp.data();
  std::size_t* counts = sort_.radix_counts.data() + t * kFirstBuckets;
  std::fill(counts, counts + buckets, std::size_t{0});
  const auto digit = [&](const Record& r) { return (code(r.x, r.y) >> shift) & mask; };
  for (std::size_t i = lo; i < hi; ++i) ++counts[digit(from[i])];
#if defined(_OPENMP)
#pragma omp barrier
#endif
  std::size_t mine[kRadixBuckets];
  std::size_t ends[kRadixBuckets];
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
void TreeBuilder::list_ranges(const SortRange& range, int width, const std::size_t* ends,
                              bool skip) {
  const bool moved_to_tmp = skip ? range.in_tmp : !range.in_tmp;
  std::size_t offset = range.begin;
  for (std::size_t b = 0; b < std::size_t{1} << width; ++b) {
    const SortRange sub{static_cast<std::uint32_t>(offset), static_cast<std::uint32_t>(ends[b]),
                        range.bits - width, moved_to_tmp};
    offset = ends[b];
    if (sub.end == sub.begin) continue;
    const bool large = sub.end - sub.begin > sort_.team_split_from && sub.bits > 0;
    (large ? sort_.large : sort_.small).push_back(sub);
  }
  if (range_parts_.size() < sort_.small.size()) range_parts_.resize(sort_.small.size());
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
void TreeBuilder::sort_range(const MortonCoder& code, const SortRange& range,
                             BuildScratch& buffers) {
  const std::size_t length = range.end - range.begin;
  const Record* from =
      (range.in_tmp ? sort_.records_tmp.data() : sort_.records.data()) + range.begin;
  std::uint64_t* key_to = keys_.data() + range.begin;
  if (builds_with_sort(range)) {
    buffers.range_keys.resize(length);
    key_to = buffers.range_keys.data();
  }
  // The range's places in the outputs, taken once: a store through order
  // could change range.begin, for all the compiler knows.
  std::uint32_t* const order_to = out_->order.data() + range.begin;
  double* const x_to = out_->sx.data() + range.begin;
  double* const y_to = out_->sy.data() + range.begin;
  double* const m_to = out_->sm.data() + range.begin;
  const auto put = [=](std::size_t k, std::uint64_t key, const Record& r) {
    key_to[k] = key;
    order_to[k] = r.index;
    x_to[k] = r.x;
    y_to[k] = r.y;
    m_to[k] = r.m;
  };
  const auto keep_ends = [&] {
    keys_[range.begin] = key_to[0];
    keys_[range.end - 1] = key_to[length - 1];
  };
  if (range.bits == 0 ||
      length <= settings_.leaf_size) {  // one key, or one leaf at most: index order
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
  build_kernels().packed_keys(from, length, code, key_mask, place_bits, packed.data());
  leaf_order(packed.data(), spare.data(), length, range.bits, place_bits, settings_.leaf_size,
             buffers.leaf_levels.data());
  const std::uint64_t place_mask = (std::uint64_t{1} << place_bits) - 1;
  for (std::size_t k = 0; k < length; ++k) {
    const std::uint64_t p = spare[k];
    put(k, shared | (p >> place_bits), from[p & place_mask]);
  }
  keep_ends();
}

}  // namespace calder::nbody::bh
