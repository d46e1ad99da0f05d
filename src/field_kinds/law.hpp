// SPDX-License-Identifier: MIT
// calder internals: the law of a field kind, the half of a kind that its
// public header (calder/field_kinds/<kind>.hpp: the struct and its
// FieldKind description) leaves out. Each kind's law is one header of this
// folder, written once over lanes (lanes.hpp) for the World's plain loops
// (src/fields.cpp, calder/forces.hpp's functions) and the kernels of
// calder::bulk and calder::gpu alike; laws.hpp gathers them.
#pragma once

#include <cstddef>
#include <string>

#include "calder/field_kinds/kind.hpp"
#include "lanes.hpp"

namespace calder {

// FieldLaw<F>: how the field kind F acts. Every kind of the Field variant
// has one. A kind that acts on each body on its own has its law over lanes:
//
//   template <class R> struct Law;                 // its parameters in precision R
//   template <class R> static Law<R> law(const F&);
//   // Hands each(op) the function op(b) that adds the field's acceleration
//   // to body lane b (one kind of op per compile-time case of the law).
//   template <class P, class Each>
//   static void run(Each&& each, const Law<typename P::R>&, const lanes::Frame<typename P::R>&);
//
// and it may have:
//
//   // The plain loops' force on body i instead (any law: the attractor's).
//   static Vec2 force(const F&, const FieldContext&, std::size_t i);
//   // Why calder::bulk can't run this field ("" when it can).
//   static std::string no_kernel(const F&);
//
// A kind without a law (mutual attraction, custom force) has only a
// no_kernel, and its own branch in accumulate (src/fields.cpp).
template <class F>
struct FieldLaw;

// Whether the kind has a law over lanes (FieldLaw::law, FieldLaw::run).
template <class F>
concept HasLaw = requires(const F& f) {
  FieldLaw<F>::template law<double>(f);
};

}  // namespace calder
