// SPDX-License-Identifier: MIT
// calder::movers internals: a batch's fields compiled into a list of passes
// (plan.cpp), and the kernels that run them over one tile (kernels_*.cpp,
// compiled per instruction set, chosen at run time by dispatch.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "calder/fields.hpp"
#include "calder/world.hpp"

namespace calder::movers::detail {

enum class OpKind : std::uint8_t {
  uniform,         // the same force on every body: Wind, Helium, Gravity, NoiseWind
  gravity_scaled,  // g * mass
  drag,            // quadratic drag, everywhere (Drag) or strictly inside a region (Liquid)
  friction,        // kinetic friction on bodies touching a canvas edge
  attractor,       // a fixed attractor, inverse-square law
  edge_force,      // pushes back from the canvas edges
  fan,             // blows away from a point, linear falloff
  lift,            // perpendicular to the velocity
};

// One pass over a tile. Fields not used by a kind keep their defaults.
struct Op {
  OpKind kind = OpKind::uniform;
  double fx = 0.0;  // uniform: the force; gravity_scaled: g
  double fy = 0.0;
  // uniform: when not null, the force of each step of the batch (x, y pairs):
  // NoiseWind changes with time.
  const double* per_step = nullptr;
  double c = 0.0;       // drag: c; friction: mu; edge_force, fan: strength; lift: coefficient
  double normal = 1.0;  // friction
  // drag: strictly inside (x_min, x_max) x (y_min, y_max); +-infinity: everywhere
  double x_min = 0.0, x_max = 0.0, y_min = 0.0, y_max = 0.0;
  bool everywhere = false;      // drag: no region (Drag), the bounds above are infinite
  bool never_reverse = false;   // drag, friction
  Edge surface = Edge::bottom;  // friction
  double tolerance = 1.0;       // friction
  double px = 0.0, py = 0.0;    // attractor, fan: position
  // attractor: law, G * M and G, M (the book's two groupings), clamp bounds, softening
  DistanceClamp law = DistanceClamp::distance;
  bool masses_first = false;
  double G = 1.0, mass = 0.0, lo = 0.0, hi = 0.0, softening = 0.0;
  double margin = 0.0;  // edge_force
  double reach = 0.0;   // fan
};

struct Plan {
  std::vector<Op> ops;
  std::vector<double> per_step;  // storage behind Op::per_step
  Boundary boundary{};
  double width = 0.0;
  double height = 0.0;
  double dt = 1.0;
  int steps = 0;
};

// Compiles the fields of a batch into plan (reusing its storage); false, with
// *why_not, when a field has no kernel.
bool compile(const StepBatch& batch, Plan& plan, std::string* why_not);
// The reason a world's fields can't be compiled, or "".
std::string unsupported_field(const std::deque<Field>& fields);

// One tile: slices of the world's columns (kTile bodies at most).
struct Tile {
  BodyColumnsOf<double*, const double*> bodies;
  std::size_t n;
};

// Advances one tile through plan.steps steps.
using AdvanceTile = void (*)(const Plan& plan, const Tile& tile);

struct KernelTable {
  const char* name;
  AdvanceTile book64;  // Arithmetic::book
  AdvanceTile fast64;  // Arithmetic::float64
  AdvanceTile fast32;  // Arithmetic::float32
};

const KernelTable& kernels();

}  // namespace calder::movers::detail
