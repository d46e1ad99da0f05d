// SPDX-License-Identifier: MIT
// calder::nbody: Barnes-Hut on a quadtree of Morton-sorted bodies (see
// calder/nbody.hpp for the algorithm and its guarantees). This file checks
// the options and runs the steps, each in its own file (barnes_hut_tree.hpp):
// build, multipole terms, walk; then the sums go back to the caller's order.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <string>

#include "barnes_hut_tree.hpp"
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
  if (n >= std::size_t{std::numeric_limits<std::uint32_t>::max()}) {
    throw Error(std::string(where) + ": too many bodies (at most 2^32 - 2)");
  }
}

// (ax, ay) += factor * the sums, from Morton order back to the caller's (a
// permutation: no two ranks write one body).
void scatter(const std::vector<std::uint32_t>& order, const std::vector<double>& sum_x,
             const std::vector<double>& sum_y, double factor, std::span<double> ax,
             std::span<double> ay, [[maybe_unused]] int team) {
  const auto n = static_cast<std::ptrdiff_t>(order.size());
#if defined(_OPENMP)
#pragma omp parallel for schedule(static) num_threads(team)
#endif
  for (std::ptrdiff_t r = 0; r < n; ++r) {
    const auto u = static_cast<std::size_t>(r);
    ax[order[u]] += factor * sum_x[u];
    ay[order[u]] += factor * sum_y[u];
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

void BarnesHut::accelerations(std::span<const double> x, std::span<const double> y,
                              std::span<const double> mass, std::span<double> ax,
                              std::span<double> ay, const BarnesHutOptions& options) {
  const char* where = "nbody::BarnesHut::accelerations";
  detail::validate(where, x, y, mass, ax, ay, options);
  check_options(where, x.size(), options);
  if (!workspace_) workspace_ = std::make_unique<Workspace>();
  Workspace& w = *workspace_;
  const std::size_t n = x.size();
  w.stats = BarnesHutStats{};
  w.stats.bodies = n;
  if (n < 2) return;
  const int threads = detail::thread_count(options);
  const int team = bh::team_for(n, threads);

  const Clock::time_point t0 = Clock::now();
  w.leaf_size = static_cast<std::size_t>(options.leaf_size);
  w.group_size = static_cast<std::size_t>(options.group_size);
  w.inv_theta = options.theta > 0.0 ? 1.0 / options.theta : std::numeric_limits<double>::infinity();
  w.build(x, y, mass, threads);
  const detail::FloatFrame frame = detail::float_frame(w.x0 + w.side * 0.5, w.y0 + w.side * 0.5,
                                                       w.side * 0.5, w.max_mass, options.G);
  const bool float32 = options.precision == Precision::float32;
  w.prepare_kernel_inputs(frame, float32, team);
  w.stats.build_seconds = seconds_since(t0);

  const Clock::time_point t1 = Clock::now();
  detail::LawParams p = detail::law_params(options, frame);
  p.float_range = detail::float_range_of(w.side, p.eps2);
  w.walk(p, frame.scale, float32, threads);
  scatter(w.order, w.sum_x, w.sum_y, float32 ? frame.factor : options.G, ax, ay, team);
  w.stats.walk_seconds = seconds_since(t1);

  w.stats.nodes = w.tree.nodes.size();
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
