// SPDX-License-Identifier: MIT
#include "summary.hpp"

#include <array>
#include <cinttypes>
#include <cstdio>
#include <optional>
#include <string>

#include "calder/diagnostics.hpp"
#include "calder/error.hpp"
#include "calder/trajectory.hpp"
#include "calder/world.hpp"

namespace calder::app {

namespace {

void line(std::ostream& out, const char* label, const std::string& value) {
  constexpr int kWidth = 18;
  std::string text = label;
  text.resize(kWidth, ' ');
  out << text << value << '\n';
}

std::string hex16(std::uint64_t value) {
  std::array<char, 17> text{};
  std::snprintf(text.data(), text.size(), "%016" PRIx64, value);
  return text.data();
}

std::string vector_text(Vec2 v) {
  std::string text = "(";
  text += format_number(v.x);
  text += ", ";
  text += format_number(v.y);
  text += ')';
  return text;
}

}  // namespace

void print_summary(std::ostream& out, const Simulation& simulation, std::uint32_t seed) {
  const World& world = simulation.world();
  const double kinetic = kinetic_energy(world);
  std::optional<double> potential;
  std::string why_not;
  try {
    potential = potential_energy(world);
  } catch (const Error& e) {
    why_not = e.what();
  }
  line(out, "scene", detail::printable(simulation.scene().name, 200));
  line(out, "frames", std::to_string(simulation.frame()));
  line(out, "bodies", std::to_string(world.body_count()));
  line(out, "dt", format_number(world.dt()));
  line(out, "seed", std::to_string(seed));
  line(out, "kinetic energy", format_number(kinetic));
  if (potential) {
    line(out, "potential energy", format_number(*potential));
    line(out, "total energy", format_number(kinetic + *potential));
  } else {
    line(out, "potential energy", std::string("n/a (").append(why_not).append(")"));
    line(out, "total energy", "n/a");
  }
  line(out, "momentum", vector_text(linear_momentum(world)));
  line(out, "angular momentum", format_number(angular_momentum(world)));
  line(out, "state hash", hex16(state_hash(world)));
}

}  // namespace calder::app
