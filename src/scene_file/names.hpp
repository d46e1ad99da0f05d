// SPDX-License-Identifier: MIT
// calder scene files: the spelling of every enumeration in a scene file,
// shared by the reader and the writer so that the two cannot drift apart.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <string_view>

#include "calder/fields.hpp"
#include "calder/forces.hpp"
#include "calder/scene.hpp"
#include "calder/world.hpp"

namespace calder::scene_file_detail {

template <class E>
struct Choice {
  std::string_view name;
  E value;
};

inline constexpr std::array<Choice<UpdateOrder>, 2> kUpdateOrders{{
    {"simultaneous", UpdateOrder::simultaneous},
    {"sequential", UpdateOrder::sequential},
}};

inline constexpr std::array<Choice<BoundaryKind>, 3> kBoundaryKinds{{
    {"none", BoundaryKind::none},
    {"bounce", BoundaryKind::bounce},
    {"wrap", BoundaryKind::wrap},
}};

inline constexpr std::array<Choice<BoundaryTiming>, 2> kBoundaryTimings{{
    {"after_update", BoundaryTiming::after_update},
    {"before_update", BoundaryTiming::before_update},
}};

// In the order a file lists them by default.
inline constexpr std::array<Choice<Edge>, 4> kEdges{{
    {"left", Edge::left},
    {"right", Edge::right},
    {"top", Edge::top},
    {"bottom", Edge::bottom},
}};

inline constexpr std::array<Choice<PressAction>, 3> kPressActions{{
    {"none", PressAction::none},
    {"reset", PressAction::reset},
    {"toss", PressAction::toss},
}};

inline constexpr std::array<Choice<BodyGroup::Layout>, 2> kLayouts{{
    {"grid", BodyGroup::Layout::grid},
    {"orbit", BodyGroup::Layout::orbit},
}};

// The core's public name tables as tables here.
template <class E, class Name, std::size_t N>
constexpr std::array<Choice<E>, N> choices_of(const std::array<Name, N>& names) {
  std::array<Choice<E>, N> out{};
  for (std::size_t i = 0; i < N; ++i) out[i] = {names[i].name, names[i].value};
  return out;
}

inline constexpr auto kIntegrators = choices_of<Integrator>(kIntegratorNames);
inline constexpr auto kClamps = choices_of<DistanceClamp>(kDistanceClampNames);

inline constexpr std::array<Choice<MassProduct>, 2> kProducts{{
    {"left_to_right", MassProduct::left_to_right},
    {"masses_first", MassProduct::masses_first},
}};

inline constexpr std::array<Choice<PairOrder>, 2> kPairOrders{{
    {"pairwise", PairOrder::pairwise},
    {"by_source", PairOrder::by_source},
}};

inline constexpr auto kArithmetics = choices_of<Arithmetic>(kArithmeticNames);
inline constexpr auto kNBodyMethods = choices_of<NBodyMethod>(kNBodyMethodNames);

// The table of an enumeration a field parameter may have (see FieldKind).
constexpr const auto& choices(Edge) { return kEdges; }
constexpr const auto& choices(PairOrder) { return kPairOrders; }
constexpr const auto& choices(NBodyMethod) { return kNBodyMethods; }

// The name of an enumerator (empty if the table lacks it, which a complete
// table never does).
template <class E, std::size_t N>
constexpr std::string_view name_of(const std::array<Choice<E>, N>& choices, E value) {
  for (const Choice<E>& c : choices) {
    if (c.value == value) return c.name;
  }
  return {};
}

// Concatenates strings, string views and literals into one string. (GCC 12
// warns, wrongly, about "literal" + std::string temporaries at -O3: -Wrestrict.)
template <class... Parts>
std::string cat(const Parts&... parts) {
  std::string out;
  (out.append(std::string_view(parts)), ...);
  return out;
}

}  // namespace calder::scene_file_detail
