// SPDX-License-Identifier: MIT
// calder::nbody: Barnes-Hut on a quadtree of Morton-sorted bodies (see
// calder/nbody.hpp for the algorithm and its guarantees). This file checks
// the options and runs the steps, each in its own files (barnes_hut_tree.hpp):
// a tree builder (the fast one, or the reference build for few bodies), the
// built tree, and a walker that sums over it and adds the sums to the
// caller's arrays.
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "barnes_hut_builder.hpp"
#include "barnes_hut_reference.hpp"
#include "barnes_hut_tree.hpp"
#include "barnes_hut_walker.hpp"
#include "calder/error.hpp"
#include "common.hpp"
#include "kernels.hpp"

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

// The solver's state between calls: the builders, the tree they hand to the
// walk, the walker, and the counts the stats report.
struct BarnesHut::Workspace {
  BarnesHutStats stats;
  bh::TreeBuilder builder;
  bh::ReferenceScratch reference;
  bh::BuiltTree tree;
  bh::Walker walker;
  std::vector<std::uint64_t> work;  // work[region * team + t] (bh::Region)
};

namespace bh {

BuildSettings build_settings(const BarnesHutOptions& options) {
  BuildSettings s;
  s.leaf_size = static_cast<std::size_t>(options.leaf_size);
  s.group_size = static_cast<std::size_t>(options.group_size);
  s.inv_theta = options.theta > 0.0 ? 1.0 / options.theta : std::numeric_limits<double>::infinity();
  s.single = options.precision == Precision::float32;
  s.G = options.G;
  s.threads = detail::thread_count(options);
  return s;
}

}  // namespace bh

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
  const bh::BuildSettings settings = bh::build_settings(options);
  const auto team = static_cast<std::size_t>(bh::team_for(n, settings.threads));
  w.work.assign(bh::kRegions * team, 0);

  const Clock::time_point t0 = Clock::now();
  if (n < bh::kParallelFrom) {
    bh::reference_build(x, y, mass, settings, w.tree, w.reference);
    w.stats.build_phases.push_back(
        BarnesHutStats::Phase{"reference build", seconds_since(t0), true});
    w.work[bh::kRegionBodies] = n;
    w.work[bh::kRegionRanges] = n;
    w.work[bh::kRegionSubtrees] = n;
    w.work[bh::kRegionNodes] = w.tree.nodes.size();
  } else {
    w.builder.build(x, y, mass, settings, w.tree, w.work.data());
    const double* end = w.builder.phase_end();
    for (int k = 0; k < bh::kBuildPhases; ++k) {
      w.stats.build_phases.push_back(BarnesHutStats::Phase{
          bh::kBuildPhaseNames[k].name, end[k + 1] - end[k], bh::kBuildPhaseNames[k].serial});
    }
  }
  w.stats.build_seconds = seconds_since(t0);

  const Clock::time_point t1 = Clock::now();
  detail::LawParams p = detail::law_params(options, w.tree.frame);
  p.float_range = detail::float_range_of(w.tree.square.side, p.eps2);
  bh::WalkSettings walk;
  walk.inv_theta = settings.inv_theta;
  walk.target_block = static_cast<std::size_t>(options.target_block < 0 ? kernel_target_block()
                                                                        : options.target_block);
  walk.threads = settings.threads;
  w.walker.walk(w.tree, walk, p, w.tree.frame.scale,
                settings.single ? w.tree.frame.factor : options.G, ax, ay, w.work.data());
  w.stats.walk_seconds = seconds_since(t1);

  w.stats.nodes = w.tree.nodes.size();
  w.stats.groups = w.tree.groups.size();
  w.stats.depth = w.tree.depth;
  w.stats.leaves = w.tree.leaves;
  w.stats.interactions = w.walker.interactions();
  w.stats.node_interactions = w.walker.node_interactions();
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
