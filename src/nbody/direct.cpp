// SPDX-License-Identifier: MIT
// calder::nbody: validation, the reference sum and direct summation.
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "calder/error.hpp"
#include "calder/nbody.hpp"
#include "common.hpp"
#include "kernels.hpp"

#if defined(_OPENMP)
#include <omp.h>
#endif

namespace calder::nbody {

namespace detail {

namespace {

bool overlaps(std::span<const double> a, std::span<double> b) {
  if (a.empty() || b.empty()) return false;
  const std::less<const double*> less;
  const double* b_begin = b.data();
  return less(a.data(), b_begin + b.size()) && less(b_begin, a.data() + a.size());
}

std::string size_message(const char* where, const char* name, std::size_t size,
                         std::size_t expected) {
  return std::string(where) + ": " + name + " has " + std::to_string(size) + " elements, x has " +
         std::to_string(expected);
}

}  // namespace

void validate(const char* where, std::span<const double> x, std::span<const double> y,
              std::span<const double> mass, std::span<double> ax, std::span<double> ay,
              const Options& options) {
  const std::size_t n = x.size();
  if (y.size() != n) throw Error(size_message(where, "y", y.size(), n));
  if (mass.size() != n) throw Error(size_message(where, "mass", mass.size(), n));
  if (ax.size() != n) throw Error(size_message(where, "ax", ax.size(), n));
  if (ay.size() != n) throw Error(size_message(where, "ay", ay.size(), n));
  for (const std::span<double> out : {ax, ay}) {
    for (const std::span<const double> in : {x, y, mass}) {
      if (overlaps(in, out)) {
        throw Error(std::string(where) + ": ax and ay must not overlap x, y or mass");
      }
    }
  }
  if (overlaps(ax, ay)) throw Error(std::string(where) + ": ax and ay must not overlap");

  const std::string w(where);
  calder::detail::require_finite(options.G, where, "options.G");
  calder::detail::require_non_negative(options.softening, where, "options.softening");
  if (options.law != Law::plummer) {
    calder::detail::require_positive(options.min_distance, where, "options.min_distance");
    calder::detail::require_positive(options.max_distance, where, "options.max_distance");
    if (options.min_distance > options.max_distance) {
      throw Error(w + ": options.min_distance must not exceed options.max_distance (got " +
                  calder::detail::format_number(options.min_distance) + " > " +
                  calder::detail::format_number(options.max_distance) + ")");
    }
  }
  if (options.threads < 0) {
    throw Error(w + ": options.threads must be >= 0 (got " + std::to_string(options.threads) + ")");
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(x[i]) || !std::isfinite(y[i])) {
      throw Error(w + ": the position of body " + std::to_string(i) + " must be finite (got " +
                  calder::detail::format_number(x[i]) + ", " + calder::detail::format_number(y[i]) +
                  ")");
    }
    if (!(std::isfinite(mass[i]) && mass[i] > 0.0)) {
      throw Error(w + ": the mass of body " + std::to_string(i) + " must be finite and > 0 (got " +
                  calder::detail::format_number(mass[i]) + ")");
    }
  }
}

int thread_count(const Options& options) {
#if defined(_OPENMP)
  return options.threads > 0 ? options.threads : std::max(1, omp_get_max_threads());
#else
  (void)options;
  return 1;
#endif
}

FloatFrame float_frame(double cx, double cy, double half, double max_mass, double G) {
  FloatFrame f;
  f.cx = cx;
  f.cy = cy;
  // The power of two that brings the largest |p - centre| (plus a margin for
  // rounding) to <= 1, and the largest mass to <= 1.
  half *= 1.0 + 1e-12;
  int e = 0;
  if (half > 0.0 && std::isfinite(half)) std::frexp(half, &e);  // half = f 2^e, f in [0.5, 1)
  int e_mass = 0;
  std::frexp(max_mass, &e_mass);
  f.scale = std::ldexp(1.0, -e);
  f.mass_scale = std::ldexp(1.0, -e_mass);
  f.factor = std::ldexp(G, 2 * -e + e_mass);  // G scale^2 / mass_scale
  return f;
}

FloatFrame float_frame(std::span<const double> x, std::span<const double> y,
                       std::span<const double> mass, double G) {
  if (x.empty()) return FloatFrame{};
  const auto [x0, x1] = std::minmax_element(x.begin(), x.end());
  const auto [y0, y1] = std::minmax_element(y.begin(), y.end());
  return float_frame(*x0 + (*x1 - *x0) * 0.5, *y0 + (*y1 - *y0) * 0.5,
                     std::max(*x1 - *x0, *y1 - *y0) * 0.5,
                     *std::max_element(mass.begin(), mass.end()), G);
}

LawParams law_params(const Options& options, const FloatFrame& frame) {
  LawParams p;
  p.law = options.law;
  const double s = frame.scale;
  if (options.law == Law::plummer) {
    p.eps2 = options.softening * options.softening;
    const double eps_f = options.softening * s;
    p.eps2_f = static_cast<float>(eps_f * eps_f);
    // A softening too small for float32 (or double) is no softening: the
    // kernels then mask coincident pairs instead.
    if (p.eps2_f < FLT_MIN) p.eps2_f = 0.0f;
    if (p.eps2 < DBL_MIN) p.eps2 = 0.0;
  } else if (options.law == Law::clamp_distance) {
    p.lo = options.min_distance;
    p.hi = options.max_distance;
    p.lo_f = static_cast<float>(options.min_distance * s);
    p.hi_f = static_cast<float>(options.max_distance * s);
  } else {
    p.lo = options.min_distance;
    p.hi = options.max_distance;
    p.lo_f = static_cast<float>(options.min_distance * s * s);
    p.hi_f = static_cast<float>(options.max_distance * s * s);
  }
  return p;
}

}  // namespace detail

Vec2 reference_acceleration(std::span<const double> x, std::span<const double> y,
                            std::span<const double> mass, std::size_t target,
                            const Options& options) {
  const std::size_t n = x.size();
  if (y.size() != n || mass.size() != n) {
    throw Error("nbody::reference_acceleration: x, y and mass must have the same size");
  }
  if (target >= n) {
    throw Error("nbody::reference_acceleration: target " + std::to_string(target) +
                " out of range (" + std::to_string(n) + " bodies)");
  }
  const double G = options.G;
  const double eps2 = options.softening * options.softening;
  const double lo = options.min_distance;
  const double hi = options.max_distance;
  double ax = 0.0;
  double ay = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    if (j == target) continue;
    const double dx = x[j] - x[target];
    const double dy = y[j] - y[target];
    const double r2 = dx * dx + dy * dy;
    if (r2 == 0.0) continue;  // coincident: no direction
    const double r = std::sqrt(r2);
    double w = 0.0;  // |a| / r
    switch (options.law) {
      case Law::plummer: {
        const double s2 = r2 + eps2;
        w = G * mass[j] / (s2 * std::sqrt(s2));
        break;
      }
      case Law::clamp_distance: {
        const double d = std::clamp(r, lo, hi);
        w = G * mass[j] / (d * d) / r;
        break;
      }
      case Law::clamp_squared_distance: {
        const double q = std::clamp(r2, lo, hi);
        w = G * mass[j] / q / r;
        break;
      }
    }
    ax += w * dx;
    ay += w * dy;
  }
  return {ax, ay};
}

void reference_accelerations(std::span<const double> x, std::span<const double> y,
                             std::span<const double> mass, std::span<double> ax,
                             std::span<double> ay, const Options& options) {
  detail::validate("nbody::reference_accelerations", x, y, mass, ax, ay, options);
  std::vector<double> sx(x.size());
  std::vector<double> sy(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Vec2 a = reference_acceleration(x, y, mass, i, options);
    sx[i] = a.x;
    sy[i] = a.y;
  }
  for (std::size_t i = 0; i < x.size(); ++i) {
    ax[i] += sx[i];
    ay[i] += sy[i];
  }
}

void direct_accelerations(std::span<const double> x, std::span<const double> y,
                          std::span<const double> mass, std::span<double> ax, std::span<double> ay,
                          const Options& options) {
  detail::validate("nbody::direct_accelerations", x, y, mass, ax, ay, options);
  const std::size_t n = x.size();
  if (n < 2) return;
  const detail::KernelTable& k = detail::kernels();
  // Below ~10^5 pairs (tens of microseconds) waking threads costs more than it saves.
  const int threads = n < 320 ? 1 : detail::thread_count(options);
  std::vector<double> sum_x(n, 0.0);
  std::vector<double> sum_y(n, 0.0);

  if (options.precision == Precision::float64) {
    detail::LawParams p = detail::law_params(options, detail::FloatFrame{});
    const auto [x0, x1] = std::minmax_element(x.begin(), x.end());
    const auto [y0, y1] = std::minmax_element(y.begin(), y.end());
    p.float_range = detail::float_range_of(std::max(*x1 - *x0, *y1 - *y0), p.eps2);
    const detail::Bodies<double> sources{x.data(), y.data(), mass.data(), n};
    const std::size_t block = k.block64;
    const auto blocks = static_cast<std::ptrdiff_t>((n + block - 1) / block);
#if defined(_OPENMP)
#pragma omp parallel for schedule(static) num_threads(threads)
#endif
    for (std::ptrdiff_t b = 0; b < blocks; ++b) {
      const std::size_t i0 = static_cast<std::size_t>(b) * block;
      k.accumulate64(x.data() + i0, y.data() + i0, std::min(block, n - i0), sources, p,
                     sum_x.data() + i0, sum_y.data() + i0);
    }
    for (std::size_t i = 0; i < n; ++i) {
      ax[i] += options.G * sum_x[i];
      ay[i] += options.G * sum_y[i];
    }
  } else {
    const detail::FloatFrame frame = detail::float_frame(x, y, mass, options.G);
    const detail::LawParams p = detail::law_params(options, frame);
    // Two-float positions: hi = the nearest float, lo = the rest (exact).
    std::vector<float> fx(n);
    std::vector<float> fy(n);
    std::vector<float> fx_lo(n);
    std::vector<float> fy_lo(n);
    std::vector<float> fm(n);
    for (std::size_t i = 0; i < n; ++i) {
      const double px = (x[i] - frame.cx) * frame.scale;
      const double py = (y[i] - frame.cy) * frame.scale;
      fx[i] = static_cast<float>(px);
      fy[i] = static_cast<float>(py);
      fx_lo[i] = static_cast<float>(px - static_cast<double>(fx[i]));
      fy_lo[i] = static_cast<float>(py - static_cast<double>(fy[i]));
      fm[i] = static_cast<float>(mass[i] * frame.mass_scale);
    }
    detail::Bodies<float> sources{fx.data(), fy.data(), fm.data(), n};
    sources.x_lo = fx_lo.data();
    sources.y_lo = fy_lo.data();
    const std::size_t block = k.block32;
    const auto blocks = static_cast<std::ptrdiff_t>((n + block - 1) / block);
#if defined(_OPENMP)
#pragma omp parallel for schedule(static) num_threads(threads)
#endif
    for (std::ptrdiff_t b = 0; b < blocks; ++b) {
      const std::size_t i0 = static_cast<std::size_t>(b) * block;
      k.accumulate32(fx.data() + i0, fy.data() + i0, fx_lo.data() + i0, fy_lo.data() + i0,
                     std::min(block, n - i0), sources, p, sum_x.data() + i0, sum_y.data() + i0);
    }
    for (std::size_t i = 0; i < n; ++i) {
      ax[i] += frame.factor * sum_x[i];
      ay[i] += frame.factor * sum_y[i];
    }
  }
  (void)threads;
}

const char* kernel_name() { return detail::kernels().name; }

int max_threads() { return detail::thread_count(Options{}); }

}  // namespace calder::nbody
