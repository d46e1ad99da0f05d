// SPDX-License-Identifier: MIT
// The field kind Friction: kinetic friction on bodies touching a canvas edge.
#pragma once

#include "calder/field_kinds/kind.hpp"

namespace calder {

// Kinetic friction on bodies touching a surface (the canvas edge `surface`,
// within `tolerance` as World::touching tells). A body's own friction
// coefficient (BodyDef::friction) replaces mu.
struct Friction {
  double mu = 0.1;
  double normal = 1.0;
  Edge surface = Edge::bottom;
  double tolerance = 1.0;
  // The book's friction can't hold a body still: near rest one step's
  // friction overshoots and the body creeps back and forth. true limits it
  // (as limit_drag does) so that it stops the body instead of reversing it.
  bool never_reverse = false;
  bool enabled = true;
};

template <>
struct FieldKind<Friction> {
  static constexpr const char* name = "friction";
  static constexpr const char* summary =
      "Kinetic friction -mu * normal * v-hat on bodies touching a canvas edge (a body's own "
      "friction replaces mu).";
  static constexpr auto parameters = std::tuple{
      Parameter<Friction, double>{"mu", &Friction::mu, Range::non_negative},
      Parameter<Friction, double>{"normal", &Friction::normal, Range::non_negative},
      Parameter<Friction, Edge>{"surface", &Friction::surface},
      Parameter<Friction, double>{"tolerance", &Friction::tolerance, Range::non_negative},
      Parameter<Friction, bool>{"never_reverse", &Friction::never_reverse},
  };
};

}  // namespace calder
