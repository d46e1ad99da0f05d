// SPDX-License-Identifier: MIT
// calder::nbody: Barnes-Hut on a quadtree of Morton-sorted bodies (see
// calder/nbody.hpp for the algorithm and its guarantees). This file checks
// the options and runs the steps, each in its own file (barnes_hut_tree.hpp):
// build, multipole terms, walk; then the sums go back to the caller's order.
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <utility>

#include "barnes_hut_tree.hpp"
#include "calder/error.hpp"
#include "common.hpp"
#include "kernels.hpp"

#if defined(_OPENMP)
#include <omp.h>
#endif

namespace calder::nbody {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

void check_options(const char* where, std::size_t n, const BarnesHutOptions& options) {
  if (!(options.theta >= 0.0 && options.theta <= 1.0)) {
    throw Error(std::string(where) + ": options.theta must be in [0, 1] (got " +
                calder::detail::format_number(options.theta) + ")");
  }
  if (options.leaf_size < 1 || options.group_size < 1) {
    throw Error(
        std::string(where) + ": options.leaf_size and options.group_size must be >= 1 (got " +
        std::to_string(options.leaf_size) + " and " + std::to_string(options.group_size) + ")");
  }
  if (options.target_block < -1) {
    throw Error(std::string(where) + ": options.target_block must be >= -1 (got " +
                std::to_string(options.target_block) + ")");
  }
  if (n >= std::size_t{std::numeric_limits<std::uint32_t>::max()}) {
    throw Error(std::string(where) + ": too many bodies (at most 2^32 - 2)");
  }
}

}  // namespace

BarnesHut::BarnesHut() : workspace_(std::make_unique<Workspace>()) {}
BarnesHut::~BarnesHut() = default;
BarnesHut::BarnesHut(BarnesHut&&) noexcept = default;
BarnesHut& BarnesHut::operator=(BarnesHut&&) noexcept = default;

const BarnesHutStats& BarnesHut::stats() const {
  static const BarnesHutStats empty;
  return workspace_ ? workspace_->stats : empty;
}

// Thread t's part of (ax, ay) += factor * the sums, from Morton order back
// to the caller's (a permutation: no two ranks write one body). The writes
// land at random: the team splits the 2n writes (ax's ranks, then ay's) in
// equal slices, so that each thread writes one component over a run of
// ranks (two at most) and two threads rarely write one cache line.
void BarnesHut::Workspace::scatter_share(std::size_t t, std::size_t nt, double factor,
                                         std::span<double> ax, std::span<double> ay) {
  const std::size_t n = order.size();
  const std::size_t lo = 2 * n * t / nt;
  const std::size_t hi = 2 * n * (t + 1) / nt;
  for (std::size_t u = lo; u < std::min(hi, n); ++u) ax[order[u]] += factor * sum_x[u];
  for (std::size_t u = std::max(lo, n); u < hi; ++u) ay[order[u - n]] += factor * sum_y[u - n];
  work[bh::kRegionScatter * nt + t] = hi - lo;
}

void BarnesHut::accelerations(std::span<const double> x, std::span<const double> y,
                              std::span<const double> mass, std::span<double> ax,
                              std::span<double> ay, const BarnesHutOptions& options) {
  const char* where = "nbody::BarnesHut::accelerations";
  detail::validate(where, x, y, mass, ax, ay, options);
  check_options(where, x.size(), options);
  if (!workspace_) workspace_ = std::make_unique<Workspace>();
  Workspace& w = *workspace_;
  const std::size_t n = x.size();
  // Fresh stats whose lists keep their storage: a call like the last one
  // allocates nothing.
  BarnesHutStats fresh;
  fresh.build_phases = std::move(w.stats.build_phases);
  fresh.build_phases.clear();
  fresh.work = std::move(w.stats.work);
  w.stats = std::move(fresh);
  w.stats.bodies = n;
  if (n < 2) {
    w.stats.work.clear();
    return;
  }
  const int threads = detail::thread_count(options);

  const Clock::time_point t0 = Clock::now();
  w.leaf_size = static_cast<std::size_t>(options.leaf_size);
  w.group_size = static_cast<std::size_t>(options.group_size);
  w.target_block = static_cast<std::size_t>(options.target_block < 0 ? kernel_target_block()
                                                                     : options.target_block);
  w.inv_theta = options.theta > 0.0 ? 1.0 / options.theta : std::numeric_limits<double>::infinity();
  w.single = options.precision == Precision::float32;
  w.build(x, y, mass, threads, options.G);
  w.stats.build_seconds = seconds_since(t0);

  const Clock::time_point t1 = Clock::now();
  detail::LawParams p = detail::law_params(options, w.frame);
  p.float_range = detail::float_range_of(w.side, p.eps2);
  w.walk(p, w.frame.scale, threads, w.single ? w.frame.factor : options.G, ax, ay);
  w.stats.walk_seconds = seconds_since(t1);

  for (int k = 0; k < bh::kBuildPhases; ++k) {
    w.stats.build_phases.push_back(BarnesHutStats::Phase{bh::kBuildPhaseNames[k].name,
                                                         w.phase_end[k + 1] - w.phase_end[k],
                                                         bh::kBuildPhaseNames[k].serial});
  }
  w.stats.nodes = w.tree.nodes.size();
  w.stats.groups = w.tree.groups.size();
  w.stats.depth = w.tree.depth;
  w.stats.leaves = w.tree.leaves;
  for (const auto& s : w.scratch) {
    w.stats.interactions += s.interactions;
    w.stats.node_interactions += s.node_interactions;
  }
  const auto team = static_cast<std::size_t>(w.team);
  w.stats.work.resize(bh::kRegions);
  for (std::size_t r = 0; r < bh::kRegions; ++r) {
    const std::uint64_t* first = w.work.data() + r * team;
    ThreadWork& region = w.stats.work[r];
    region.region = bh::kRegionNames[r][0];
    region.unit = bh::kRegionNames[r][1];
    region.per_thread.assign(first, first + team);
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
