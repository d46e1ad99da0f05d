// SPDX-License-Identifier: MIT
#include "summary.hpp"

#include <array>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <string>

#include "calder/diagnostics.hpp"
#include "calder/error.hpp"
#include "calder/trajectory.hpp"
#include "calder/world.hpp"
#include "errors.hpp"

namespace calder::app {

namespace {

void line(std::ostream& out, const char* label, const std::string& value) {
  constexpr int kWidth = 18;
  std::string text = label;
  text.resize(kWidth, ' ');
  out << text << value << '\n';
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

std::uint64_t summary_potential_cost(const World& world) {
  return potential_energy_cost(world, summary_potential_pairs);
}

// The energy error and, for ias15, what its steps were.
// `total`: the total energy now, when summed exactly.
void print_accuracy(std::ostream& out, const World& world, const EnergyWatch* energy,
                    std::optional<double> total) {
  if (energy != nullptr && energy->active() && total) {
    const double start = energy->start_energy();
    const double change = std::fabs(*total - start);
    line(out, "energy error",
         format_number(start != 0.0 ? change / std::fabs(start) : change) +
             " (relative, since frame 0)");
  } else if (energy != nullptr) {
    line(out, "energy error", "n/a (the scene's fields or boundary don't conserve energy)");
  }
  if (world.integrator() != Integrator::ias15) return;
  const AdaptiveStats& s = world.adaptive_stats();
  line(out, "internal steps",
       std::to_string(s.steps) + " (" + std::to_string(s.rejected) + " rejected, " +
           std::to_string(s.force_evaluations) + " force evaluations)");
  if (s.steps > 0) line(out, "smallest step", format_number(s.smallest_step));
  if (std::isfinite(s.closest_approach)) {
    line(out, "closest approach",
         format_number(s.closest_approach) + " at t = " + format_number(s.closest_approach_time));
  }
}

void print_summary(std::ostream& out, const Simulation& simulation, std::uint32_t seed,
                   const std::string& source, const std::function<void()>& before_printing,
                   const EnergyWatch* energy_watch) {
  const World& world = simulation.world();
  // The displays' energy (calder::displayed_energy), with the summary's
  // larger budget: it is computed once.
  const DisplayedEnergy energy = displayed_energy(world, summary_potential_pairs);
  const double kinetic = energy.kinetic;
  std::optional<PotentialEstimate> potential;
  if (energy.has_potential) potential = energy.potential;
  const std::string& why_not = energy.why_not;
  const Vec2 momentum = linear_momentum(world);
  const double angular = angular_momentum(world);
  // Finite inputs can still overflow a diagnostic (masses of 1e10 at
  // speeds of 1e300): the run failed, and nothing is printed as its result.
  const auto check = [&](const char* what, double value) {
    if (!std::isfinite(value)) {
      throw RunError(source + ": frame " + std::to_string(simulation.frame()) + ": the " + what +
                     " overflows (" + format_number(value) + "); the summary is not printed");
    }
  };
  check("kinetic energy", kinetic);
  if (potential) {
    check("potential energy", potential->value);
    check("total energy", kinetic + potential->value);
  }
  check("momentum", momentum.x);
  check("momentum", momentum.y);
  check("angular momentum", angular);
  if (before_printing) before_printing();

  line(out, "scene", detail::printable(simulation.scene().name, 200));
  line(out, "frames", std::to_string(simulation.frame()));
  line(out, "bodies", std::to_string(world.body_count()));
  line(out, "dt", format_number(world.dt()));
  line(out, "seed", std::to_string(seed));
  line(out, "kinetic energy", format_number(kinetic));
  if (potential && potential->exact) {
    line(out, "potential energy", format_number(potential->value));
    line(out, "total energy", format_number(kinetic + potential->value));
  } else if (potential) {
    // Too many pairs to sum in bounded time: a sampled estimate, so labelled.
    std::string text(1, '~');
    text += format_number(potential->value);
    text += " (estimated from " + std::to_string(potential->pairs_summed) + " of " +
            std::to_string(potential->pairs_total) + " pairs, sampled)";
    line(out, "potential energy", text);
    text.assign(1, '~');
    text += format_number(kinetic + potential->value);
    text += " (estimated)";
    line(out, "total energy", text);
  } else {
    line(out, "potential energy", std::string("n/a (").append(why_not).append(")"));
    line(out, "total energy", "n/a");
  }
  line(out, "momentum", vector_text(momentum));
  line(out, "angular momentum", format_number(angular));
  print_accuracy(out, world, energy_watch,
                 potential && potential->exact ? std::optional<double>(kinetic + potential->value)
                                               : std::nullopt);
  line(out, "state hash", state_hash_text(world));
}

}  // namespace calder::app
