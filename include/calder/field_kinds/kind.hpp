// SPDX-License-Identifier: MIT
// calder: what a field kind is made of. Each kind is one header in this
// folder: its struct (the parameters a sketch sets) and its FieldKind<F>
// description (name, parameters and their ranges, for validation, scene
// files, bindings and docs). calder/fields.hpp gathers them into the Field
// variant. How a kind acts, its law, is calder's own (src/field_kinds/).
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <tuple>

#include "calder/backends.hpp"
#include "calder/body_columns.hpp"
#include "calder/vec2.hpp"

namespace calder {

class Noise;

// An axis-aligned rectangle: top-left corner (x, y), width w, height h.
struct Rect {
  double x = 0.0;
  double y = 0.0;
  double w = 0.0;
  double h = 0.0;
  // Strictly inside, as the book's Liquid.contains: x < p.x < x + w, same in y.
  [[nodiscard]] bool contains(Vec2 p) const {
    return p.x > x && p.x < x + w && p.y > y && p.y < y + h;
  }
};

// A canvas edge. y points down: top is y = 0, bottom is y = height.
enum class Edge { left, right, top, bottom };

// Whether a circle of this radius at position touches a canvas edge of a
// width x height canvas within tolerance (book 2.4: y > height - radius - 1).
[[nodiscard]] bool touches_edge(Edge edge, Vec2 position, double radius, double width,
                                double height, double tolerance);

// Read-only view of the bodies' state that forces are evaluated at. During a
// multi-stage integrator step the positions and velocities are the stage's.
// (The columns are calder/body_columns.hpp's.)
struct BodyView : BodyColumnsOf<std::span<const double>> {
  [[nodiscard]] std::size_t size() const { return x.size(); }
  [[nodiscard]] Vec2 position(std::size_t i) const { return {x[i], y[i]}; }
  [[nodiscard]] Vec2 velocity(std::size_t i) const { return {vx[i], vy[i]}; }
  // The body's own friction coefficient, or fallback when it has none.
  [[nodiscard]] double friction_or(std::size_t i, double fallback) const;
};

// Everything a field may read while it acts.
struct FieldContext {
  BodyView bodies;
  double time = 0.0;  // simulation time of the state in `bodies`
  double dt = 1.0;
  double width = 640.0;
  double height = 240.0;
  const Noise* noise = nullptr;
  // The world's fast methods of MutualAttraction (calder/backends.hpp; null:
  // the process default).
  MutualAttractionBackend mutual_attraction = nullptr;
};

// The values a parameter accepts (every number of a Vec2 or a Rect: finite).
enum class Range {
  finite,
  positive,
  non_negative,
  // [0, 1]. A scene file's reader checks >= 0 at the value, validate the rest.
  unit_interval,
};

template <class F, class T>
struct Parameter {
  const char* key;  // in scene files and messages
  T F::*member;
  Range range = Range::finite;
  // When to_toml writes it (nullptr: always; false: left out, so the default applies).
  bool (*written)(const F&) = nullptr;
};

// FieldKind<F> describes the field kind F: its name and its parameters, each
// with its scene-file key, the values it accepts and when a file lists it.
// field_name, validate, accumulate, the scene reader and writer, the Python
// classes and the docs' lists of kinds all work from it (they std::visit
// Field, so a kind without a FieldKind doesn't compile). Besides name and
// parameters a kind has a summary, one line that the Python class shows as
// its docstring:
//
//   static constexpr const char* summary = "...";
//
// and it may have:
//
//   static constexpr bool in_scene_files = false;  // C++ code, no scene-file form
//   static constexpr auto position = &F::position; // it can follow the mouse
//   static void check(const F&, const std::string& where);  // rules across parameters
template <class F>
struct FieldKind;

namespace field_kind_detail {
template <class F, class T>
F owner_of(T F::*);
}  // namespace field_kind_detail

// Parameter::written for a parameter written only when it is not the default.
template <auto member>
constexpr bool differs(const decltype(field_kind_detail::owner_of(member))& field) {
  using F = decltype(field_kind_detail::owner_of(member));
  return !(field.*member == F{}.*member);
}

}  // namespace calder
