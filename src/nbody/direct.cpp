// SPDX-License-Identifier: MIT
// calder::nbody: validation, the reference sum and direct summation.
#include <algorithm>
#include <atomic>
#include <cfloat>
#include <cmath>
#include <cstddef>
#include <functional>
#include <iterator>
#include <memory>
#include <string>
#include <thread>
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

struct ThisThread {
  std::size_t t;
  std::size_t nt;
};
ThisThread this_thread() {
#if defined(_OPENMP)
  return {static_cast<std::size_t>(omp_get_thread_num()),
          static_cast<std::size_t>(omp_get_num_threads())};
#else
  return {0, 1};
#endif
}

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

  calder::detail::require_finite(options.G, where, "options.G");
  calder::detail::require_non_negative(options.softening, where, "options.softening");
  if (options.law != Law::plummer) {
    calder::detail::require_positive(options.min_distance, where, "options.min_distance");
    calder::detail::require_positive(options.max_distance, where, "options.max_distance");
    if (options.min_distance > options.max_distance) {
      throw Error(std::string(where) +
                  ": options.min_distance must not exceed options.max_distance (got " +
                  calder::detail::format_number(options.min_distance) + " > " +
                  calder::detail::format_number(options.max_distance) + ")");
    }
  }
  if (options.threads < 0) {
    throw Error(std::string(where) + ": options.threads must be >= 0 (got " +
                std::to_string(options.threads) + ")");
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(x[i]) || !std::isfinite(y[i])) {
      throw Error(std::string(where) + ": the position of body " + std::to_string(i) +
                  " must be finite (got " + calder::detail::format_number(x[i]) + ", " +
                  calder::detail::format_number(y[i]) + ")");
    }
    if (!(std::isfinite(mass[i]) && mass[i] > 0.0)) {
      throw Error(std::string(where) + ": the mass of body " + std::to_string(i) +
                  " must be finite and > 0 (got " + calder::detail::format_number(mass[i]) + ")");
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
// vectors as can be (at most kFloatTile bodies, so that all tasks cost about
// the same); a first round sums each stripe over itself (self_pairs), then
// the circle method's rounds pair every two stripes once, each stripe in one
// pair a round at most. Each stripe's sums take their pairs in round order,
// the same for any thread count.
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

// The tasks of the pair-once sum, in one global order: task k < P sums
// stripe k over itself; task P + r M + u is match u of round r (M matches a
// round; P stripes, one of them idle a round when P is odd). Threads claim
// the tasks in that order, each the next unclaimed one when it is free (a
// fast thread takes more of them than a slow or busy one), and no barrier
// holds the threads between rounds. Instead a task waits until its two
// stripes have finished their earlier tasks (done[s] counts them): the
// lowest unfinished task can always run, and each stripe's sums still take
// their pairs in round order, whichever thread runs them. The work is
// counted by share, task k in share k mod T (what thread k mod T would run
// if all ran alike): the same on any machine.
class StripeSchedule {
 public:
  explicit StripeSchedule(std::size_t stripes)
      : stripes_(stripes),
        players_(stripes + stripes % 2),
        done_(std::make_unique<std::atomic<std::uint32_t>[]>(stripes)) {
    for (std::size_t s = 0; s < stripes; ++s) done_[s].store(0, std::memory_order_relaxed);
  }
  std::size_t matches() const { return players_ / 2; }
  std::size_t tasks() const { return stripes_ + (players_ - 1) * matches(); }
  // Task k's stripes and round (a == b: a stripe over itself); a >= stripes: the idle match.
  struct Task {
    std::size_t a;
    std::size_t b;
    std::size_t round;
  };
  Task task(std::size_t k) const {
    if (k < stripes_) return {k, k, 0};
    const std::size_t r = (k - stripes_) / matches();
    const std::size_t u = (k - stripes_) % matches();
    const std::size_t circle = players_ - 1;
    const std::size_t a = u == 0 ? players_ - 1 : (r + u) % circle;
    const std::size_t b = u == 0 ? r : (r + circle - u) % circle;
    return {a, b, r};
  }
  // The tasks stripe s has finished before its match of round r (its own
  // sum, the rounds before; with P odd, stripe s is idle in round s).
  std::uint32_t before(std::size_t s, std::size_t r) const {
    const std::size_t idle = stripes_ % 2 == 1 && s < r ? 1 : 0;
    return static_cast<std::uint32_t>(1 + r - idle);
  }
  void wait(std::size_t s, std::uint32_t count) const {
    for (int spin = 0; done_[s].load(std::memory_order_acquire) < count; ++spin) {
      if (spin >= 64) std::this_thread::yield();
    }
  }
  void finish(std::size_t s) { done_[s].fetch_add(1, std::memory_order_release); }

 private:
  std::size_t stripes_;
  std::size_t players_;
  std::unique_ptr<std::atomic<std::uint32_t>[]> done_;
};

template <typename T, typename OneSided, typename Pairs>
void sum_by_stripes(const Bodies<T>& bodies, std::size_t lanes, int threads, double* sum_x,
                    double* sum_y, std::uint64_t* work, OneSided one_sided, Pairs pairs) {
  const std::size_t stripes = (bodies.n + kFloatTile - 1) / kFloatTile;
  const std::size_t vectors = bodies.n / lanes;  // (bodies.n: whole vectors)
  // Stripe k: vectors k V / P to (k + 1) V / P (at most kFloatTile bodies:
  // bodies.n <= P kFloatTile).
  const auto first = [&](std::size_t k) { return k * vectors / stripes * lanes; };
  const auto stripe = [&](std::size_t k) {
    return bodies.slice(first(k), first(k + 1) - first(k));
  };
  StripeSchedule schedule(stripes);
  std::vector<std::uint64_t> task_pairs(schedule.tasks(), 0);
  std::atomic<std::size_t> next_task{0};
  std::size_t team = 1;
#if defined(_OPENMP)
#pragma omp parallel num_threads(threads)
#endif
  {
    const auto [t, nt] = this_thread();
    if (t == 0) team = nt;
    for (std::size_t k = next_task.fetch_add(1, std::memory_order_relaxed); k < schedule.tasks();
         k = next_task.fetch_add(1, std::memory_order_relaxed)) {
      const StripeSchedule::Task task = schedule.task(k);
      if (task.a >= stripes || task.b >= stripes) continue;  // the idle match
      const std::size_t na = first(task.a + 1) - first(task.a);
      const std::size_t nb = first(task.b + 1) - first(task.b);
      if (task.a == task.b) {
        self_pairs(stripe(task.a), lanes, sum_x + first(task.a), sum_y + first(task.a), one_sided,
                   pairs);
        task_pairs[k] = na * na;
      } else {
        schedule.wait(task.a, schedule.before(task.a, task.round));
        schedule.wait(task.b, schedule.before(task.b, task.round));
        pairs(stripe(task.a), stripe(task.b), sum_x + first(task.a), sum_y + first(task.a),
              sum_x + first(task.b), sum_y + first(task.b));
        schedule.finish(task.b);
        task_pairs[k] = 2 * na * nb;
      }
      schedule.finish(task.a);
    }
  }
  for (std::size_t s = 0; s < team; ++s) work[s] = 0;
  for (std::size_t k = 0; k < task_pairs.size(); ++k) work[k % team] += task_pairs[k];
  (void)threads;
}

// The direct kernels' sums of `bodies` (n of them, n_pad in its arrays:
// whole vectors of `lanes`, massless after n) into (sum_x, sum_y): each pair once from
// kStripesForPairs stripes on (sum_by_stripes), else each target's sum over
// all sources, blocks of `block` targets in static slices. work[t]: the
// pairs of thread t's share (each pair evaluated once counts 2).
template <typename T, typename OneSided, typename Pairs>
void direct_sums(Bodies<T> bodies, std::size_t n_pad, std::size_t lanes, std::size_t block,
                 int threads, double* sum_x, double* sum_y, std::uint64_t* work, OneSided one_sided,
                 Pairs pairs) {
  const std::size_t n = bodies.n;
  if (sums_pairs_once(n)) {
    bodies.n = n_pad;
    sum_by_stripes(bodies, lanes, threads, sum_x, sum_y, work, one_sided, pairs);
    return;
  }
  const std::size_t blocks = (n + block - 1) / block;
#if defined(_OPENMP)
#pragma omp parallel num_threads(threads)
#endif
  {
    const auto [t, nt] = this_thread();
    std::uint64_t pair_count = 0;
    for (std::size_t b = blocks * t / nt; b < blocks * (t + 1) / nt; ++b) {
      const std::size_t i0 = b * block;
      const std::size_t targets = std::min(block, n - i0);
      one_sided(bodies.slice(i0, targets), bodies, sum_x + i0, sum_y + i0);
      pair_count += targets * n;
    }
    work[t] = pair_count;
  }
  (void)threads;
}

// Bodies in float32 for the direct kernels, count of them (padded with body
// 0's position and no mass): two-float positions in the frame (hi = the
// nearest float, lo = the rest, exact), scaled masses.
struct FloatBodies {
  std::vector<float> x, y, x_lo, y_lo, m;
  std::size_t n;
  FloatBodies(std::span<const double> px, std::span<const double> py, std::span<const double> mass,
              std::size_t count, const FloatFrame& frame)
      : x(count), y(count), x_lo(count), y_lo(count), m(count, 0.0f), n(px.size()) {
    for (std::size_t i = 0; i < count; ++i) {
      const double u = (px[i < n ? i : 0] - frame.cx) * frame.scale;
      const double v = (py[i < n ? i : 0] - frame.cy) * frame.scale;
      x[i] = static_cast<float>(u);
      y[i] = static_cast<float>(v);
      x_lo[i] = static_cast<float>(u - static_cast<double>(x[i]));
      y_lo[i] = static_cast<float>(v - static_cast<double>(y[i]));
      if (i < n) m[i] = static_cast<float>(mass[i] * frame.mass_scale);
    }
  }
  Bodies<float> bodies() const {
    Bodies<float> b{x.data(), y.data(), m.data(), n};
    b.x_lo = x_lo.data();
    b.y_lo = y_lo.data();
    return b;
  }
};

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
                          const Options& options, DirectStats* stats) {
  detail::validate("nbody::direct_accelerations", x, y, mass, ax, ay, options);
  if (stats != nullptr) *stats = DirectStats{x.size(), false, {}};
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
  std::vector<std::uint64_t> work(static_cast<std::size_t>(threads), 0);
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
        bodies, n_pad, lanes, k.block64, threads, sum_x.data(), sum_y.data(), work.data(),
        [&](const detail::Bodies<double>& t, const detail::Bodies<double>& s, double* out_x,
            double* out_y) { k.accumulate64(t.x, t.y, t.n, s, p, out_x, out_y); },
        [&](const detail::Bodies<double>& a, const detail::Bodies<double>& b, double* a_x,
            double* a_y, double* b_x, double* b_y) { k.pairs64(a, b, p, a_x, a_y, b_x, b_y); });
  } else {
    const detail::FloatFrame frame = detail::float_frame(x, y, mass, options.G);
    const detail::LawParams p = detail::law_params(options, frame);
    const detail::FloatBodies f(x, y, mass, n_pad, frame);
    const detail::Bodies<float> bodies = f.bodies();
    detail::direct_sums(
        bodies, n_pad, lanes, k.block32, threads, sum_x.data(), sum_y.data(), work.data(),
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
  if (stats != nullptr) {
    stats->pairs_once = pairs_once;
    stats->work.push_back(ThreadWork{"pairs", "pairs", std::move(work)});
  }
}

double ThreadWork::imbalance() const {
  if (per_thread.empty()) return 0.0;
  double total = 0.0;
  double most = 0.0;
  for (const std::uint64_t w : per_thread) {
    total += static_cast<double>(w);
    most = std::max(most, static_cast<double>(w));
  }
  if (total <= 0.0) return 0.0;
  return most / (total / static_cast<double>(per_thread.size())) - 1.0;
}

const char* kernel_name() { return detail::kernels().name; }
int kernel_target_block() { return static_cast<int>(detail::kernels().target_block64); }

int max_threads() { return detail::thread_count(Options{}); }

}  // namespace calder::nbody
