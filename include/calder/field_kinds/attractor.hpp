// SPDX-License-Identifier: MIT
// The field kind Attractor: a fixed point that attracts (or repels) every
// body under an attraction law (calder/forces.hpp).
#pragma once

#include "calder/field_kinds/kind.hpp"
#include "calder/forces.hpp"

namespace calder {

// A fixed point attractor (a repulsor when law.G < 0). Not a body: it never
// moves by itself, and trajectories don't list it.
struct Attractor {
  Vec2 position{320.0, 120.0};
  double mass = 20.0;
  AttractionLaw law{};
  bool enabled = true;

  // The force it exerts on a body (book: attractor.attract(mover)).
  [[nodiscard]] Vec2 attract(Vec2 body_position, double body_mass) const {
    return attraction(position, mass, body_position, body_mass, law);
  }
};

template <>
struct FieldKind<Attractor> {
  static constexpr const char* name = "attractor";
  static constexpr const char* summary =
      "A fixed point that attracts every body under an attraction law (repels when G < 0).";
  static constexpr auto parameters = std::tuple{
      Parameter<Attractor, Vec2>{"position", &Attractor::position},
      Parameter<Attractor, double>{"mass", &Attractor::mass, Range::positive},
      Parameter<Attractor, AttractionLaw>{"law", &Attractor::law},
  };
  static constexpr auto position = &Attractor::position;
};

}  // namespace calder
