// SPDX-License-Identifier: MIT
// calder: random numbers and Perlin noise that match p5.js 2.x bit for bit
// (see calder/random.hpp and shared/spec/chapter2.md).
#include "calder/random.hpp"

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>

#include "calder/detmath.hpp"
#include "calder/error.hpp"

namespace calder {

namespace {

// Written out: std::numbers is missing from the libc++ that Emscripten ships.
constexpr double pi = 3.141592653589793;
// p5's TWO_PI is Math.PI * 2 (an exact doubling).
constexpr double two_pi = pi * 2.0;

// p5's LCG (the values of Numerical Recipes): state = (a * state + c) mod m.
constexpr std::uint64_t lcg_a = 1664525;
constexpr std::uint64_t lcg_c = 1013904223;
constexpr double lcg_m = 4294967296.0;  // 2^32

// One LCG step on state, returning the draw state / 2^32 in [0, 1).
// JavaScript computes a * state + c exactly (it stays below 2^53), and so does
// this 64-bit arithmetic.
double lcg_next(std::uint32_t& state) {
  state = static_cast<std::uint32_t>((lcg_a * state + lcg_c) & 0xFFFFFFFFU);
  return static_cast<double>(state) / lcg_m;
}

// JavaScript's ToUint32 (`s >>> 0`) for a finite number: truncate toward zero,
// then reduce modulo 2^32 into [0, 2^32).
std::uint32_t to_uint32(double value) {
  double r = std::fmod(std::trunc(value), lcg_m);  // exact, in (-2^32, 2^32)
  if (r < 0.0) r += lcg_m;                         // exact: an integer below 2^32
  return static_cast<std::uint32_t>(r);
}

// JavaScript's Math.min / Math.max for non-NaN numbers (-0 is below +0).
double js_min(double a, double b) {
  if (a == b) return std::signbit(a) ? a : b;
  return a < b ? a : b;
}
double js_max(double a, double b) {
  if (a == b) return std::signbit(a) ? b : a;
  return a > b ? a : b;
}

// Infinite bounds are meaningful for constrain; only NaN is rejected.
void reject_nan(double value, const char* where, const char* what) {
  if (std::isnan(value)) {
    throw Error(std::string(where) + ": " + what + " must not be NaN (got nan)");
  }
}

// p5's scaled_cosine: the blending weight 0.5 * (1 - cos(t * pi)).
double scaled_cosine(double t) { return 0.5 * (1.0 - math::cos(t * pi)); }

}  // namespace

// ---------------------------------------------------------------- Random ---

void Random::random_seed(std::uint32_t seed) {
  state_ = seed;
  has_spare_gaussian_ = false;
  spare_gaussian_ = 0.0;
}

void Random::random_seed(double seed) {
  detail::require_finite(seed, "random_seed", "seed");
  random_seed(to_uint32(seed));
}

std::optional<double> Random::spare_gaussian() const {
  return has_spare_gaussian_ ? std::optional<double>(spare_gaussian_) : std::nullopt;
}

void Random::restore(std::uint32_t state, std::optional<double> spare_gaussian) {
  if (spare_gaussian) detail::require_finite(*spare_gaussian, "Random::restore", "spare_gaussian");
  state_ = state;
  has_spare_gaussian_ = spare_gaussian.has_value();
  spare_gaussian_ = spare_gaussian.value_or(0.0);
}

double Random::random() { return lcg_next(state_); }

double Random::random(double max) {
  detail::require_finite(max, "random", "max");
  return random() * max;
}

double Random::random(double min, double max) {
  detail::require_finite(min, "random", "min");
  detail::require_finite(max, "random", "max");
  if (min > max) {
    const double tmp = min;
    min = max;
    max = tmp;
  }
  return random() * (max - min) + min;
}

double Random::random_gaussian(double mean, double sd) {
  detail::require_finite(mean, "random_gaussian", "mean");
  detail::require_finite(sd, "random_gaussian", "sd");
  double y1 = 0.0;
  if (has_spare_gaussian_) {
    y1 = spare_gaussian_;
    has_spare_gaussian_ = false;
  } else {
    double x1 = 0.0;
    double x2 = 0.0;
    double w = 0.0;
    // p5 rejects only w >= 1. Rejecting w == 0 as well (x1 = x2 = 0, i.e. two
    // draws of exactly 0.5) departs from p5 only where p5 would compute
    // log(0) and return NaN or infinity.
    do {
      x1 = random(2.0) - 1.0;
      x2 = random(2.0) - 1.0;
      w = x1 * x1 + x2 * x2;
    } while (w >= 1.0 || w == 0.0);
    w = std::sqrt(-2.0 * math::log(w) / w);
    y1 = x1 * w;
    spare_gaussian_ = x2 * w;
    has_spare_gaussian_ = true;
  }
  return y1 * sd + mean;
}

Vec2 Random::random2d() { return Vec2::from_angle(random() * two_pi); }

Vec2 Vec2::random2d(Random& rng) { return rng.random2d(); }

Vec2 Vec2::random2d() { return default_random().random2d(); }

// ----------------------------------------------------------------- Noise ---

void Noise::noise_seed(std::uint32_t seed) {
  seed_ = seed;
  std::uint32_t state = seed;
  for (double& value : table_) value = lcg_next(state);
}

void Noise::noise_seed(double seed) {
  detail::require_finite(seed, "noise_seed", "seed");
  noise_seed(to_uint32(seed));
}

void Noise::noise_detail(int octaves, double falloff) {
  if (octaves < 1 || octaves > kMaxOctaves) {
    throw Error("noise_detail: octaves must be from 1 to " + std::to_string(kMaxOctaves) +
                " (got " + std::to_string(octaves) + ")");
  }
  detail::require_finite(falloff, "noise_detail", "falloff");
  octaves_ = octaves;
  falloff_ = falloff;
}

double Noise::noise(double x, double y, double z) const {
  detail::require_finite(x, "noise", "x");
  detail::require_finite(y, "noise", "y");
  detail::require_finite(z, "noise", "z");
  constexpr std::uint32_t mask = table_size - 1;  // 4095
  constexpr std::uint32_t y_wrap = 16;            // 1 << 4
  constexpr std::uint32_t z_wrap = 256;           // 1 << 8

  x = std::fabs(x);
  y = std::fabs(y);
  z = std::fabs(z);
  // Integer parts as JavaScript's 32-bit integers (modulo 2^32: only the low
  // 12 bits reach the table), fractions in double. Unsigned arithmetic keeps
  // the shifts and the wrap-around defined. (p5 adds the first octave's
  // integer parts in double; the low bits agree while that sum is exact, i.e.
  // for coordinates below about 9e15.)
  const double x_floor = std::floor(x);
  const double y_floor = std::floor(y);
  const double z_floor = std::floor(z);
  std::uint32_t xi = to_uint32(x_floor);
  std::uint32_t yi = to_uint32(y_floor);
  std::uint32_t zi = to_uint32(z_floor);
  double xf = x - x_floor;
  double yf = y - y_floor;
  double zf = z - z_floor;

  const auto& t = table_;
  double r = 0.0;
  double ampl = 0.5;
  for (int octave = 0; octave < octaves_; ++octave) {
    std::uint32_t of = xi + (yi << 4) + (zi << 8);
    const double rxf = scaled_cosine(xf);
    const double ryf = scaled_cosine(yf);

    double n1 = t[of & mask];
    n1 += rxf * (t[(of + 1) & mask] - n1);
    double n2 = t[(of + y_wrap) & mask];
    n2 += rxf * (t[(of + y_wrap + 1) & mask] - n2);
    n1 += ryf * (n2 - n1);

    of += z_wrap;
    n2 = t[of & mask];
    n2 += rxf * (t[(of + 1) & mask] - n2);
    double n3 = t[(of + y_wrap) & mask];
    n3 += rxf * (t[(of + y_wrap + 1) & mask] - n3);
    n2 += ryf * (n3 - n2);

    n1 += scaled_cosine(zf) * (n2 - n1);

    r += n1 * ampl;
    ampl *= falloff_;

    xi <<= 1;
    xf *= 2.0;
    yi <<= 1;
    yf *= 2.0;
    zi <<= 1;
    zf *= 2.0;
    if (xf >= 1.0) {
      ++xi;
      xf -= 1.0;
    }
    if (yf >= 1.0) {
      ++yi;
      yf -= 1.0;
    }
    if (zf >= 1.0) {
      ++zi;
      zf -= 1.0;
    }
  }
  return r;
}

// --------------------------------------------------------------- globals ---

Random& default_random() {
  static Random instance;
  return instance;
}

Noise& default_noise() {
  static Noise instance;
  return instance;
}

void random_seed(std::uint32_t seed) { default_random().random_seed(seed); }
void random_seed(double seed) { default_random().random_seed(seed); }
void random_seed(int seed) { default_random().random_seed(seed); }
double random() { return default_random().random(); }
double random(double max) { return default_random().random(max); }
double random(double min, double max) { return default_random().random(min, max); }
double random_gaussian(double mean, double sd) {
  return default_random().random_gaussian(mean, sd);
}
void noise_seed(std::uint32_t seed) { default_noise().noise_seed(seed); }
void noise_seed(double seed) { default_noise().noise_seed(seed); }
void noise_seed(int seed) { default_noise().noise_seed(seed); }
void noise_detail(int octaves, double falloff) { default_noise().noise_detail(octaves, falloff); }
double noise(double x, double y, double z) { return default_noise().noise(x, y, z); }

double map_range(double value, double start1, double stop1, double start2, double stop2) {
  detail::require_finite(value, "map_range", "value");
  detail::require_finite(start1, "map_range", "start1");
  detail::require_finite(stop1, "map_range", "stop1");
  detail::require_finite(start2, "map_range", "start2");
  detail::require_finite(stop2, "map_range", "stop2");
  if (stop1 == start1) {
    throw Error("map_range: stop1 must differ from start1 (got " + detail::format_number(stop1) +
                " for both)");
  }
  return (value - start1) / (stop1 - start1) * (stop2 - start2) + start2;
}

double constrain(double n, double low, double high) {
  reject_nan(n, "constrain", "n");
  reject_nan(low, "constrain", "low");
  reject_nan(high, "constrain", "high");
  return js_max(js_min(n, high), low);
}

}  // namespace calder
