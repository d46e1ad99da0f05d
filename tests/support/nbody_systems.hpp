// SPDX-License-Identifier: MIT
// Bodies for calder::nbody's tests: a System of columns, and a uniform disk.
#pragma once

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

}  // namespace calder::test
