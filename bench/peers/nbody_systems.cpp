// SPDX-License-Identifier: MIT
#include "peers/nbody_systems.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <random>
#include <thread>
#include <utility>
#include <vector>

#include "../../tests/support/nbody_systems.hpp"  // the one clustered generator

namespace calder::peers {

namespace {

double uniform(std::mt19937_64& g) { return static_cast<double>(g() >> 11) * 0x1.0p-53; }

// force_error's weak pull: below this fraction of the sample's median.
constexpr double kWeakPull = 0.125;

}  // namespace

NBodySystem disk(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 g(seed);
  const double r = 50.0 * std::sqrt(static_cast<double>(n) / 1000.0);
  NBodySystem s;
  s.x.reserve(n);
  s.y.reserve(n);
  s.m.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double radius = r * std::sqrt(uniform(g));
    const double angle = 6.283185307179586 * uniform(g);
    s.x.push_back(radius * std::cos(angle));
    s.y.push_back(radius * std::sin(angle));
    s.m.push_back(0.5 + uniform(g));
  }
  return s;
}

NBodySystem clusters(std::size_t n, std::uint64_t seed) {
  test::System s = test::clusters(n, seed, {.clumps = 8, .half_span = 100.0, .max_q = 0.9999});
  return NBodySystem{std::move(s.x), std::move(s.y), std::move(s.m)};
}

ExactSample exact_sample(const NBodySystem& s, const nbody::Options& options, std::size_t sample) {
  ExactSample e;
  const std::size_t n = s.size();
  nbody::Options o = options;
  o.precision = nbody::Precision::float64;
  o.threads = 0;
  if (sample >= n) {
    e.ax.assign(n, 0.0);
    e.ay.assign(n, 0.0);
    nbody::direct_accelerations(s.x, s.y, s.m, e.ax, e.ay, o);
    for (std::size_t i = 0; i < n; ++i) e.bodies.push_back(i);
    return e;
  }
  std::mt19937_64 g(7);
  for (std::size_t k = 0; k < sample; ++k) e.bodies.push_back(static_cast<std::size_t>(g() % n));
  e.ax.resize(sample);
  e.ay.resize(sample);
  // O(N) each in plain loops: 10^9 pairs for 1000 bodies of 10^6, so spread
  // the sample over the cores (each body's sum is the same on any thread).
  const std::size_t workers = std::max(1u, std::thread::hardware_concurrency());
  auto work = [&](std::size_t w) {
    for (std::size_t k = w; k < sample; k += workers) {
      const Vec2 a = nbody::reference_acceleration(s.x, s.y, s.m, e.bodies[k], o);
      e.ax[k] = a.x;
      e.ay[k] = a.y;
    }
  };
  std::vector<std::thread> pool;
  for (std::size_t w = 1; w < workers; ++w) pool.emplace_back(work, w);
  work(0);
  for (auto& t : pool) t.join();
  return e;
}

ForceError force_error(const ExactSample& e, std::span<const double> ax,
                       std::span<const double> ay) {
  ForceError error;
  const std::size_t count = e.bodies.size();
  if (count == 0) return error;
  std::vector<double> pull(count);
  for (std::size_t k = 0; k < count; ++k) pull[k] = std::hypot(e.ax[k], e.ay[k]);
  std::vector<double> sorted = pull;
  const auto middle = sorted.begin() + static_cast<std::ptrdiff_t>(count / 2);
  std::nth_element(sorted.begin(), middle, sorted.end());
  const double median = *middle;
  double sum = 0.0;
  double weak = 0.0;
  double absolute = 0.0;
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t i = e.bodies[k];
    const double miss = std::hypot(ax[i] - e.ax[k], ay[i] - e.ay[k]);
    const double rel = miss / pull[k];
    sum += rel * rel;
    if (pull[k] < kWeakPull * median) weak += rel * rel;
    absolute += miss * miss;
    error.max = std::max(error.max, rel);
  }
  error.rms = std::sqrt(sum / static_cast<double>(count));
  error.weak_share = sum > 0.0 ? weak / sum : 0.0;
  // (A sample whose median pull is zero has no scale: 0, not a NaN.)
  error.abs_rms = median > 0.0 ? std::sqrt(absolute / static_cast<double>(count)) / median : 0.0;
  return error;
}

}  // namespace calder::peers
