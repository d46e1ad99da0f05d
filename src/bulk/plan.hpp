// SPDX-License-Identifier: MIT
// calder::bulk internals: a batch's fields compiled into a list of passes,
// one per enabled field, each the field kind's law (plan.cpp), and the
// kernels that run them over one tile (kernels_*.cpp, compiled per
// instruction set, chosen at run time by dispatch.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <string>
#include <variant>
#include <vector>

#include "../field_kinds/laws.hpp"
#include "../step_batch.hpp"
#include "calder/fields.hpp"
#include "calder/world.hpp"

namespace calder::bulk::detail {

// A field's law in the precision R of a kernel (FieldLaw<F>::Law<R>, its
// parameters converted once per batch), for the kinds that have one; an
// empty struct for the others, which compile() never makes.
template <class F, class R>
struct KindLaw {};
template <class F, class R>
requires HasLaw<F>
struct KindLaw<F, R> {
  using Kind = FieldLaw<F>;
  typename Kind::template Law<R> law;
};

template <class R, class Fields>
struct LawsOf;
template <class R, class... Kinds>
struct LawsOf<R, std::variant<Kinds...>> {
  using type = std::variant<KindLaw<Kinds, R>...>;
};
// Any kind's law in precision R.
template <class R>
using AnyLaw = typename LawsOf<R, Field>::type;

// One pass over a tile: an enabled field's law, in both precisions.
struct Op {
  AnyLaw<double> law64;
  AnyLaw<float> law32;

  template <class R>
  [[nodiscard]] const AnyLaw<R>& law() const {
    if constexpr (sizeof(R) == sizeof(double)) {
      return law64;
    } else {
      return law32;
    }
  }
};

struct Plan {
  std::vector<Op> ops;
  std::vector<double> per_step;  // storage behind the noise winds' Law::per_step
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
