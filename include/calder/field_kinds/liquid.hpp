// SPDX-License-Identifier: MIT
// The field kind Liquid: quadratic drag on bodies strictly inside a region
// (example 2.5); the law is Drag's (field_kinds/drag.hpp).
#pragma once

#include "calder/field_kinds/drag.hpp"
#include "calder/field_kinds/kind.hpp"

namespace calder {

struct Liquid {
  Rect region{0.0, 120.0, 640.0, 120.0};
  double c = 0.1;
  bool never_reverse = false;  // limit the drag so it never reverses a velocity in one step
  bool enabled = true;

  [[nodiscard]] bool contains(Vec2 position) const { return region.contains(position); }
  // The drag on a body with this velocity and frontal area (book: calculateDrag).
  [[nodiscard]] Vec2 calculate_drag(Vec2 velocity, double area = 1.0) const;
};

template <>
struct FieldKind<Liquid> {
  static constexpr const char* name = "liquid";
  static constexpr const char* summary =
      "Quadratic drag, as drag, on bodies strictly inside a region.";
  static constexpr auto parameters = std::tuple{
      Parameter<Liquid, Rect>{"region", &Liquid::region},  // w and h >= 0
      Parameter<Liquid, double>{"c", &Liquid::c, Range::non_negative},
      Parameter<Liquid, bool>{"never_reverse", &Liquid::never_reverse},
  };

  // The region as Rect::contains reads it: x < p.x < x + w, y < p.y < y + h
  // (the sums in double).
  template <class R>
  struct Law {
    R c;
    bool never_reverse;
    R x_min, x_max, y_min, y_max;
  };
  template <class R>
  static Law<R> law(const Liquid& f) {
    return {R(f.c),        f.never_reverse,           R(f.region.x), R(f.region.x + f.region.w),
            R(f.region.y), R(f.region.y + f.region.h)};
  }
  template <class P, class Each>
  static void run(Each&& each, const Law<typename P::R>& p,
                  const lanes::Frame<typename P::R>& frame) {
    const auto dt = frame.dt;
    const auto inside = [=](const auto& b) CALDER_LANE_INLINE {
      return (b.x > p.x_min) & (b.x < p.x_max) & (b.y > p.y_min) & (b.y < p.y_max);
    };
    if (p.never_reverse) {
      return each([=](auto& b)
                      CALDER_LANE_INLINE { laws::add_drag<P, true>(b, inside(b), p.c, dt); });
    }
    each([=](auto& b) CALDER_LANE_INLINE { laws::add_drag<P, false>(b, inside(b), p.c, dt); });
  }
};

}  // namespace calder
