// SPDX-License-Identifier: MIT
// calder: numbers to trust a simulation by: energy, momentum, a state hash.
#pragma once

#include <cstdint>
#include <string>

#include "calder/forces.hpp"
#include "calder/vec2.hpp"

namespace calder {

class World;

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

// A 64-bit hash of the bodies' state: count, positions, velocities, masses,
// radii, bit for bit. Same state, same hash; any changed bit changes it
// (with overwhelming probability).
std::uint64_t state_hash(const World& world);

// state_hash as the command, the Python module and the page print it: 16
// lowercase hexadecimal digits.
std::string state_hash_text(const World& world);

}  // namespace calder
