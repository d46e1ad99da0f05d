// SPDX-License-Identifier: MIT
// calder::movers: the tile kernels (see plan.hpp), as templates over the
// precision R and the arithmetic: kBook = true repeats the book's operations
// in its order (World's plain loops, calder/forces.hpp), kBook = false is the
// fast form of the same physics.
//
// Included by kernels_book.cpp (compiled with -ffp-contract=off: no fused
// multiply-adds, so the book kernels give the plain loops' bits) and
// kernels_fast.cpp (-ffp-contract=fast), each compiled once per instruction
// set. A tile is cut into blocks of kBlockVectors vector registers (GCC
// vector extensions); a block's state stays in registers through every step
// of the batch, so the steps cost arithmetic, not memory traffic. Conditions
// are computed for every lane and select results, and lanes that must not
// change add exactly +0 or keep their old value. (A sum that is exactly zero is +0 in IEEE
// round-to-nearest unless both terms are -0, so accelerations, which start at +0, are never -0 and
// adding +0 leaves them unchanged: the book's skipped branches and the kernels' selects agree bit
// for bit.)
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "../integrate.hpp"
#include "calder/movers.hpp"
#include "plan.hpp"

namespace calder::movers::detail {
// Internal linkage: each kernel file has its own copies, built with its own
// flags (see integrate.hpp).
namespace {

// One vector register of R: 64 bytes with AVX-512, 32 with AVX, 16 otherwise.
#if defined(__AVX512F__)
constexpr std::size_t kVectorBytes = 64;
#elif defined(__AVX__)
constexpr std::size_t kVectorBytes = 32;
#else
constexpr std::size_t kVectorBytes = 16;
#endif

template <class R>
struct Simd;
template <>
struct Simd<double> {
  using V = double __attribute__((vector_size(kVectorBytes)));
  using M = decltype(V{} < V{});  // comparison results: 0 or all ones per lane
};
template <>
struct Simd<float> {
  using V = float __attribute__((vector_size(kVectorBytes)));
  using M = decltype(V{} < V{});
};

// Vectors per block: a block's state stays in registers through all the
// steps of a batch, and S independent vectors hide the latency of each
// step's chain (sqrt, division) behind one another.
constexpr int kBlockVectors = 4;

template <class R>
struct Block {
  using V = typename Simd<R>::V;
  static constexpr int kLanes = static_cast<int>(kVectorBytes / sizeof(R));
  static constexpr int kBodies = kBlockVectors * kLanes;
  V x[kBlockVectors], y[kBlockVectors], vx[kBlockVectors], vy[kBlockVectors];
  V ax[kBlockVectors], ay[kBlockVectors];
  V m[kBlockVectors], inv_m[kBlockVectors], r[kBlockVectors], area[kBlockVectors],
      mu[kBlockVectors];
};

// Lane by lane; GCC turns the loop into one vsqrtp* (with -fno-math-errno).
template <class V>
[[gnu::always_inline]] inline V vsqrt(V v) {
  constexpr int lanes = static_cast<int>(sizeof(V) / sizeof(v[0]));
  V out = v;
  for (int l = 0; l < lanes; ++l) out[l] = std::sqrt(v[l]);
  return out;
}

template <class V, class R>
[[gnu::always_inline]] inline V splat(R value) {
  return V{} + value;
}

// Op's parameters in the kernel's precision.
template <class R>
struct Params {
  R fx, fy, c, normal, x_min, x_max, y_min, y_max, tolerance, px, py, gm, G, mass, lo, hi, eps,
      margin, reach;
  bool never_reverse, masses_first;
  Edge surface;
  AttractorLaw law;

  explicit Params(const Op& op)
      : fx(R(op.fx)),
        fy(R(op.fy)),
        c(R(op.c)),
        normal(R(op.normal)),
        x_min(R(op.x_min)),
        x_max(R(op.x_max)),
        y_min(R(op.y_min)),
        y_max(R(op.y_max)),
        tolerance(R(op.tolerance)),
        px(R(op.px)),
        py(R(op.py)),
        gm(R(op.G * op.mass)),
        G(R(op.G)),
        mass(R(op.mass)),
        lo(R(op.lo)),
        hi(R(op.hi)),
        eps(R(op.softening)),
        margin(R(op.margin)),
        reach(R(op.reach)),
        never_reverse(op.never_reverse),
        masses_first(op.masses_first),
        surface(op.surface),
        law(op.law) {}
};

// acceleration += force / mass (book) or force * (1 / mass) (fast), in the
// lanes where apply is set.
template <class R, bool kBook, class V, class M>
[[gnu::always_inline]] inline void add_force(Block<R>& b, int s, M apply, V fx, V fy) {
  V ax, ay;
  if constexpr (kBook) {
    ax = b.ax[s] + fx / b.m[s];
    ay = b.ay[s] + fy / b.m[s];
  } else {
    ax = b.ax[s] + fx * b.inv_m[s];
    ay = b.ay[s] + fy * b.inv_m[s];
  }
  b.ax[s] = apply ? ax : b.ax[s];
  b.ay[s] = apply ? ay : b.ay[s];
}

// Vec2::limit(max) on (fx, fy): if |f|^2 > max^2, f / |f| * max.
template <class V>
[[gnu::always_inline]] inline void limit(V& fx, V& fy, V max) {
  const V m_sq = fx * fx + fy * fy;
  const V len = vsqrt(m_sq);
  const auto over = m_sq > max * max;
  fx = over ? fx / len * max : fx;
  fy = over ? fy / len * max : fy;
}

template <class R, bool kBook>
void op_uniform(Block<R>& b, R fx, R fy) {
  using V = typename Simd<R>::V;
  using M = typename Simd<R>::M;
  for (int s = 0; s < kBlockVectors; ++s) {
    add_force<R, kBook>(b, s, ~M{}, splat<V>(fx), splat<V>(fy));
  }
}

template <class R, bool kBook>
void op_gravity_scaled(Block<R>& b, R gx, R gy) {
  for (int s = 0; s < kBlockVectors; ++s) {
    if constexpr (kBook) {
      // p5.Vector.mult(gravity, mass), then applyForce divides by mass.
      b.ax[s] += gx * b.m[s] / b.m[s];
      b.ay[s] += gy * b.m[s] / b.m[s];
    } else {
      b.ax[s] += gx;
      b.ay[s] += gy;
    }
  }
}

// Quadratic drag -c |v| v area, where strictly inside the op's region.
template <class R, bool kBook, bool kNeverReverse>
void op_drag(Block<R>& b, const Params<R>& p, R dt) {
  using V = typename Simd<R>::V;
  for (int s = 0; s < kBlockVectors; ++s) {
    const V vx = b.vx[s];
    const V vy = b.vy[s];
    const auto inside =
        (b.x[s] > p.x_min) & (b.x[s] < p.x_max) & (b.y[s] > p.y_min) & (b.y[s] < p.y_max);
    const V speed = vsqrt(vx * vx + vy * vy);
    if constexpr (kBook) {
      // calder::drag: magnitude c * speed * speed * area; -v set to it
      // (normalize multiplies by 1 / |v| unless |v| = 0).
      const V magnitude = p.c * speed * speed * b.area[s];
      const V inv = R(1) / (speed != R(0) ? speed : splat<V>(R(1)));
      V fx = -vx * inv * magnitude;
      V fy = -vy * inv * magnitude;
      if constexpr (kNeverReverse) limit(fx, fy, b.m[s] * speed / dt);
      add_force<R, true>(b, s, inside, fx, fy);
    } else {
      // a = -k v with k = c area |v| / m; never reversing: k dt <= 1.
      V k = p.c * b.area[s] * speed * b.inv_m[s];
      if constexpr (kNeverReverse) k = k < R(1) / dt ? k : splat<V>(R(1) / dt);
      b.ax[s] = inside ? b.ax[s] - k * vx : b.ax[s];
      b.ay[s] = inside ? b.ay[s] - k * vy : b.ay[s];
    }
  }
}

// Kinetic friction -mu N v-hat on bodies touching the op's surface.
template <class R, bool kBook, bool kNeverReverse>
void op_friction(Block<R>& b, const Params<R>& p, R width, R height, R dt) {
  using V = typename Simd<R>::V;
  for (int s = 0; s < kBlockVectors; ++s) {
    const V vx = b.vx[s];
    const V vy = b.vy[s];
    const V r = b.r[s];
    // calder::touches_edge, term by term.
    typename Simd<R>::M touching{};
    switch (p.surface) {
      case Edge::left:
        touching = b.x[s] < r + p.tolerance;
        break;
      case Edge::right:
        touching = b.x[s] > width - r - p.tolerance;
        break;
      case Edge::top:
        touching = b.y[s] < r + p.tolerance;
        break;
      case Edge::bottom:
        touching = b.y[s] > height - r - p.tolerance;
        break;
    }
    const V own = b.mu[s];
    const V mu = own != own ? splat<V>(p.c) : own;  // NaN: no coefficient of its own
    const V speed = vsqrt(vx * vx + vy * vy);
    if constexpr (kBook) {
      const V magnitude = mu * p.normal;
      const V inv = R(1) / (speed != R(0) ? speed : splat<V>(R(1)));
      V fx = -vx * inv * magnitude;
      V fy = -vy * inv * magnitude;
      if constexpr (kNeverReverse) limit(fx, fy, b.m[s] * speed / dt);
      add_force<R, true>(b, s, touching, fx, fy);
    } else {
      const V moving = speed != R(0) ? speed : splat<V>(R(1));
      V k = speed != R(0) ? mu * p.normal * b.inv_m[s] / moving : splat<V>(R(0));
      if constexpr (kNeverReverse) k = k < R(1) / dt ? k : splat<V>(R(1) / dt);
      b.ax[s] = touching ? b.ax[s] - k * vx : b.ax[s];
      b.ay[s] = touching ? b.ay[s] - k * vy : b.ay[s];
    }
  }
}

// A fixed attractor at (px, py) of mass M: calder::attraction(source =
// attractor, target = body) for the inverse-square laws.
template <class R, bool kBook, AttractorLaw kLaw, bool kSoftened>
void op_attractor(Block<R>& b, const Params<R>& p) {
  using V = typename Simd<R>::V;
  using M = typename Simd<R>::M;
  for (int s = 0; s < kBlockVectors; ++s) {
    const V rx = p.px - b.x[s];
    const V ry = p.py - b.y[s];
    const V d_sq = rx * rx + ry * ry;
    const V d = vsqrt(d_sq);
    if constexpr (kBook) {
      const V m = b.m[s];
      // strength_of: G * M * m, or G * (M * m), over the denominator.
      const V numerator = p.masses_first ? p.G * (p.mass * m) : p.G * p.mass * m;
      V strength;
      M apply = ~M{};
      if constexpr (kLaw == AttractorLaw::clamp_distance) {
        V dc = d < p.hi ? d : splat<V>(p.hi);  // constrain(d, lo, hi) = max(min(d, hi), lo)
        dc = dc > p.lo ? dc : splat<V>(p.lo);
        strength = numerator / (dc * dc);
      } else if constexpr (kLaw == AttractorLaw::clamp_squared) {
        V q = d_sq < p.hi ? d_sq : splat<V>(p.hi);
        q = q > p.lo ? q : splat<V>(p.lo);
        strength = numerator / q;
      } else {
        apply = d_sq != R(0);  // coincident: no direction, no force
        if constexpr (!kSoftened) {
          strength = numerator / d_sq;
        } else {
          const V s_sq = d_sq + p.eps * p.eps;
          strength = numerator / (s_sq * vsqrt(s_sq)) * d;
        }
      }
      // set_mag(strength): normalize (times 1 / |r| unless 0), then times strength.
      const V inv = R(1) / (d != R(0) ? d : splat<V>(R(1)));
      add_force<R, true>(b, s, apply, rx * inv * strength, ry * inv * strength);
    } else {
      // acceleration = G M w r, with w = 1 / (d_c^2 d) (clamped) or 1 / s^3 (Plummer).
      V denominator;
      if constexpr (kLaw == AttractorLaw::clamp_distance) {
        V dc = d < p.hi ? d : splat<V>(p.hi);
        dc = dc > p.lo ? dc : splat<V>(p.lo);
        denominator = dc * dc * d;
      } else if constexpr (kLaw == AttractorLaw::clamp_squared) {
        V q = d_sq < p.hi ? d_sq : splat<V>(p.hi);
        q = q > p.lo ? q : splat<V>(p.lo);
        denominator = q * d;
      } else {
        const V s_sq = d_sq + p.eps * p.eps;
        denominator = s_sq * vsqrt(s_sq);
      }
      const auto zero = d_sq == R(0);
      const V w = zero ? splat<V>(R(0)) : R(1) / (zero ? splat<V>(R(1)) : denominator);
      b.ax[s] += p.gm * w * rx;
      b.ay[s] += p.gm * w * ry;
    }
  }
}

// calder::edge_force: strength * (margin - d) / margin within margin of each edge.
template <class R, bool kBook>
void op_edge_force(Block<R>& b, const Params<R>& p, R width, R height) {
  using V = typename Simd<R>::V;
  using M = typename Simd<R>::M;
  const auto push = [&](V d) {
    const V inward = p.c * (p.margin - d) / p.margin;
    return d < p.margin ? inward : splat<V>(R(0));
  };
  for (int s = 0; s < kBlockVectors; ++s) {
    const V x = b.x[s];
    const V y = b.y[s];
    add_force<R, kBook>(b, s, ~M{}, push(x) - push(width - x), push(y) - push(height - y));
  }
}

// calder::fan: away from (px, py), strength * (1 - d / reach) for 0 < d < reach.
template <class R, bool kBook>
void op_fan(Block<R>& b, const Params<R>& p) {
  using V = typename Simd<R>::V;
  for (int s = 0; s < kBlockVectors; ++s) {
    const V awx = b.x[s] - p.px;
    const V awy = b.y[s] - p.py;
    const V d = vsqrt(awx * awx + awy * awy);
    const auto apply = (d != R(0)) & (d < p.reach);
    const V magnitude = p.c * (R(1) - d / p.reach);
    const V inv = R(1) / (d != R(0) ? d : splat<V>(R(1)));
    add_force<R, kBook>(b, s, apply, awx * inv * magnitude, awy * inv * magnitude);
  }
}

// calder::lift: (vy, -vx) set to coefficient * |v|^2.
template <class R, bool kBook>
void op_lift(Block<R>& b, const Params<R>& p) {
  using V = typename Simd<R>::V;
  using M = typename Simd<R>::M;
  for (int s = 0; s < kBlockVectors; ++s) {
    const V vx = b.vx[s];
    const V vy = b.vy[s];
    const V magnitude = p.c * (vx * vx + vy * vy);
    const V len = vsqrt(vy * vy + vx * vx);
    const V inv = R(1) / (len != R(0) ? len : splat<V>(R(1)));
    add_force<R, kBook>(b, s, ~M{}, vy * inv * magnitude, -vx * inv * magnitude);
  }
}

// World::boundary_one's bounce: right before left, bottom before top; clamp,
// then reverse.
template <class R, bool kUseRadius>
[[gnu::always_inline]] inline void bounce(Block<R>& b, int s, const Boundary& boundary, R width,
                                          R height, R reverse) {
  using V = typename Simd<R>::V;
  using M = typename Simd<R>::M;
  const V r = kUseRadius ? b.r[s] : splat<V>(R(0));
  const V x = b.x[s];
  const V y = b.y[s];
  const V x_hi = width - r;
  const V y_hi = height - r;
  const M none{};
  const M right = boundary.edges.right ? M(x > x_hi) : none;
  const M left = boundary.edges.left ? M((x < r) & ~right) : none;
  const M bottom = boundary.edges.bottom ? M(y > y_hi) : none;
  const M top = boundary.edges.top ? M((y < r) & ~bottom) : none;
  V nx = right ? x_hi : x;
  nx = left ? r : nx;
  V ny = bottom ? y_hi : y;
  ny = top ? r : ny;
  b.x[s] = nx;
  b.y[s] = ny;
  b.vx[s] = (right | left) ? b.vx[s] * reverse : b.vx[s];
  b.vy[s] = (bottom | top) ? b.vy[s] * reverse : b.vy[s];
}

// The update (semi-implicit Euler, acceleration cleared) and the bounce.
template <class R, bool kUseRadius>
void update_bounce(Block<R>& b, const Boundary& boundary, R width, R height, R dt) {
  const R reverse = R(-boundary.restitution);
  const bool before = boundary.timing == BoundaryTiming::before_update;
  for (int s = 0; s < kBlockVectors; ++s) {
    if (before) bounce<R, kUseRadius>(b, s, boundary, width, height, reverse);
    calder::detail::kick_drift(b.x[s], b.y[s], b.vx[s], b.vy[s], b.ax[s], b.ay[s],
                               splat<typename Simd<R>::V>(dt));
    if (!before) bounce<R, kUseRadius>(b, s, boundary, width, height, reverse);
  }
}

// The periodic wrap, lane by lane (rare and branchy: not worth vectorising).
template <class R>
void wrap(Block<R>& b, const Boundary& boundary, R width, R height) {
  for (int s = 0; s < kBlockVectors; ++s) {
    for (int l = 0; l < Block<R>::kLanes; ++l) {
      const R r = boundary.use_radius ? b.r[s][l] : R(0);
      if (boundary.edges.left || boundary.edges.right) {
        b.x[s][l] = calder::detail::wrap_coordinate(R(b.x[s][l]), -r, width + r);
      }
      if (boundary.edges.top || boundary.edges.bottom) {
        b.y[s][l] = calder::detail::wrap_coordinate(R(b.y[s][l]), -r, height + r);
      }
    }
  }
}

template <class R>
void update(Block<R>& b, const Boundary& boundary, R width, R height, R dt) {
  using V = typename Simd<R>::V;
  if (boundary.kind == BoundaryKind::bounce) {
    if (boundary.use_radius) return update_bounce<R, true>(b, boundary, width, height, dt);
    return update_bounce<R, false>(b, boundary, width, height, dt);
  }
  const bool wrapping = boundary.kind == BoundaryKind::wrap;
  const bool before = boundary.timing == BoundaryTiming::before_update;
  if (wrapping && before) wrap(b, boundary, width, height);
  for (int s = 0; s < kBlockVectors; ++s) {
    calder::detail::kick_drift(b.x[s], b.y[s], b.vx[s], b.vy[s], b.ax[s], b.ay[s], splat<V>(dt));
  }
  if (wrapping && !before) wrap(b, boundary, width, height);
}

template <class R, bool kBook>
void apply_op(Block<R>& b, const Op& op, const Params<R>& p, int step, R width, R height, R dt) {
  switch (op.kind) {
    case OpKind::uniform:
      if (op.per_step != nullptr) {
        const auto si = static_cast<std::size_t>(step);
        return op_uniform<R, kBook>(b, R(op.per_step[2 * si]), R(op.per_step[2 * si + 1]));
      }
      return op_uniform<R, kBook>(b, p.fx, p.fy);
    case OpKind::gravity_scaled:
      return op_gravity_scaled<R, kBook>(b, p.fx, p.fy);
    case OpKind::drag:
      if (p.never_reverse) return op_drag<R, kBook, true>(b, p, dt);
      return op_drag<R, kBook, false>(b, p, dt);
    case OpKind::friction:
      if (p.never_reverse) return op_friction<R, kBook, true>(b, p, width, height, dt);
      return op_friction<R, kBook, false>(b, p, width, height, dt);
    case OpKind::attractor:
      switch (p.law) {
        case AttractorLaw::clamp_distance:
          return op_attractor<R, kBook, AttractorLaw::clamp_distance, false>(b, p);
        case AttractorLaw::clamp_squared:
          return op_attractor<R, kBook, AttractorLaw::clamp_squared, false>(b, p);
        case AttractorLaw::plummer:
          if (p.eps == R(0)) return op_attractor<R, kBook, AttractorLaw::plummer, false>(b, p);
          return op_attractor<R, kBook, AttractorLaw::plummer, true>(b, p);
      }
      return;
    case OpKind::edge_force:
      return op_edge_force<R, kBook>(b, p, width, height);
    case OpKind::fan:
      return op_fan<R, kBook>(b, p);
    case OpKind::lift:
      return op_lift<R, kBook>(b, p);
  }
}

// Loads bodies [first, first + count) of the tile into a block (lanes past
// count get a harmless body: unit mass at the origin, at rest), runs every
// step of the batch on it, and stores the bodies back.
template <class R, bool kBook>
void advance_block(const Plan& plan, const std::vector<Params<R>>& params, const Tile& tile,
                   std::size_t first, std::size_t count) {
  constexpr int lanes = Block<R>::kLanes;
  Block<R> b;
  for (int s = 0; s < kBlockVectors; ++s) {
    for (int l = 0; l < lanes; ++l) {
      const std::size_t k = static_cast<std::size_t>(s * lanes + l);
      const bool real = k < count;
      const std::size_t i = first + (real ? k : 0);
      b.x[s][l] = real ? R(tile.x[i]) : R(0);
      b.y[s][l] = real ? R(tile.y[i]) : R(0);
      b.vx[s][l] = real ? R(tile.vx[i]) : R(0);
      b.vy[s][l] = real ? R(tile.vy[i]) : R(0);
      b.ax[s][l] = real ? R(tile.ax[i]) : R(0);
      b.ay[s][l] = real ? R(tile.ay[i]) : R(0);
      b.m[s][l] = real ? R(tile.mass[i]) : R(1);
      b.inv_m[s][l] = real ? R(1.0 / tile.mass[i]) : R(1);
      b.r[s][l] = real ? R(tile.radius[i]) : R(0);
      b.area[s][l] = real ? R(tile.drag_area[i]) : R(1);
      b.mu[s][l] = real ? R(tile.friction[i]) : R(0);
    }
  }
  const R width = R(plan.width);
  const R height = R(plan.height);
  const R dt = R(plan.dt);
  for (int step = 0; step < plan.steps; ++step) {
    for (std::size_t k = 0; k < plan.ops.size(); ++k) {
      apply_op<R, kBook>(b, plan.ops[k], params[k], step, width, height, dt);
    }
    update(b, plan.boundary, width, height, dt);
  }
  for (int s = 0; s < kBlockVectors; ++s) {
    for (int l = 0; l < lanes; ++l) {
      const std::size_t k = static_cast<std::size_t>(s * lanes + l);
      if (k >= count) break;
      const std::size_t i = first + k;
      tile.x[i] = b.x[s][l];
      tile.y[i] = b.y[s][l];
      tile.vx[i] = b.vx[s][l];
      tile.vy[i] = b.vy[s][l];
      tile.ax[i] = b.ax[s][l];
      tile.ay[i] = b.ay[s][l];
    }
  }
}

template <class R, bool kBook>
void advance_tile(const Plan& plan, const Tile& tile) {
  // The ops' parameters, converted once per tile.
  thread_local std::vector<Params<R>> params;
  params.clear();
  for (const Op& op : plan.ops) params.emplace_back(op);
  constexpr auto block = static_cast<std::size_t>(Block<R>::kBodies);
  for (std::size_t first = 0; first < tile.n; first += block) {
    advance_block<R, kBook>(plan, params, tile, first, std::min(block, tile.n - first));
  }
}

inline void advance_book64(const Plan& plan, const Tile& tile) {
  advance_tile<double, true>(plan, tile);
}
inline void advance_fast64(const Plan& plan, const Tile& tile) {
  advance_tile<double, false>(plan, tile);
}
inline void advance_fast32(const Plan& plan, const Tile& tile) {
  advance_tile<float, false>(plan, tile);
}

}  // namespace
}  // namespace calder::movers::detail
