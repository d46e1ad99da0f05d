// SPDX-License-Identifier: MIT
// calder::bulk: the whole-world batch stepper (see calder/bulk.hpp):
// compiles the fields, cuts the bodies into tiles and hands the tiles to
// threads; each tile runs the whole batch in one kernel call.
#include "calder/bulk.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "../claims.hpp"
#include "../step_batch.hpp"
#include "plan.hpp"

#if defined(_OPENMP)
#include <omp.h>
#endif

namespace calder::bulk {

namespace {

// Fewer bodies than this run on one thread: a batch of a few tiles takes
// microseconds, comparable to waking a thread.
constexpr std::size_t kMinBodiesPerThread = 2 * kTile;

// The first of bodies [first, first + count) whose position or velocity is
// not finite (an infinity or NaN: every exponent bit set), or first + count.
// The common case, all finite, is one branch-free pass that vectorises; the
// scan for the body runs only when there is one.
std::size_t first_non_finite(const BodyColumnsOf<std::span<double>, std::span<const double>>& b,
                             std::size_t first, std::size_t count) {
  const double* x = b.x.data() + first;
  const double* y = b.y.data() + first;
  const double* vx = b.vx.data() + first;
  const double* vy = b.vy.data() + first;
  // 1 when the 11 exponent bits are all set (their sum with 1 carries into bit 11), else 0.
  const auto non_finite = [](double v) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &v, sizeof bits);  // std::bit_cast is not in Emscripten's libc++ 13
    return (((bits >> 52) & 0x7ff) + 1) >> 11;
  };
  const auto bad = [&](std::size_t i) {
    return non_finite(x[i]) | non_finite(y[i]) | non_finite(vx[i]) | non_finite(vy[i]);
  };
  std::uint64_t any = 0;
  for (std::size_t i = 0; i < count; ++i) any |= bad(i);
  if (any == 0) return first + count;
  std::size_t i = 0;
  while (bad(i) == 0) ++i;
  return first + i;
}

// The calling thread's record of its last batch's tiles per thread.
std::vector<std::size_t>& caller_tiles() {
  thread_local std::vector<std::size_t> tiles;
  return tiles;
}

// Runs run_tile(k) for tiles [0, tiles) on `threads` threads. Tiles are
// independent: which thread runs one changes no bit of it. Thread t of nt
// has the share of tiles [tiles t / nt, tiles (t + 1) / nt), cut in chunks;
// a thread done with its share takes the last unstarted chunks of the
// others' (src/claims.hpp). caller_tiles(): the tiles of each share.
template <class RunTile>
void run_in_shares(long long tiles, int threads, const RunTile& run_tile) {
  const auto nt = static_cast<long long>(threads);
  const auto share_first = [&](long long k) { return tiles * k / nt; };
  std::vector<std::size_t>& per_share = caller_tiles();
  per_share.resize(static_cast<std::size_t>(threads));
  for (long long k = 0; k < nt; ++k) {
    per_share[static_cast<std::size_t>(k)] =
        static_cast<std::size_t>(share_first(k + 1) - share_first(k));
  }
  thread_local calder::detail::Claims caller_claims;
  calder::detail::Claims& claims = caller_claims;
  claims.reset(static_cast<std::size_t>(threads), calder::detail::kChunksPerShare);
#if defined(_OPENMP)
#pragma omp parallel num_threads(threads) if (threads > 1)
#endif
  {
    const std::size_t t = calder::detail::team_thread();
    std::size_t share = 0;
    std::uint32_t chunk = 0;
    while (claims.next(t, share, chunk)) {
      const auto k = static_cast<long long>(share);
      const auto [begin, end] = calder::detail::chunk_of(
          static_cast<std::size_t>(share_first(k)),
          static_cast<std::size_t>(share_first(k + 1) - share_first(k)), chunk);
      for (std::size_t tile = begin; tile < end; ++tile) run_tile(static_cast<long long>(tile));
    }
  }
}

}  // namespace

bool step_batch(const StepBatch& batch, std::string* why_not) {
  // One plan per calling thread keeps its storage from batch to batch.
  // (A reference: inside the parallel loop, the name of a thread_local would
  // mean each worker thread's own, empty, plan.)
  thread_local detail::Plan caller_plan;
  detail::Plan& plan = caller_plan;
  if (!detail::compile(batch, plan, why_not)) return false;
  const detail::KernelTable& table = detail::kernels();
  detail::AdvanceTile advance = table.book64;
  if (batch.arithmetic == Arithmetic::float64) advance = table.fast64;
  if (batch.arithmetic == Arithmetic::float32) advance = table.fast32;

  const std::size_t n = batch.bodies.x.size();
  const auto tiles = static_cast<long long>((n + kTile - 1) / kTile);
  int threads = batch.threads > 0 ? batch.threads : max_threads();
  threads = static_cast<int>(
      std::min<std::size_t>(static_cast<std::size_t>(threads), n / kMinBodiesPerThread + 1));
  // Each tile's first body left non-finite (n: none), reduced in tile order.
  thread_local std::vector<std::size_t> caller_bad;
  std::vector<std::size_t>& bad = caller_bad;
  bad.assign(static_cast<std::size_t>(tiles), n);
  const auto run_tile = [&](long long t) {
    const std::size_t first = static_cast<std::size_t>(t) * kTile;
    const std::size_t count = std::min(kTile, n - first);
    if (batch.saved != nullptr) {
      std::size_t k = 0;
      for_each_state(
          [&](const char*, std::span<double> column) {
            std::copy_n(column.data() + first, count, batch.saved + (k++) * n + first);
          },
          batch.bodies);
    }
    detail::Tile tile{{}, count};
    for_each_column([first](const char*, auto*& to, auto column) { to = column.data() + first; },
                    tile.bodies, batch.bodies);
    advance(plan, tile);
    const std::size_t i = first_non_finite(batch.bodies, first, count);
    if (i < first + count) bad[static_cast<std::size_t>(t)] = i;
  };
  run_in_shares(tiles, threads, run_tile);
  if (batch.first_non_finite != nullptr) {
    *batch.first_non_finite = n;
    for (const std::size_t i : bad) {
      if (i < n) {
        *batch.first_non_finite = i;
        break;
      }
    }
  }
  return true;
}

std::string unsupported(const World& world) {
  if (world.integrator() != Integrator::semi_implicit_euler) {
    return "the kernels integrate with semi_implicit_euler only";
  }
  if (world.update_order() != UpdateOrder::simultaneous) {
    return "the kernels need the simultaneous update order";
  }
  return detail::unsupported_field(world.fields());
}

const char* kernel_name() { return detail::kernels().name; }

std::vector<std::size_t> last_batch_tiles() { return caller_tiles(); }

int max_threads() {
#if defined(_OPENMP)
  return omp_get_max_threads();
#else
  return 1;
#endif
}

}  // namespace calder::bulk
