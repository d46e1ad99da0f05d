// SPDX-License-Identifier: MIT
// Bodies for calder::nbody's tests and benchmarks: a System of columns, a
// uniform disk, and clustered bodies (bench/peers/nbody_systems.cpp uses the
// same generator with its own shape).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

namespace calder::test {

struct System {
  std::vector<double> x;
  std::vector<double> y;
  std::vector<double> m;
  std::size_t size() const { return x.size(); }
};

inline double uniform(std::mt19937_64& g) {  // [0, 1), the same on every platform
  return static_cast<double>(g() >> 11) * 0x1.0p-53;
}

// n bodies uniform in a disk of radius r around (cx, cy), masses in [0.5, 1.5).
inline System disk(std::size_t n, std::uint64_t seed, double r = 50.0, double cx = 0.0,
                   double cy = 0.0) {
  std::mt19937_64 g(seed);
  System s;
  for (std::size_t i = 0; i < n; ++i) {
    const double radius = r * std::sqrt(uniform(g));
    const double angle = 6.283185307179586 * uniform(g);
    s.x.push_back(cx + radius * std::cos(angle));
    s.y.push_back(cy + radius * std::sin(angle));
    s.m.push_back(0.5 + uniform(g));
  }
  return s;
}

// Clustered bodies: `clumps` Plummer-like clumps of scale 1 to 5, centres
// uniform over [-half_span, half_span]^2; body i in clump i % clumps, at the
// radius that holds the fraction q (uniform, at most max_q) of a Plummer
// sphere's mass, a sqrt(q / (1 - q)); masses in [0.5, 1.5).
struct ClusterShape {
  std::size_t clumps = 6;
  double half_span = 50.0;
  double max_q = 0.999;
};
inline System clusters(std::size_t n, std::uint64_t seed, const ClusterShape& shape = {}) {
  std::mt19937_64 g(seed);
  std::vector<double> cx(shape.clumps);
  std::vector<double> cy(shape.clumps);
  std::vector<double> a(shape.clumps);
  for (std::size_t c = 0; c < shape.clumps; ++c) {
    cx[c] = 2.0 * shape.half_span * uniform(g) - shape.half_span;
    cy[c] = 2.0 * shape.half_span * uniform(g) - shape.half_span;
    a[c] = 1.0 + 4.0 * uniform(g);
  }
  System s;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t c = i % shape.clumps;
    const double q = std::min(uniform(g), shape.max_q);
    const double radius = a[c] * std::sqrt(q / (1.0 - q));
    const double angle = 6.283185307179586 * uniform(g);
    s.x.push_back(cx[c] + radius * std::cos(angle));
    s.y.push_back(cy[c] + radius * std::sin(angle));
    s.m.push_back(0.5 + uniform(g));
  }
  return s;
}

}  // namespace calder::test
