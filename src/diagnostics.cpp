// SPDX-License-Identifier: MIT
#include "calder/diagnostics.hpp"

#include <cmath>
#include <cstring>
#include <variant>

#include "calder/world.hpp"

namespace calder {

double kinetic_energy(const World& world) {
  const BodyView b = world.bodies();
  double sum = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    sum += 0.5 * b.mass[i] * (b.vx[i] * b.vx[i] + b.vy[i] * b.vy[i]);
  }
  return sum;
}

double potential_energy(const World& world, const AttractionLaw& law) {
  const BodyView b = world.bodies();
  double sum = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    for (std::size_t j = i + 1; j < b.size(); ++j) {
      sum += attraction_potential(b.position(i).dist(b.position(j)), b.mass[i], b.mass[j], law);
    }
  }
  return sum;
}

double potential_energy(const World& world) {
  const BodyView b = world.bodies();
  double sum = 0.0;
  for (const Field& field : world.fields()) {
    if (const auto* mutual = std::get_if<MutualAttraction>(&field)) {
      if (!mutual->enabled) continue;
      sum += potential_energy(world, mutual->law);
      if (mutual->central) {
        for (std::size_t i = 0; i < b.size(); ++i) {
          sum += attraction_potential(mutual->central->position.dist(b.position(i)),
                                      mutual->central->mass, b.mass[i], mutual->law);
        }
      }
    } else if (const auto* attractor = std::get_if<Attractor>(&field)) {
      if (!attractor->enabled) continue;
      for (std::size_t i = 0; i < b.size(); ++i) {
        sum += attraction_potential(attractor->position.dist(b.position(i)), attractor->mass,
                                    b.mass[i], attractor->law);
      }
    } else if (const auto* g = std::get_if<Gravity>(&field)) {
      if (!g->enabled) continue;
      for (std::size_t i = 0; i < b.size(); ++i) {
        sum -= gravity(g->g, b.mass[i], g->scale_by_mass).dot(b.position(i));
      }
    }
  }
  return sum;
}

double total_energy(const World& world) { return kinetic_energy(world) + potential_energy(world); }

Vec2 linear_momentum(const World& world) {
  const BodyView b = world.bodies();
  Vec2 p;
  for (std::size_t i = 0; i < b.size(); ++i) p += b.velocity(i) * b.mass[i];
  return p;
}

double angular_momentum(const World& world, Vec2 origin) {
  const BodyView b = world.bodies();
  double l = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    l += b.mass[i] * (b.position(i) - origin).cross(b.velocity(i));
  }
  return l;
}

Vec2 center_of_mass(const World& world) {
  const BodyView b = world.bodies();
  Vec2 weighted;
  double total = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    weighted += b.position(i) * b.mass[i];
    total += b.mass[i];
  }
  return total > 0.0 ? weighted / total : Vec2{};
}

namespace {

// splitmix64's finaliser (Steele, Lea, Flood 2014): a strong 64-bit mixer.
std::uint64_t mix(std::uint64_t z) {
  z = (z ^ (z >> 30U)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27U)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31U);
}

std::uint64_t combine(std::uint64_t h, std::uint64_t word) {
  return mix(h ^ (word + 0x9e3779b97f4a7c15ULL + (h << 6U) + (h >> 2U)));
}

std::uint64_t bits_of(double v) {
  std::uint64_t u = 0;
  std::memcpy(&u, &v, sizeof u);  // std::bit_cast is not in Emscripten's libc++ 13
  return u;
}

}  // namespace

std::uint64_t state_hash(const World& world) {
  const BodyView b = world.bodies();
  std::uint64_t h = combine(0x63616c646572ULL, b.size());  // "calder"
  for (std::size_t i = 0; i < b.size(); ++i) {
    for (const double v : {b.x[i], b.y[i], b.vx[i], b.vy[i], b.mass[i], b.radius[i]}) {
      h = combine(h, bits_of(v));
    }
  }
  return h;
}

}  // namespace calder
