// SPDX-License-Identifier: MIT
// The field kind MutualAttraction: every body attracts every other (the
// n-body problem), pair by pair under calder::attraction, or by calder::nbody's
// kernels (NBodyMethod).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "calder/field_kinds/kind.hpp"
#include "calder/forces.hpp"

namespace calder {

// The order in which mutual attraction adds up its forces (it decides the
// last bits, and so whether a sketch is reproduced exactly).
enum class PairOrder {
  // Each pair once, +F on one body and exactly -F on the other: Newton's
  // third law holds exactly and momentum is conserved (the default).
  pairwise,
  // For each body i in order: the central body (if any) pulls i, then i pulls
  // every other body (exercise 2.16's galaxy).
  by_source,
};

// A fixed heavy body that is not a mover (the galaxy's sun): it pulls every
// body under the same law and is never moved.
struct CentralBody {
  Vec2 position{};
  double mass = 500.0;
};

// How mutual attraction is summed.
enum class NBodyMethod {
  // The core's loops in the order PairOrder sets: bit-faithful to the book's
  // sketches, Newton's third law exact. Any law.
  exact,
  // The same O(n^2) sum by calder::nbody's vectorised, threaded kernels
  // (different last bits; the book clamp, the squared clamp or Plummer).
  direct,
  // O(n log n) on a quadtree (calder::nbody), approximate: see theta.
  barnes_hut,
};

// The methods' names, as scene files, Python and the web page spell them.
using NBodyMethodName = EnumName<NBodyMethod>;
inline constexpr std::array<NBodyMethodName, 3> kNBodyMethodNames{{
    {"exact", NBodyMethod::exact},
    {"direct", NBodyMethod::direct},
    {"barnes_hut", NBodyMethod::barnes_hut},
}};

// Barnes-Hut's opening angle unless a field or calder::nbody's options say
// otherwise: the largest in steps of 0.05 whose RMS relative force error on a
// uniform disk of 10^6 bodies stays clearly below 1e-3 with multipoles to
// fourth order (docs/PERFORMANCE.md, "Barnes-Hut"). The clamped laws, summed
// with monopoles, err more (calder/nbody.hpp).
inline constexpr double kDefaultTheta = 0.7;

// Every body attracts every other (the n-body problem). In a world updated
// simultaneously all forces come from one state (see PairOrder). In a world
// updated sequentially (example 2.9), body i feels all others at their current
// positions, including the ones already moved this step.
struct MutualAttraction {
  AttractionLaw law{};
  PairOrder order = PairOrder::pairwise;
  std::optional<CentralBody> central = std::nullopt;
  NBodyMethod method = NBodyMethod::exact;
  double theta = kDefaultTheta;   // barnes_hut: opening angle in [0, 1]
  bool single_precision = false;  // direct, barnes_hut: pair sums in float32
  int threads = 0;                // direct, barnes_hut: 0 = every core
  bool enabled = true;
};

namespace field_kind_detail {
constexpr bool fast_method(const MutualAttraction& f) { return f.method != NBodyMethod::exact; }
}  // namespace field_kind_detail

template <>
struct FieldKind<MutualAttraction> {
  static constexpr const char* name = "mutual_attraction";
  static constexpr const char* summary =
      "Every body attracts every other under an attraction law (exact, direct or Barnes-Hut).";
  using M = MutualAttraction;
  static constexpr auto parameters = std::tuple{
      Parameter<M, AttractionLaw>{"law", &M::law},
      Parameter<M, PairOrder>{"order", &M::order},
      Parameter<M, NBodyMethod>{"method", &M::method, Range::finite,
                                field_kind_detail::fast_method},
      Parameter<M, double>{"theta", &M::theta, Range::unit_interval,
                           field_kind_detail::fast_method},
      Parameter<M, bool>{"single_precision", &M::single_precision, Range::finite,
                         field_kind_detail::fast_method},
      Parameter<M, int>{"threads", &M::threads, Range::non_negative,
                        field_kind_detail::fast_method},
      Parameter<M, std::optional<CentralBody>>{"central", &M::central},  // position, mass > 0
  };
  // The fast methods support the inverse-square law only.
  static void check(const MutualAttraction& field, const std::string& where);
};

}  // namespace calder
