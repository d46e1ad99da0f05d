// SPDX-License-Identifier: MIT
#include "peers/soa_rain.hpp"

#include <algorithm>
#include <stdexcept>
#include <variant>

#if defined(_OPENMP)
#include <omp.h>
#endif

namespace calder::peers {

// The copies of the loop (soa_rain_loop.cpp).
void soa_rain_native(SoaRainState<float>& state, std::size_t first, std::size_t count, int steps);
void soa_rain_native(SoaRainState<double>& state, std::size_t first, std::size_t count, int steps);
#if defined(CALDER_SOA_RAIN_AVX2)
void soa_rain_avx2(SoaRainState<float>& state, std::size_t first, std::size_t count, int steps);
void soa_rain_avx2(SoaRainState<double>& state, std::size_t first, std::size_t count, int steps);
#endif

namespace {

template <class R>
SoaRainState<R> state_of(const World& world) {
  SoaRainState<R> s;
  const BodyView b = world.bodies();
  const auto copy = [](std::span<const double> from, std::vector<R>& to) {
    to.assign(from.begin(), from.end());
  };
  copy(b.x, s.x);
  copy(b.y, s.y);
  copy(b.vx, s.vx);
  copy(b.vy, s.vy);
  copy(b.mass, s.mass);
  copy(b.radius, s.radius);
  for (const double area : b.drag_area) {
    if (area != 1.0) throw std::invalid_argument("SoaRain: a drag area other than 1");
  }
  const Boundary& boundary = world.boundary();
  if (boundary.kind != BoundaryKind::bounce || !boundary.use_radius ||
      boundary.timing != BoundaryTiming::after_update || !boundary.edges.left ||
      !boundary.edges.right || !boundary.edges.bottom || boundary.edges.top) {
    throw std::invalid_argument("SoaRain: not the rain scene's boundary");
  }
  s.width = R(world.width());
  s.height = R(world.height());
  s.restitution = R(boundary.restitution);
  s.dt = R(world.dt());
  int gravity = 0, drag = 0;
  for (const Field& field : world.fields()) {
    if (const auto* g = std::get_if<Gravity>(&field)) {
      if (!g->scale_by_mass || g->g.x != 0.0) {
        throw std::invalid_argument("SoaRain: not the rain scene's gravity");
      }
      s.gravity = R(g->g.y);
      ++gravity;
    } else if (const auto* d = std::get_if<Drag>(&field)) {
      s.drag = R(d->c);
      ++drag;
    } else {
      throw std::invalid_argument("SoaRain: a field the rain scene doesn't have");
    }
  }
  if (gravity != 1 || drag != 1)
    throw std::invalid_argument("SoaRain: not the rain scene's fields");
  return s;
}

template <class R>
std::vector<double> widen(const std::vector<R>& v) {
  return {v.begin(), v.end()};
}

}  // namespace

bool soa_rain_has_avx2() {
#if defined(CALDER_SOA_RAIN_AVX2)
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
  return false;
#endif
}

SoaRain::SoaRain(const World& world, bool float32, bool avx2, int threads)
    : float32_(float32), avx2_(avx2 && soa_rain_has_avx2()), threads_(threads < 1 ? 1 : threads) {
  flags_ = avx2_ ? "-O3 -mavx2 -mfma -ffast-math" : "-O3 -march=native -ffast-math";
  if (float32_) {
    f_ = state_of<float>(world);
  } else {
    d_ = state_of<double>(world);
  }
}

namespace {

template <class R>
void run_slice(SoaRainState<R>& state, bool avx2, std::size_t first, std::size_t count, int steps) {
#if defined(CALDER_SOA_RAIN_AVX2)
  if (avx2) return soa_rain_avx2(state, first, count, steps);
#endif
  (void)avx2;
  soa_rain_native(state, first, count, steps);
}

// Each thread runs every step on its own slice (64-byte aligned cuts): the
// threads share nothing and never wait on each other within a call.
template <class R>
void run(SoaRainState<R>& state, bool avx2, int threads, int steps) {
  const std::size_t n = state.x.size();
#if defined(_OPENMP)
#pragma omp parallel num_threads(threads)
  {
    const auto parts = static_cast<std::size_t>(omp_get_num_threads());
    const auto part = static_cast<std::size_t>(omp_get_thread_num());
    constexpr std::size_t kAlign = 64 / sizeof(R);
    const auto cut = [&](std::size_t k) {
      return k == parts ? n : std::min(n, (n * k / parts) / kAlign * kAlign);
    };
    run_slice(state, avx2, cut(part), cut(part + 1) - cut(part), steps);
  }
#else
  (void)threads;
  run_slice(state, avx2, 0, n, steps);
#endif
}

}  // namespace

void SoaRain::step(int steps) {
  if (float32_) return run(f_, avx2_, threads_, steps);
  run(d_, avx2_, threads_, steps);
}

std::vector<double> SoaRain::x() const { return float32_ ? widen(f_.x) : d_.x; }
std::vector<double> SoaRain::y() const { return float32_ ? widen(f_.y) : d_.y; }
std::vector<double> SoaRain::vx() const { return float32_ ? widen(f_.vx) : d_.vx; }
std::vector<double> SoaRain::vy() const { return float32_ ? widen(f_.vy) : d_.vy; }

}  // namespace calder::peers
