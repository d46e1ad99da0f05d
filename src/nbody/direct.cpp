// SPDX-License-Identifier: MIT
// calder::nbody: validation, the reference sum and direct summation.
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstddef>
#include <functional>
#include <iterator>
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

// Direct summation with each pair once (Newton's third law), for systems of
// kStripesForPairs stripes of kFloatTile bodies or more (below, the one-sided
// blocks cost little and share out better). The bodies, padded to whole
// vectors with massless copies of body 0, are cut into stripes of as many
// vectors as can be (at most kFloatTile bodies, so that the threads' pairs
// of a round cost the same; a short last stripe held one thread back); a first
// round sums each stripe over itself (self_pairs), then the circle method's
// rounds pair every two stripes once, each stripe in one pair a round at
// most: the pairs of a round run side by side and add to disjoint sums, and
// each body's sum runs in round order, the same for any thread count.
inline constexpr std::size_t kStripesForPairs = 8;

bool sums_pairs_once(std::size_t n) {
  return (n + kFloatTile - 1) / kFloatTile >= kStripesForPairs;
}

// A stripe's pairs among its own bodies: halves of whole vectors pair each
// other once, down to kSelfVectors vectors, which sum over themselves
// (one-sided: every pair twice, which below a few vectors costs less than
// the splits).
inline constexpr std::size_t kSelfVectors = 4;

template <typename T, typename OneSided, typename Pairs>
void self_pairs(const Bodies<T>& own, std::size_t lanes, double* sum_x, double* sum_y,
                OneSided& one_sided, Pairs& pairs) {
  const std::size_t vectors = own.n / lanes;
  if (vectors <= kSelfVectors) {
    one_sided(own, own, sum_x, sum_y);
    return;
  }
  const std::size_t half = vectors / 2 * lanes;
  const Bodies<T> lower = own.slice(0, half);
  const Bodies<T> upper = own.slice(half, own.n - half);
  pairs(lower, upper, sum_x, sum_y, sum_x + half, sum_y + half);
  self_pairs(lower, lanes, sum_x, sum_y, one_sided, pairs);
  self_pairs(upper, lanes, sum_x + half, sum_y + half, one_sided, pairs);
}

template <typename T, typename OneSided, typename Pairs>
void sum_by_stripes(const Bodies<T>& bodies, std::size_t lanes, int threads, double* sum_x,
                    double* sum_y, OneSided one_sided, Pairs pairs) {
  const std::size_t stripes = (bodies.n + kFloatTile - 1) / kFloatTile;
  const std::size_t vectors = bodies.n / lanes;  // (bodies.n: whole vectors)
  // Stripe k: vectors k V / P to (k + 1) V / P (at most kFloatTile bodies:
  // bodies.n <= P kFloatTile).
  const auto first = [&](std::size_t k) { return k * vectors / stripes * lanes; };
  const auto stripe = [&](std::size_t k) {
    return bodies.slice(first(k), first(k + 1) - first(k));
  };
  const std::size_t players = stripes + stripes % 2;  // even: a bye when odd
  const auto diagonal = static_cast<std::ptrdiff_t>(stripes);
  const auto matches = static_cast<std::ptrdiff_t>(players / 2);
#if defined(_OPENMP)
#pragma omp parallel num_threads(threads)
#endif
  {
#if defined(_OPENMP)
#pragma omp for schedule(static)
#endif
    for (std::ptrdiff_t k = 0; k < diagonal; ++k) {
      const auto u = static_cast<std::size_t>(k);
      self_pairs(stripe(u), lanes, sum_x + first(u), sum_y + first(u), one_sided, pairs);
    }
    for (std::size_t round = 0; round + 1 < players; ++round) {
#if defined(_OPENMP)
#pragma omp for schedule(static)
#endif
      for (std::ptrdiff_t t = 0; t < matches; ++t) {
        const auto u = static_cast<std::size_t>(t);
        const std::size_t circle = players - 1;
        const std::size_t a = u == 0 ? players - 1 : (round + u) % circle;
        const std::size_t b = u == 0 ? round : (round + circle - u) % circle;
        if (a >= stripes || b >= stripes) continue;  // the bye
        pairs(stripe(a), stripe(b), sum_x + first(a), sum_y + first(a), sum_x + first(b),
              sum_y + first(b));
      }
    }
  }
  (void)threads;
}

// The direct kernels' sums of `bodies` (n of them, n_pad in its arrays:
// whole vectors of `lanes`, massless after n) into (sum_x, sum_y): each pair once from
// kStripesForPairs stripes on (sum_by_stripes), else each target's sum over
// all sources, blocks of `block` targets side by side.
template <typename T, typename OneSided, typename Pairs>
void direct_sums(Bodies<T> bodies, std::size_t n_pad, std::size_t lanes, std::size_t block,
                 int threads, double* sum_x, double* sum_y, OneSided one_sided, Pairs pairs) {
  const std::size_t n = bodies.n;
  if (sums_pairs_once(n)) {
    bodies.n = n_pad;
    sum_by_stripes(bodies, lanes, threads, sum_x, sum_y, one_sided, pairs);
    return;
  }
  const auto blocks = static_cast<std::ptrdiff_t>((n + block - 1) / block);
#if defined(_OPENMP)
#pragma omp parallel for schedule(static) num_threads(threads)
#endif
  for (std::ptrdiff_t b = 0; b < blocks; ++b) {
    const std::size_t i0 = static_cast<std::size_t>(b) * block;
    one_sided(bodies.slice(i0, std::min(block, n - i0)), bodies, sum_x + i0, sum_y + i0);
  }
  (void)threads;
}

// A copy of `from` padded to `count` with `pad`.
template <typename T>
std::vector<T> padded(const T* from, std::size_t n, std::size_t count, T pad) {
  std::vector<T> out(count, pad);
  std::copy(from, from + n, out.begin());
  return out;
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
  // Each pair once: the bodies padded to whole vectors (massless copies of body 0).
  const bool pairs_once = detail::sums_pairs_once(n);
  const std::size_t lanes = std::max(k.group_block64, k.group_block32);
  const std::size_t n_pad = pairs_once ? (n + lanes - 1) / lanes * lanes : n;
  std::vector<double> sum_x(n_pad, 0.0);
  std::vector<double> sum_y(n_pad, 0.0);
  double factor = options.G;

  if (options.precision == Precision::float64) {
    detail::LawParams p = detail::law_params(options, detail::FloatFrame{});
    const auto [x0, x1] = std::minmax_element(x.begin(), x.end());
    const auto [y0, y1] = std::minmax_element(y.begin(), y.end());
    p.float_range = detail::float_range_of(std::max(*x1 - *x0, *y1 - *y0), p.eps2);
    // The caller's arrays, or copies padded to whole vectors where the pairs need them.
    detail::Bodies<double> bodies{x.data(), y.data(), mass.data(), n};
    std::vector<double> px, py, pm;
    if (n_pad != n) {
      px = detail::padded(x.data(), n, n_pad, x[0]);
      py = detail::padded(y.data(), n, n_pad, y[0]);
      pm = detail::padded(mass.data(), n, n_pad, 0.0);
      bodies = {px.data(), py.data(), pm.data(), n};
    }
    detail::direct_sums(
        bodies, n_pad, lanes, k.block64, threads, sum_x.data(), sum_y.data(),
        [&](const detail::Bodies<double>& t, const detail::Bodies<double>& s, double* out_x,
            double* out_y) { k.accumulate64(t.x, t.y, t.n, s, p, out_x, out_y); },
        [&](const detail::Bodies<double>& a, const detail::Bodies<double>& b, double* a_x,
            double* a_y, double* b_x, double* b_y) { k.pairs64(a, b, p, a_x, a_y, b_x, b_y); });
  } else {
    const detail::FloatFrame frame = detail::float_frame(x, y, mass, options.G);
    const detail::LawParams p = detail::law_params(options, frame);
    // Two-float positions: hi = the nearest float, lo = the rest (exact);
    // the padding is body 0's position with no mass.
    std::vector<float> fx(n_pad);
    std::vector<float> fy(n_pad);
    std::vector<float> fx_lo(n_pad);
    std::vector<float> fy_lo(n_pad);
    std::vector<float> fm(n_pad, 0.0f);
    for (std::size_t i = 0; i < n_pad; ++i) {
      const double px = (x[i < n ? i : 0] - frame.cx) * frame.scale;
      const double py = (y[i < n ? i : 0] - frame.cy) * frame.scale;
      fx[i] = static_cast<float>(px);
      fy[i] = static_cast<float>(py);
      fx_lo[i] = static_cast<float>(px - static_cast<double>(fx[i]));
      fy_lo[i] = static_cast<float>(py - static_cast<double>(fy[i]));
      if (i < n) fm[i] = static_cast<float>(mass[i] * frame.mass_scale);
    }
    detail::Bodies<float> bodies{fx.data(), fy.data(), fm.data(), n};
    bodies.x_lo = fx_lo.data();
    bodies.y_lo = fy_lo.data();
    detail::direct_sums(
        bodies, n_pad, lanes, k.block32, threads, sum_x.data(), sum_y.data(),
        [&](const detail::Bodies<float>& t, const detail::Bodies<float>& s, double* out_x,
            double* out_y) { k.accumulate32(t.x, t.y, t.x_lo, t.y_lo, t.n, s, p, out_x, out_y); },
        [&](const detail::Bodies<float>& a, const detail::Bodies<float>& b, double* a_x,
            double* a_y, double* b_x, double* b_y) { k.pairs32(a, b, p, a_x, a_y, b_x, b_y); });
    factor = frame.factor;
  }
  for (std::size_t i = 0; i < n; ++i) {
    ax[i] += factor * sum_x[i];
    ay[i] += factor * sum_y[i];
  }
}

const char* kernel_name() { return detail::kernels().name; }
int kernel_target_block() { return static_cast<int>(detail::kernels().target_block64); }

int max_threads() { return detail::thread_count(Options{}); }

}  // namespace calder::nbody
