// SPDX-License-Identifier: MIT
// The law of Attractor (calder/field_kinds/attractor.hpp), and the
// inverse-square laws of attraction (calder/forces.hpp's DistanceClamp),
// which calder::attraction and MutualAttraction use too.
#pragma once

#include <string>

#include "calder/field_kinds/attractor.hpp"
#include "calder/forces.hpp"
#include "law.hpp"

namespace calder {

namespace laws {

// An inverse-square law (AttractionLaw::inverse_square) with its source: the
// source's position and mass M, G, G * M, the clamp's bounds, the softening.
template <class R>
struct InverseSquare {
  R px, py, mass, G, gm, lo, hi, eps;
  DistanceClamp clamp;
  bool masses_first;  // G * (M * m) rather than (G * M) * m: the sketches differ
};
template <class R>
InverseSquare<R> inverse_square_law(Vec2 source, double mass, const AttractionLaw& law) {
  return {R(source.x),     R(source.y),
          R(mass),         R(law.G),
          R(law.G * mass), R(law.min),
          R(law.max),      R(law.softening),
          law.clamp,       law.product == MassProduct::masses_first};
}

// The force of the source on a target at (x, y) of mass m, where `apply`:
// r = source - target, |F| = G M m over d_c^2 (d clamped to [lo, hi]), over
// d^2 clamped to [lo, hi], over d^2, or times d over (d^2 + eps^2)^(3/2)
// (Plummer); F = r set to |F|. The unclamped law has no force (no direction)
// where the two coincide.
template <class P, DistanceClamp kClamp, bool kSoftened>
CALDER_LANE_INLINE inline auto inverse_square(const InverseSquare<typename P::R>& p,
                                              typename P::L x, typename P::L y, typename P::L m) {
  using L = typename P::L;
  using R = typename P::R;
  const L rx = p.px - x;
  const L ry = p.py - y;
  const L d_sq = rx * rx + ry * ry;
  const L d = P::sqrt(d_sq);
  const L numerator = p.masses_first ? p.G * (p.mass * m) : p.G * p.mass * m;
  L strength;
  decltype(d_sq != d_sq) apply = P::all();  // a comparison's mask, true in every lane
  if constexpr (kClamp == DistanceClamp::distance) {
    L dc = d < p.hi ? d : P::splat(p.hi);  // constrain(d, lo, hi) = max(min(d, hi), lo)
    dc = dc > p.lo ? dc : P::splat(p.lo);
    strength = numerator / (dc * dc);
  } else if constexpr (kClamp == DistanceClamp::squared_distance) {
    L q = d_sq < p.hi ? d_sq : P::splat(p.hi);
    q = q > p.lo ? q : P::splat(p.lo);
    strength = numerator / q;
  } else {
    apply = d_sq != R(0);
    if constexpr (!kSoftened) {
      strength = numerator / d_sq;
    } else {
      const L s_sq = d_sq + p.eps * p.eps;
      strength = numerator / (s_sq * P::sqrt(s_sq)) * d;
    }
  }
  return lanes::Masked<L, decltype(apply)>{lanes::set_mag<P>(rx, ry, d, strength), apply};
}

// The acceleration of body lane b toward the source: the book's force over the
// body's mass, or the fast form G M w r, w = 1 / (d_c^2 d) (clamped) or 1 / s^3
// (Plummer), 0 where the two coincide.
template <class P, DistanceClamp kClamp, bool kSoftened, class B>
CALDER_LANE_INLINE inline void add_inverse_square(B& b, const InverseSquare<typename P::R>& p) {
  using L = typename P::L;
  using R = typename P::R;
  if constexpr (P::book) {
    const auto pull = inverse_square<P, kClamp, kSoftened>(p, b.x, b.y, b.m());
    lanes::add_force<P>(b, pull.apply, pull.f.x, pull.f.y);
  } else {
    const L rx = p.px - b.x;
    const L ry = p.py - b.y;
    const L d_sq = rx * rx + ry * ry;
    const L d = P::sqrt(d_sq);
    L denominator;
    if constexpr (kClamp == DistanceClamp::distance) {
      L dc = d < p.hi ? d : P::splat(p.hi);
      dc = dc > p.lo ? dc : P::splat(p.lo);
      denominator = dc * dc * d;
    } else if constexpr (kClamp == DistanceClamp::squared_distance) {
      L q = d_sq < p.hi ? d_sq : P::splat(p.hi);
      q = q > p.lo ? q : P::splat(p.lo);
      denominator = q * d;
    } else {
      const L s_sq = d_sq + p.eps * p.eps;
      denominator = s_sq * P::sqrt(s_sq);
    }
    const auto zero = d_sq == R(0);
    const L w = zero ? P::splat(R(0)) : R(1) / (zero ? P::splat(R(1)) : denominator);
    b.ax += p.gm * w * rx;
    b.ay += p.gm * w * ry;
  }
}

// Calls visit.template operator()<kClamp, kSoftened>() for the law's case.
template <class R, class Visit>
inline void with_inverse_square_case(const InverseSquare<R>& p, Visit&& visit) {
  switch (p.clamp) {
    case DistanceClamp::distance:
      return visit.template operator()<DistanceClamp::distance, false>();
    case DistanceClamp::squared_distance:
      return visit.template operator()<DistanceClamp::squared_distance, false>();
    case DistanceClamp::none:
      break;
  }
  if (p.eps == R(0)) return visit.template operator()<DistanceClamp::none, false>();
  visit.template operator()<DistanceClamp::none, true>();
}

}  // namespace laws

template <>
struct FieldLaw<Attractor> {
  // The plain loops: calder::attraction, any law.
  static Vec2 force(const Attractor& f, const FieldContext& c, std::size_t i) {
    return f.attract(c.bodies.position(i), c.bodies.mass[i]);
  }

  template <class R>
  using Law = laws::InverseSquare<R>;
  template <class R>
  static Law<R> law(const Attractor& f) {
    return laws::inverse_square_law<R>(f.position, f.mass, f.law);
  }
  template <class P, class Each>
  static void run(Each&& each, const Law<typename P::R>& p, const lanes::Frame<typename P::R>&) {
    laws::with_inverse_square_case(p, [&]<DistanceClamp kClamp, bool kSoftened>() {
      each([=](auto& b)
               CALDER_LANE_INLINE { laws::add_inverse_square<P, kClamp, kSoftened>(b, p); });
    });
  }
  static std::string no_kernel(const Attractor& f) {
    if (f.law.inverse_square()) return "";
    return "field attractor: only the inverse-square laws have a kernel (no custom law, "
           "exponent 2, no repulsive core)";
  }
};

}  // namespace calder
