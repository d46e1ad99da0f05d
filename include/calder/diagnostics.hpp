// SPDX-License-Identifier: MIT
// calder: numbers to trust a simulation by: energy, momentum, a state hash.
#pragma once

#include <cstdint>
#include <string>

#include "calder/forces.hpp"
#include "calder/vec2.hpp"

namespace calder {

class World;
class Simulation;

// Sum of 1/2 m |v|^2 over all bodies.
double kinetic_energy(const World& world);

// Gravitational potential energy of every pair of bodies under `law`
// (see attraction_potential: -G m1 m2 / r for the unclamped law).
double potential_energy(const World& world, const AttractionLaw& law);

// The potential energy of the world's enabled conservative fields: mutual
// attraction, point attractors and uniform gravity (-F . position). Throws
// calder::Error if a mutual or point attraction uses a custom law.
double potential_energy(const World& world);

// kinetic_energy + potential_energy of the world's fields.
double total_energy(const World& world);

// The potential energy of the world's fields (as potential_energy(world)),
// in bounded time: each enabled mutual attraction sums all its n (n - 1) / 2
// pairs when they are at most `max_pairs`, and otherwise estimates their sum
// from `max_pairs` pairs drawn at random with a fixed seed (the same world
// gives the same estimate): the sampled mean times the number of pairs,
// unbiased, but not exact (close pairs weigh much). The other fields cost one
// term per body. Throws calder::Error as potential_energy does.
struct PotentialEstimate {
  double value = 0.0;
  bool exact = true;               // every pair was summed
  std::uint64_t pairs_summed = 0;  // of the mutual attractions
  std::uint64_t pairs_total = 0;
};
PotentialEstimate bounded_potential_energy(const World& world, std::uint64_t max_pairs);

// The pair terms bounded_potential_energy evaluates: min(pairs, max_pairs)
// for each enabled mutual attraction, plus one per body for each other field.
std::uint64_t potential_energy_cost(const World& world, std::uint64_t max_pairs);

// The energy a display shows, the same in every front end (the renderer's
// HUD, the calder command's summary, Python, the web page): the kinetic
// energy and the potential in bounded time (bounded_potential_energy with
// max_pairs), or none where the fields have no potential (why_not: the
// reason, calder::Error's message).
struct DisplayedEnergy {
  double kinetic = 0.0;
  bool has_potential = false;
  PotentialEstimate potential;
  std::string why_not;  // when !has_potential
  // kinetic + potential (the kinetic energy alone without a potential).
  double total() const { return has_potential ? kinetic + potential.value : kinetic; }
  // Whether total() is exact: every pair summed.
  bool exact() const { return !has_potential || potential.exact; }
};
// The displays' budget a frame: about 5 ms; past it the potential is a
// sampled estimate, shown with a leading "~".
inline constexpr std::uint64_t kHudEnergyPairs = std::uint64_t{1} << 18;
DisplayedEnergy displayed_energy(const World& world, std::uint64_t max_pairs = kHudEnergyPairs);

// Sum of m v.
Vec2 linear_momentum(const World& world);

// Sum of m (r - origin) x v (the z component).
double angular_momentum(const World& world, Vec2 origin = {});

// Mass-weighted mean position.
Vec2 center_of_mass(const World& world);

// Whether the world's total energy (total_energy) should stay constant: every
// enabled field conserves it (gravity, attractors, mutual attraction under a
// law with a potential), there is no boundary rule and no speed limit.
// Drag, friction, wind, fans and bounces change it on purpose.
bool conserves_energy(const World& world);

// The relative energy error of a run since its start, |E - E0| / |E0|
// (|E - E0| when E0 is 0): what tells a user that a fixed step was too long
// for a close approach. Measure it after every frame (or every few), and
// warn the first time it passes the threshold.
inline constexpr double kDefaultEnergyThreshold = 1e-6;
// The most pair terms one measurement of the watch sums (potential_energy_cost):
// past them the exact energy costs more than a frame should, and a sampled
// estimate can't show an error of 1e-6, so the watch measures nothing.
inline constexpr std::uint64_t kEnergyWatchTerms = std::uint64_t{1} << 22;
// Whether the watch can measure this world: it conserves energy and its exact
// energy costs at most kEnergyWatchTerms terms.
bool energy_watchable(const World& world);
// |now - start| / |start|, or |now - start| when start is 0.
double relative_energy_error(double start, double now);
// The world's total energy now when the watch can measure it
// (energy_watchable, a known potential), else NaN.
double watched_energy(const World& world);
// What a run's error is measured from: the total energy of the simulation's
// scene at its first frame (built again when the run was resumed from a
// snapshot). NaN when the world isn't energy_watchable or a field's
// potential isn't known.
double start_energy(const Simulation& simulation);
class EnergyWatch {
 public:
  // Records the energy now; inactive (measures nothing) when the world isn't
  // energy_watchable or its potential isn't known.
  explicit EnergyWatch(const World& world, double threshold = kDefaultEnergyThreshold);
  // Measures from a start energy given (a run resumed from a snapshot: the
  // energy of its scene's first frame); inactive when not finite.
  EnergyWatch(const World& world, double threshold, double start_energy);
  // Measures the error now; true only the first time it passes the threshold.
  bool observe(const World& world, std::int64_t frame);
  [[nodiscard]] bool active() const { return active_; }
  [[nodiscard]] double start_energy() const { return start_; }
  [[nodiscard]] double last_error() const { return last_; }
  // The total energy the last observe measured (0 before the first).
  [[nodiscard]] double last_energy() const { return last_energy_; }
  [[nodiscard]] double worst_error() const { return worst_; }
  [[nodiscard]] double threshold() const { return threshold_; }
  // The first frame observed past the threshold, or -1.
  [[nodiscard]] std::int64_t first_frame_over() const { return first_over_; }

 private:
  bool active_ = false;
  double start_ = 0.0;
  double threshold_ = kDefaultEnergyThreshold;
  double last_ = 0.0;
  double last_energy_ = 0.0;
  double worst_ = 0.0;
  std::int64_t first_over_ = -1;
};

// A 64-bit hash of the bodies' state: count, positions, velocities, masses,
// radii, bit for bit. Same state, same hash; any changed bit changes it
// (with overwhelming probability).
std::uint64_t state_hash(const World& world);

// state_hash as the command, the Python module and the page print it: 16
// lowercase hexadecimal digits.
std::string state_hash_text(const World& world);

}  // namespace calder
