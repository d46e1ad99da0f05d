// SPDX-License-Identifier: MIT
#include "calder/diagnostics.hpp"

#include <algorithm>
#include <array>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <type_traits>
#include <variant>
#include <vector>

#include "calder/error.hpp"
#include "calder/scene.hpp"
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

namespace {

// The potential energy of the world's enabled conservative fields, in their
// order; `pairs` gives a mutual attraction's pair sum.
template <class PairSum>
double field_potential(const World& world, PairSum&& pairs) {
  const BodyView b = world.bodies();
  double sum = 0.0;
  for (const Field& field : world.fields()) {
    if (const auto* mutual = std::get_if<MutualAttraction>(&field)) {
      if (!mutual->enabled) continue;
      sum += pairs(mutual->law);
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

}  // namespace

double potential_energy(const World& world) {
  return field_potential(world,
                         [&](const AttractionLaw& law) { return potential_energy(world, law); });
}

double total_energy(const World& world) { return kinetic_energy(world) + potential_energy(world); }

namespace {

// splitmix64's step and finaliser (Steele, Lea, Flood 2014).
std::uint64_t splitmix(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30U)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27U)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31U);
}

std::uint64_t pair_count(std::size_t n) {
  const auto m = static_cast<std::uint64_t>(n);
  return m < 2 ? 0 : m * (m - 1) / 2;
}

// The pair sum of `law` from `samples` pairs (i != j, uniform, fixed seed),
// scaled to all pairs.
double sampled_pair_potential(const BodyView& b, const AttractionLaw& law, std::uint64_t samples) {
  const auto n = static_cast<std::uint64_t>(b.size());
  std::uint64_t state = 0x706f74656e7469ULL;  // "potenti"
  double sum = 0.0;
  for (std::uint64_t k = 0; k < samples; ++k) {
    const auto i = static_cast<std::size_t>(splitmix(state) % n);
    auto j = static_cast<std::size_t>(splitmix(state) % (n - 1));
    if (j >= i) ++j;
    sum += attraction_potential(b.position(i).dist(b.position(j)), b.mass[i], b.mass[j], law);
  }
  return sum / static_cast<double>(samples) * static_cast<double>(pair_count(b.size()));
}

}  // namespace

PotentialEstimate bounded_potential_energy(const World& world, std::uint64_t max_pairs) {
  max_pairs = std::max<std::uint64_t>(max_pairs, 1);
  const BodyView b = world.bodies();
  const std::uint64_t pairs = pair_count(b.size());
  PotentialEstimate result;
  result.value = field_potential(world, [&](const AttractionLaw& law) {
    result.pairs_total += pairs;
    if (pairs <= max_pairs) {
      result.pairs_summed += pairs;
      return potential_energy(world, law);
    }
    result.pairs_summed += max_pairs;
    result.exact = false;
    return sampled_pair_potential(b, law, max_pairs);
  });
  return result;
}

std::uint64_t potential_energy_cost(const World& world, std::uint64_t max_pairs) {
  const auto n = static_cast<std::uint64_t>(world.body_count());
  std::uint64_t cost = 0;
  for (const Field& field : world.fields()) {
    const auto* mutual = std::get_if<MutualAttraction>(&field);
    if (mutual != nullptr && mutual->enabled) {
      cost += std::min(pair_count(world.body_count()), max_pairs) + n;
    } else {
      cost += n;
    }
  }
  return cost;
}

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

std::string state_hash_text(const World& world) {
  std::array<char, 17> text{};
  std::snprintf(text.data(), text.size(), "%016" PRIx64, state_hash(world));
  return text.data();
}

DisplayedEnergy displayed_energy(const World& world, std::uint64_t max_pairs) {
  DisplayedEnergy e;
  e.kinetic = kinetic_energy(world);
  try {
    e.potential = bounded_potential_energy(world, max_pairs);
    e.has_potential = true;
  } catch (const Error& error) {
    e.why_not = error.what();  // a field without a potential (wind, a custom law)
  }
  return e;
}

bool conserves_energy(const World& world) {
  if (world.boundary().kind != BoundaryKind::none || world.max_speed() > 0.0) return false;
  for (const Field& field : world.fields()) {
    const bool conservative = std::visit(
        [](const auto& f) {
          using F = std::decay_t<decltype(f)>;
          if (!f.enabled) return true;
          if constexpr (std::is_same_v<F, Gravity>) return true;
          if constexpr (std::is_same_v<F, Attractor> || std::is_same_v<F, MutualAttraction>) {
            return !f.law.custom;
          }
          return false;
        },
        field);
    if (!conservative) return false;
  }
  return true;
}

bool energy_watchable(const World& world) {
  return conserves_energy(world) &&
         potential_energy_cost(world, std::numeric_limits<std::uint64_t>::max()) <=
             kEnergyWatchTerms;
}

EnergyWatch::EnergyWatch(const World& world, double threshold) : threshold_(threshold) {
  if (!energy_watchable(world)) return;
  start_ = total_energy(world);
  active_ = std::isfinite(start_);
}

EnergyWatch::EnergyWatch(const World& world, double threshold, double start_energy)
    : threshold_(threshold) {
  if (!energy_watchable(world)) return;
  start_ = start_energy;
  active_ = std::isfinite(start_);
}

double relative_energy_error(double start, double now) {
  const double change = std::fabs(now - start);
  return start != 0.0 ? change / std::fabs(start) : change;
}

double watched_energy(const World& world) {
  try {
    if (energy_watchable(world)) return total_energy(world);
  } catch (const Error&) {
    // no known potential: not measured
  }
  return std::numeric_limits<double>::quiet_NaN();
}

double start_energy(const Simulation& simulation) {
  if (simulation.frame() == 0) return watched_energy(simulation.world());
  return watched_energy(Simulation(simulation.scene()).world());
}

bool EnergyWatch::observe(const World& world, std::int64_t frame) {
  if (!active_) return false;
  last_energy_ = total_energy(world);
  last_ = relative_energy_error(start_, last_energy_);
  if (!(last_ <= worst_)) worst_ = last_;  // a NaN is the worst
  if (first_over_ >= 0 || !(last_ > threshold_ || std::isnan(last_))) return false;
  first_over_ = frame;
  return true;
}

}  // namespace calder
