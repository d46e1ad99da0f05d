// SPDX-License-Identifier: MIT
// calder: numbers to trust a simulation by: energy, momentum, a state hash.
#pragma once

#include <cstdint>

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

}  // namespace calder
