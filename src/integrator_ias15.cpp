// SPDX-License-Identifier: MIT
// IAS15, the adaptive 15th-order integrator (calder/adaptive.hpp): Gauss-Radau
// predictor-corrector steps (Everhart 1985; Rein & Spiegel 2015, MNRAS 446,
// 1424) with the step criterion of Pham, Rein & Spiegel (2024, MNRAS 527).
//
// Over an internal step of length h, with s = (t - t0) / h in [0, 1], the
// acceleration of each coordinate is the polynomial
//   a(s) = a0 + b0 s + b1 s^2 + ... + b6 s^7,
// written through the Gauss-Radau nodes s_1..s_7 as
//   a(s) = a0 + g0 s + g1 s (s - s_1) + ... + g6 s (s - s_1) ... (s - s_6).
// Each iteration evaluates the forces at the seven nodes, at positions and
// velocities integrated from the current b, and corrects the g (divided
// differences) and so the b; when the last coefficient stops changing, the
// step integrates the polynomial twice to s = 1.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "calder/detmath.hpp"
#include "calder/error.hpp"
#include "calder/world.hpp"

namespace calder {

namespace {

constexpr std::size_t kCoefficients = 7;

// The Gauss-Radau nodes on [0, 1] with 0 fixed: 0 and the roots of
// (P_7 + P_8)(2 s - 1) / (2 s), P_n the Legendre polynomials (Everhart 1985);
// computed to 50 digits with mpmath, as are the tables below.
constexpr double kNode[8] = {0.0,
                             0.05626256053692214646565219,
                             0.1802406917368923649875799,
                             0.3526247171131696373739078,
                             0.5471536263305553830014486,
                             0.7342101772154105315232106,
                             0.8853209468390957680903598,
                             0.9775206135612875018911745};

// kNodeDifference[n][i] = s_n - s_i (i < n), each rounded once.
constexpr double kNodeDifference[8][7] = {
    {},
    {0.05626256053692214646565219},
    {0.1802406917368923649875799, 0.1239781311999702185219278},
    {0.3526247171131696373739078, 0.2963621565762474909082556, 0.1723840253762772723863278},
    {0.5471536263305553830014486, 0.4908910657936332365357964, 0.3669129345936630180138686,
     0.1945289092173857456275408},
    {0.7342101772154105315232106, 0.6779476166784883850575584, 0.5539694854785181665356307,
     0.3815854601022408941493028, 0.1870565508848551485217621},
    {0.8853209468390957680903598, 0.8290583863021736216247076, 0.7050802551022034031027798,
     0.532696229725926130716452, 0.3381673205085403850889112, 0.1511107696236852365671492},
    {0.9775206135612875018911745, 0.9212580530243653554255223, 0.7972799218243951369035946,
     0.6248958964481178645172667, 0.4303669872307321188897259, 0.2433104363458769703679639,
     0.09219966672219173380081474},
};

// The Newton polynomial s (s - s_1) ... (s - s_j) in powers of s:
// kNewtonInPowers[j][k] is its coefficient of s^(k + 1), so that
// b_k = sum over j >= k of kNewtonInPowers[j][k] g_j.
constexpr double kNewtonInPowers[7][7] = {
    {1.0},
    {-0.05626256053692214646565219, 1.0},
    {0.0101408028300636299864818, -0.2365032522738145114532321, 1.0},
    {-0.003575897729251617594934459, 0.09353769525946206589574846, -0.5891279693869841488271399,
     1.0},
    {0.001956565409947221076900567, -0.05475538688906868644080843, 0.4158812000823068616886219,
     -1.136281595717539531828588, 1.0},
    {-0.001436530236370891542445955, 0.04215852772126870770729735, -0.3600995965020568122897665,
     1.250150711840691025850544, -1.870491772932950063351799, 1.0},
    {0.001271790309026867749294312, -0.03876035791590677036990462, 0.3609622434528459832253398,
     -1.466884208400426964370155, 2.906136259308429301423791, -2.755812719772045831442159, 1.0},
};

// The inverse: s^(k + 1) in Newton polynomials, kPowersInNewton[j][k] the
// weight of polynomial j in s^(k + 1) (k >= j), so that
// g_j = sum over k >= j of kPowersInNewton[j][k] b_k.
constexpr double kPowersInNewton[7][7] = {
    {1.0, 0.05626256053692214646565219, 0.00316547571817082924999048,
     0.0001780977692217433881125279, 0.00001002023652232912720956722,
     0.000000563764163931820761038385, 0.00000003171881540176136647585482},
    {0.0, 1.0, 0.2365032522738145114532321, 0.04579298550602791889545387,
     0.008431857153525701544499974, 0.001529784002500465818949008, 0.0002762930909826476593130226},
    {0.0, 0.0, 1.0, 0.5891279693869841488271399, 0.2535340690545692665214616,
     0.09783423653244400536536484, 0.03602855398373645960038707},
    {0.0, 0.0, 0.0, 1.0, 1.136281595717539531828588, 0.8752546646840910912297246,
     0.5767330002770787313544596},
    {0.0, 0.0, 0.0, 0.0, 1.0, 1.870491772932950063351799, 2.24858876076915979339269},
    {0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 2.755812719772045831442159},
    {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0},
};

// Binomial coefficients C(k + 1, m + 1): the polynomial shifted to start at
// the end of the last step (the predictor of the next step's b).
constexpr double kShift[7][7] = {
    {1, 2, 3, 4, 5, 6, 7},   {0, 1, 3, 6, 10, 15, 21}, {0, 0, 1, 4, 10, 20, 35},
    {0, 0, 0, 1, 5, 15, 35}, {0, 0, 0, 0, 1, 6, 21},   {0, 0, 0, 0, 0, 1, 7},
    {0, 0, 0, 0, 0, 0, 1},
};

// A step whose criterion asks for less than this fraction of it is tried
// again; the next step grows by at most its inverse (Rein & Spiegel 2015).
constexpr double kSafety = 0.25;
constexpr int kMaxIterations = 12;
// A frame that needs more internal steps than this is an error, not a hang
// (a dt of 1e300 over a bound orbit).
constexpr std::int64_t kMaxStepsPerFrame = 100'000;
// The predictor-corrector has converged when the last coefficient changes
// by less than this, relative to the largest acceleration.
constexpr double kConverged = 1e-16;
// Beyond this ratio of the next step to the last, the shifted polynomial
// predicts nothing useful: the next step starts from zero coefficients.
constexpr double kMaxPredictionRatio = 20.0;

// Kahan's compensated sum: sum - compensation is the sum of every term.
inline void add_compensated(double& sum, double& compensation, double term) {
  const double y = term - compensation;
  const double t = sum + y;
  compensation = (t - sum) - y;
  sum = t;
}

bool normal(double v) { return std::isnormal(v); }

// The working arrays of one frame, 2n coordinates each (x of every body, then y).
struct Work {
  std::size_t size = 0;               // 2n
  std::span<double> x0, v0, a0;       // the step's start
  std::span<double> x, v, a;          // at a node
  std::span<double> b, g, predicted;  // 7 x 2n each
  double* block(std::span<double> s, std::size_t j) const { return s.data() + j * size; }
};

Work carve(std::vector<double>& scratch, std::size_t size) {
  scratch.assign(size * (6 + 3 * kCoefficients), 0.0);
  double* p = scratch.data();
  const auto take = [&p](std::size_t n) {
    std::span<double> s(p, n);
    p += n;
    return s;
  };
  Work w;
  w.size = size;
  w.x0 = take(size);
  w.v0 = take(size);
  w.a0 = take(size);
  w.x = take(size);
  w.v = take(size);
  w.a = take(size);
  w.b = take(size * kCoefficients);
  w.g = take(size * kCoefficients);
  w.predicted = take(size * kCoefficients);
  return w;
}

// The next step's b from the last step's (shifted to start at its end and
// scaled to a step of h), plus the correction the last prediction needed.
void predict(const AdaptiveState& s, const Work& w, double h) {
  const double q = s.last_step > 0.0 ? h / s.last_step : 0.0;
  if (s.coefficients.size() != w.size * kCoefficients || !(q > 0.0) || q > kMaxPredictionRatio) {
    std::fill(w.b.begin(), w.b.end(), 0.0);
    std::fill(w.predicted.begin(), w.predicted.end(), 0.0);
    return;
  }
  double qm = 1.0;
  for (std::size_t m = 0; m < kCoefficients; ++m) {
    qm *= q;
    double* e = w.block(w.predicted, m);
    double* b = w.block(w.b, m);
    const double* c = s.correction.data() + m * w.size;
    for (std::size_t k = 0; k < w.size; ++k) {
      double sum = 0.0;
      for (std::size_t j = kCoefficients; j-- > m;) {
        sum += kShift[m][j] * s.coefficients[j * w.size + k];
      }
      e[k] = qm * sum;
      b[k] = e[k] + c[k];
    }
  }
}

// g from b (kPowersInNewton).
void newton_from_powers(const Work& w) {
  for (std::size_t j = 0; j < kCoefficients; ++j) {
    double* g = w.block(w.g, j);
    for (std::size_t k = 0; k < w.size; ++k) {
      double sum = 0.0;
      for (std::size_t m = kCoefficients; m-- > j;)
        sum += kPowersInNewton[j][m] * w.b[m * w.size + k];
      g[k] = sum;
    }
  }
}

// Positions and velocities at node n of a step of length h, from the b.
void at_node(const Work& w, std::span<const double> cx, std::span<const double> cv, std::size_t n,
             double h) {
  const double s = kNode[n];
  const double hs = h * s;
  const std::size_t m = w.size;
  const double* b = w.b.data();
  for (std::size_t k = 0; k < m; ++k) {
    const double b0 = b[k], b1 = b[m + k], b2 = b[2 * m + k], b3 = b[3 * m + k];
    const double b4 = b[4 * m + k], b5 = b[5 * m + k], b6 = b[6 * m + k];
    const double dx =
        hs * (w.v0[k] +
              hs * (w.a0[k] / 2.0 +
                    s * (b0 / 6.0 +
                         s * (b1 / 12.0 +
                              s * (b2 / 20.0 +
                                   s * (b3 / 30.0 +
                                        s * (b4 / 42.0 + s * (b5 / 56.0 + s * b6 / 72.0))))))));
    const double dv =
        hs * (w.a0[k] +
              s * (b0 / 2.0 +
                   s * (b1 / 3.0 +
                        s * (b2 / 4.0 +
                             s * (b3 / 5.0 + s * (b4 / 6.0 + s * (b5 / 7.0 + s * b6 / 8.0)))))));
    w.x[k] = w.x0[k] + (dx - cx[k]);
    w.v[k] = w.v0[k] + (dv - cv[k]);
  }
}

// The new g_(n-1) from the acceleration at node n, and the b it changes.
// Returns the largest change of b6 when n is the last node (0 otherwise),
// and the largest acceleration there in max_a.
double correct(const Work& w, std::size_t n, double& max_a) {
  const std::size_t j = n - 1;
  const std::size_t m = w.size;
  double max_change = 0.0;
  for (std::size_t k = 0; k < m; ++k) {
    double gk = (w.a[k] - w.a0[k]) / kNodeDifference[n][0];
    for (std::size_t i = 0; i < j; ++i) gk = (gk - w.g[i * m + k]) / kNodeDifference[n][i + 1];
    const double change = gk - w.g[j * m + k];
    w.g[j * m + k] = gk;
    for (std::size_t i = 0; i < j; ++i) w.b[i * m + k] += kNewtonInPowers[j][i] * change;
    w.b[j * m + k] += change;
    if (n == 7) {
      const double a = std::fabs(w.a[k]);
      const double c = std::fabs(change);
      if (normal(a) && a > max_a) max_a = a;
      if (normal(c) && c > max_change) max_change = c;
    }
  }
  return max_change;
}

// Pham, Rein & Spiegel (2024): for each body, from its acceleration at the
// step's end (y2), jerk (y3) and snap (y4) in units of the step, the timescale
// sqrt(2 y2 / (y3 + sqrt(y2 y4))); the next step is the smallest of them times
// the step, times (5040 tolerance)^(1/7). A body feeling no force is skipped.
double proposed_step(const Work& w, std::size_t bodies, double h, double factor) {
  double min_timescale2 = std::numeric_limits<double>::infinity();
  const std::size_t m = w.size;
  const double* b = w.b.data();
  for (std::size_t i = 0; i < bodies; ++i) {
    double a0 = 0.0, y2 = 0.0, y3 = 0.0, y4 = 0.0;
    for (const std::size_t k : {i, i + bodies}) {
      const double b0 = b[k], b1 = b[m + k], b2 = b[2 * m + k], b3 = b[3 * m + k];
      const double b4 = b[4 * m + k], b5 = b[5 * m + k], b6 = b[6 * m + k];
      a0 += w.a0[k] * w.a0[k];
      const double end = w.a0[k] + b0 + b1 + b2 + b3 + b4 + b5 + b6;
      const double jerk = b0 + 2.0 * b1 + 3.0 * b2 + 4.0 * b3 + 5.0 * b4 + 6.0 * b5 + 7.0 * b6;
      const double snap = 2.0 * b1 + 6.0 * b2 + 12.0 * b3 + 20.0 * b4 + 30.0 * b5 + 42.0 * b6;
      y2 += end * end;
      y3 += jerk * jerk;
      y4 += snap * snap;
    }
    if (!normal(a0)) continue;
    const double timescale2 = 2.0 * y2 / (y3 + std::sqrt(y2 * y4));
    if (normal(timescale2) && timescale2 < min_timescale2) min_timescale2 = timescale2;
  }
  if (!normal(min_timescale2)) return h / kSafety;
  return std::sqrt(min_timescale2) * h * factor;
}

// The step's end: x0 += v0 h + h^2 (a0 / 2 + b0 / 6 + ... + b6 / 72) and
// v0 += h (a0 + b0 / 2 + ... + b6 / 8), term by term, smallest first, each
// into a compensated sum.
void finish_step(const Work& w, std::span<double> cx, std::span<double> cv, double h) {
  constexpr double kPositionDivisor[7] = {6.0, 12.0, 20.0, 30.0, 42.0, 56.0, 72.0};
  const std::size_t m = w.size;
  for (std::size_t k = 0; k < m; ++k) {
    for (std::size_t j = kCoefficients; j-- > 0;) {
      add_compensated(w.x0[k], cx[k], w.b[j * m + k] / kPositionDivisor[j] * h * h);
    }
    add_compensated(w.x0[k], cx[k], w.a0[k] / 2.0 * h * h);
    add_compensated(w.x0[k], cx[k], w.v0[k] * h);
    for (std::size_t j = kCoefficients; j-- > 0;) {
      add_compensated(w.v0[k], cv[k], w.b[j * m + k] / static_cast<double>(j + 2) * h);
    }
    add_compensated(w.v0[k], cv[k], w.a0[k] * h);
  }
}

double closest_pair(std::span<const double> x, std::size_t n) {
  double best2 = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const double dx = x[j] - x[i];
      const double dy = x[n + j] - x[n + i];
      best2 = std::min(best2, dx * dx + dy * dy);
    }
  }
  return std::sqrt(best2);
}

// One try of a step of h from time t: the predictor-corrector iterations,
// then the step the criterion proposes.
template <class Evaluate>
double try_step(AdaptiveState& s, const Work& w, std::size_t n, double h, double t, double factor,
                const Evaluate& evaluate) {
  predict(s, w, h);
  newton_from_powers(w);
  double error = std::numeric_limits<double>::infinity();
  double last_error = error;
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    if (error < kConverged || (iteration > 2 && last_error <= error)) break;
    last_error = error;
    double max_change = 0.0;
    double max_a = 0.0;
    for (std::size_t node = 1; node <= 7; ++node) {
      at_node(w, s.position_compensation, s.velocity_compensation, node, h);
      evaluate(w.x, w.v, w.a, t + h * kNode[node]);
      max_change = correct(w, node, max_a);
    }
    error = max_a > 0.0 ? max_change / max_a : 0.0;
    ++s.stats.iterations;
  }
  // A step far too long for the forces (the first one, which tries the
  // whole frame) can send the iterations off to infinity: try a sixteenth.
  for (const double v : w.b) {
    if (!std::isfinite(v)) return kSafety * kSafety * h;
  }
  return proposed_step(w, n, h, factor);
}

// The step of h from time t is taken: the state moves to its end, and what
// the next step needs (its length, the polynomial) and the counts are kept.
void accept_step(AdaptiveState& s, const Work& w, std::size_t n, double h, double natural,
                 double proposed, double t) {
  finish_step(w, s.position_compensation, s.velocity_compensation, h);
  // The frame's end may have shortened the step: grow from the natural one.
  const double grown = (h < natural ? natural : h) / kSafety;
  s.next_step = std::min(proposed, grown);
  s.last_step = h;
  s.coefficients.assign(w.b.begin(), w.b.end());
  s.correction.resize(w.b.size());
  for (std::size_t k = 0; k < w.b.size(); ++k) s.correction[k] = w.b[k] - w.predicted[k];
  AdaptiveStats& stats = s.stats;
  ++stats.steps;
  stats.smallest_step = std::min(stats.smallest_step, h);
  if (n >= 2 && n <= kClosestApproachBodies) {
    const double d = closest_pair(w.x0, n);
    if (d < stats.closest_approach) {
      stats.closest_approach = d;
      stats.closest_approach_time = t + h;
    }
  }
}

void reset_carried(AdaptiveState& s, std::size_t size, bool keep_step) {
  s.position_compensation.assign(size, 0.0);
  s.velocity_compensation.assign(size, 0.0);
  s.coefficients.clear();
  s.correction.clear();
  s.last_step = 0.0;
  if (!keep_step) s.next_step = 0.0;
}

}  // namespace

void World::step_ias15() {
  const std::size_t n = bodies_.x.size();
  const Boundary& boundary = def_.boundary;
  if (boundary.timing == BoundaryTiming::before_update) {
    for (std::size_t i = 0; i < n; ++i) boundary_one(i, boundary);
  }
  if (adaptive_.position_compensation.size() != 2 * n) reset_carried(adaptive_, 2 * n, false);
  // Forces applied by hand before the step hold for every internal step.
  std::vector<double> applied(bodies_.ax);
  applied.insert(applied.end(), bodies_.ay.begin(), bodies_.ay.end());
  ias15_substeps(def_.dt, std::span<const double>(applied).first(n),
                 std::span<const double>(applied).subspan(n));
  std::fill(bodies_.ax.begin(), bodies_.ax.end(), 0.0);
  std::fill(bodies_.ay.begin(), bodies_.ay.end(), 0.0);
  if (boundary.timing == BoundaryTiming::after_update && boundary.kind != BoundaryKind::none) {
    bool moved = false;
    for (std::size_t i = 0; i < n; ++i) {
      const double before[4] = {bodies_.x[i], bodies_.y[i], bodies_.vx[i], bodies_.vy[i]};
      boundary_one(i, boundary);
      moved = moved || before[0] != bodies_.x[i] || before[1] != bodies_.y[i] ||
              before[2] != bodies_.vx[i] || before[3] != bodies_.vy[i];
    }
    // A bounce or a wrap breaks the polynomial: start the next step afresh.
    if (moved) reset_carried(adaptive_, 2 * n, true);
  }
}

void World::ias15_substeps(double frame_dt, std::span<const double> applied_ax,
                           std::span<const double> applied_ay) {
  const std::size_t n = bodies_.x.size();
  Work w = carve(scratch_, 2 * n);
  std::copy(bodies_.x.begin(), bodies_.x.end(), w.x0.begin());
  std::copy(bodies_.y.begin(), bodies_.y.end(), w.x0.begin() + static_cast<std::ptrdiff_t>(n));
  std::copy(bodies_.vx.begin(), bodies_.vx.end(), w.v0.begin());
  std::copy(bodies_.vy.begin(), bodies_.vy.end(), w.v0.begin() + static_cast<std::ptrdiff_t>(n));
  AdaptiveState& s = adaptive_;
  AdaptiveStats& stats = s.stats;
  const double factor = math::pow(def_.tolerance * 5040.0, 1.0 / 7.0);

  // The accelerations at (x, v) and time t into a.
  const auto evaluate = [&](std::span<const double> x, std::span<const double> v,
                            std::span<double> a, double t) {
    std::copy(applied_ax.begin(), applied_ax.end(), a.begin());
    std::copy(applied_ay.begin(), applied_ay.end(), a.begin() + static_cast<std::ptrdiff_t>(n));
    BodyView view = bodies();
    view.x = x.first(n);
    view.y = x.subspan(n);
    view.vx = v.first(n);
    view.vy = v.subspan(n);
    accumulate_fields(context(view, t), 0, n, a.first(n), a.subspan(n));
    ++stats.force_evaluations;
  };
  const auto attempt = [&](double h, double t) {
    return try_step(s, w, n, h, t, factor, evaluate);
  };

  double tau = 0.0;  // into the frame
  for (std::int64_t taken = 0;; ++taken) {
    if (taken == kMaxStepsPerFrame) {
      throw RunError("World::step: ias15 needs more than " + std::to_string(kMaxStepsPerFrame) +
                     " internal steps for one frame of dt = " + detail::format_number(frame_dt) +
                     " (at time " + detail::format_number(time_ + tau) + "): use a smaller dt");
    }
    const double remaining = frame_dt - tau;
    const double natural = s.next_step > 0.0 ? s.next_step : frame_dt;
    double h = natural;
    bool last = false;
    if (h >= remaining) {
      h = remaining;
      last = true;
    } else if (2.0 * h > remaining) {
      h = remaining / 2.0;  // two equal steps to the frame's end rather than a sliver
    }
    const double t = time_ + tau;
    evaluate(w.x0, w.v0, w.a0, t);
    double proposed = attempt(h, t);
    // With no step carried over (the first), the frame's dt is only a guess:
    // take it only if the criterion accepts it whole.
    if (s.next_step == 0.0 && proposed < h) {
      ++stats.rejected;
      h = proposed;
      last = false;
      proposed = attempt(h, t);
    }
    while (proposed < kSafety * h) {
      ++stats.rejected;
      h = proposed;
      last = false;
      if (!(h > 0.0) || tau + h == tau) {
        throw RunError("World::step: the ias15 step fell to " + detail::format_number(h) +
                       " at time " + detail::format_number(t) +
                       " (a collision of point masses? soften the law)");
      }
      proposed = attempt(h, t);
    }
    accept_step(s, w, n, h, natural, proposed, t);
    if (last) break;
    tau += h;
  }
  std::copy(w.x0.begin(), w.x0.begin() + static_cast<std::ptrdiff_t>(n), bodies_.x.begin());
  std::copy(w.x0.begin() + static_cast<std::ptrdiff_t>(n), w.x0.end(), bodies_.y.begin());
  std::copy(w.v0.begin(), w.v0.begin() + static_cast<std::ptrdiff_t>(n), bodies_.vx.begin());
  std::copy(w.v0.begin() + static_cast<std::ptrdiff_t>(n), w.v0.end(), bodies_.vy.begin());
}

void World::advance_clock() {
  if (def_.integrator == Integrator::ias15) {
    add_compensated(time_, adaptive_.clock_compensation, def_.dt);
  } else {
    time_ += def_.dt;
  }
}

void World::set_tolerance(double tolerance) {
  detail::require_positive(tolerance, "World::set_tolerance", "tolerance");
  def_.tolerance = tolerance;
}

void World::restore_adaptive(const AdaptiveState& state) {
  const std::size_t size = 2 * body_count();
  const auto fits = [size](const std::vector<double>& v, std::size_t blocks, bool may_be_empty) {
    return v.size() == size * blocks || (may_be_empty && v.empty());
  };
  if (!fits(state.position_compensation, 1, true) || !fits(state.velocity_compensation, 1, true) ||
      state.position_compensation.size() != state.velocity_compensation.size() ||
      !fits(state.coefficients, kCoefficients, true) ||
      !fits(state.correction, kCoefficients, true) ||
      state.coefficients.size() != state.correction.size()) {
    throw InvalidArgument("World::restore_adaptive: the arrays don't fit " +
                          std::to_string(body_count()) + " bodies");
  }
  const char* where = "World::restore_adaptive";
  for (const double v :
       {state.next_step, state.last_step, state.clock_compensation, state.stats.smallest_step,
        state.stats.closest_approach, state.stats.closest_approach_time}) {
    if (std::isnan(v)) detail::require_finite(v, where, "a value");
  }
  if (state.next_step < 0.0 || state.last_step < 0.0 || !std::isfinite(state.next_step) ||
      !std::isfinite(state.last_step) || !std::isfinite(state.clock_compensation)) {
    throw InvalidArgument("World::restore_adaptive: steps must be finite and >= 0");
  }
  for (const std::vector<double>* v : {&state.position_compensation, &state.velocity_compensation,
                                       &state.coefficients, &state.correction}) {
    for (const double x : *v) detail::require_finite(x, where, "an array value");
  }
  adaptive_ = state;
}

}  // namespace calder
