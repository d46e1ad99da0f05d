// SPDX-License-Identifier: MIT
// calder: fields, the forces that act on every body of a world each step.
//
// A field is a plain struct of parameters; World::add stores it and returns a
// reference that stays valid for the world's lifetime, so a sketch can turn
// the wind on while the mouse is pressed or drag an attractor:
//
//   auto& wind = world.add(calder::Wind{.force = {0.1, 0}});
//   wind.enabled = mouse_pressed;
//
// Fields act in the order they were added, each one body at a time, and each
// force is divided by the body's mass and added to its acceleration as
// apply_force does. Each kind of field is one header of calder/field_kinds/:
// its struct and its description (FieldKind).
#pragma once

#include <cstddef>
#include <span>
#include <variant>

#include "calder/field_kinds/attractor.hpp"
#include "calder/field_kinds/custom_force.hpp"
#include "calder/field_kinds/drag.hpp"
#include "calder/field_kinds/edge_force.hpp"
#include "calder/field_kinds/fan.hpp"
#include "calder/field_kinds/friction.hpp"
#include "calder/field_kinds/gravity.hpp"
#include "calder/field_kinds/helium.hpp"
#include "calder/field_kinds/kind.hpp"
#include "calder/field_kinds/lift.hpp"
#include "calder/field_kinds/liquid.hpp"
#include "calder/field_kinds/mutual_attraction.hpp"
#include "calder/field_kinds/noise_wind.hpp"
#include "calder/field_kinds/wind.hpp"
#include "calder/forces.hpp"
#include "calder/vec2.hpp"

namespace calder {

// Every field kind, in the order scene files, bindings and docs list them.
using Field = std::variant<Gravity, Wind, NoiseWind, Helium, Fan, EdgeForce, Friction, Liquid, Drag,
                           Lift, Attractor, MutualAttraction, CustomForce>;

// Throws calder::Error naming the field and parameter when a field's
// parameters are out of range (negative drag, zero reach, NaN, ...).
void validate(const Field& field);

// A field's name as error messages and scene files spell it ("gravity", ...).
const char* field_name(const Field& field);

// Whether a scene file can hold this kind of field.
template <class F>
constexpr bool in_scene_files() {
  if constexpr (requires { FieldKind<F>::in_scene_files; }) {
    return FieldKind<F>::in_scene_files;
  } else {
    return true;
  }
}

// Whether this kind has a position that can follow the mouse (FieldKind::position).
template <class F>
constexpr bool has_position() {
  return requires { FieldKind<F>::position; };
}

// Adds the field's acceleration (force / mass, one body at a time) to
// (ax, ay) for bodies [first, last). Does nothing when the field is disabled.
// MutualAttraction over all bodies uses the pairwise (third-law) form; over a
// sub-range, each target feels every other body in index order.
void accumulate(const Field& field, const FieldContext& context, std::size_t first,
                std::size_t last, std::span<double> ax, std::span<double> ay);

}  // namespace calder
