// SPDX-License-Identifier: MIT
// calder::bulk internals: a batch's fields compiled into a list of passes
// (plan.cpp), and the kernels that run them over one tile (kernels_*.cpp,
// compiled per instruction set, chosen at run time by dispatch.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "calder/fields.hpp"
#include "calder/step_batch.hpp"
#include "calder/world.hpp"

namespace calder::bulk::detail {

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

// An op's parameters in the precision R of a kernel (each field kind's
// op_of in plan.cpp writes them, once for each precision). Parameters not
// used by a kind keep their defaults.
template <class R>
struct Params {
  R fx{}, fy{};     // uniform: the force; gravity_scaled: g
  R c{};            // drag: c; friction: mu; edge_force, fan: strength; lift: coefficient
  R normal = R(1);  // friction
  // drag: strictly inside (x_min, x_max) x (y_min, y_max); everywhere: no
  // region (Drag), the bounds infinite
  R x_min{}, x_max{}, y_min{}, y_max{};
  bool everywhere = false;
  bool never_reverse = false;   // drag, friction
  Edge surface = Edge::bottom;  // friction
  R tolerance = R(1);           // friction
  R px{}, py{};                 // attractor, fan: position
  // attractor: the law, G and the attractor's mass M, G * M, the clamp
  // bounds, the softening (eps); the book's two groupings of G M m
  DistanceClamp law = DistanceClamp::distance;
  bool masses_first = false;
  R G = R(1), mass{}, gm{}, lo{}, hi{}, eps{};
  R margin{};  // edge_force
  R reach{};   // fan
};

// One pass over a tile.
struct Op {
  OpKind kind = OpKind::uniform;
  // uniform: when not null, the force of each step of the batch (x, y pairs):
  // NoiseWind changes with time.
  const double* per_step = nullptr;
  Params<double> p64;
  Params<float> p32;

  template <class R>
  [[nodiscard]] const Params<R>& params() const {
    if constexpr (sizeof(R) == sizeof(double)) {
      return p64;
    } else {
      return p32;
    }
  }
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

// out[i] = x[i] / mass[i] as the book kernels divide (for the tests).
using BookQuotients = void (*)(const double* x, const double* mass, double* out, std::size_t n);

struct KernelTable {
  const char* name;
  AdvanceTile book64;  // Arithmetic::book
  AdvanceTile fast64;  // Arithmetic::float64
  AdvanceTile fast32;  // Arithmetic::float32
  BookQuotients book_quotients;
};

const KernelTable& kernels();

}  // namespace calder::bulk::detail
