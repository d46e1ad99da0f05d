// SPDX-License-Identifier: MIT
// Tests of the conservation laws a world obeys, and of its determinism.
//
//  - Linear momentum: with the simultaneous update, MutualAttraction applies
//    +F and exactly -F to each pair, so sum m v changes only by rounding.
//  - Angular momentum: pairwise central forces exert no net torque; semi-
//    implicit Euler and velocity Verlet are compositions of "kicks"
//    (v += dt F / m, which change L by dt sum x x F = 0) and "drifts"
//    (x += dt v, which change L by dt sum m v x v = 0), so they conserve L up
//    to rounding; RK4 does not (only to its truncation error).
//  - Energy: the piecewise potential of the clamped book law is the integral
//    of its force, so a symplectic integration conserves it to O(dt^2).
//  - state_hash and copies: same state, same bits, same hash.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <ostream>
#include <string_view>
#include <vector>

#include "calder/diagnostics.hpp"
#include "calder/error.hpp"
#include "calder/fields.hpp"
#include "calder/forces.hpp"
#include "calder/random.hpp"
#include "calder/scene.hpp"
#include "calder/vec2.hpp"
#include "calder/world.hpp"
#include "support/test_support.hpp"

namespace {

using calder::AttractionLaw;
using calder::BodyId;
using calder::DistanceClamp;
using calder::Integrator;
using calder::MassProduct;
using calder::UpdateOrder;
using calder::Vec2;
using calder::World;
using calder::WorldDef;

// n bodies drawn from a seeded generator: position in the 640 x 240 canvas,
// mass in [0.5, 3), velocity components in [-1, 1).
void add_random_bodies(World& world, std::uint32_t seed, int n) {
  calder::Random rng(seed);
  for (int i = 0; i < n; ++i) {
    const double x = rng.random(640.0);
    const double y = rng.random(240.0);
    const double m = rng.random(0.5, 3.0);
    const Vec2 v{rng.random(-1.0, 1.0), rng.random(-1.0, 1.0)};
    world.add_body({.position = {x, y}, .velocity = v, .mass = m});
  }
}

// sum_i m_i |v_i|: the scale momentum errors are measured against (rounding
// in sum m v is relative to it, and it does not vanish when P does).
double momentum_scale(const World& world) {
  const calder::BodyView b = world.bodies();
  double s = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i) s += b.mass[i] * b.velocity(i).mag();
  return s;
}

// sum_i m_i |x_i| |v_i|: the same for the angular momentum about the origin.
double angular_scale(const World& world) {
  const calder::BodyView b = world.bodies();
  double s = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    s += b.mass[i] * b.position(i).mag() * b.velocity(i).mag();
  }
  return s;
}

// ============================================================ linear momentum ===

struct MomentumCase {
  const char* law_name;
  AttractionLaw law;
  double dt;
};

std::vector<MomentumCase> momentum_cases() {
  return {{"book (clamped)", AttractionLaw::book(), 1.0},
          {"newtonian softened", AttractionLaw::newtonian(1.0, 2.0), 0.5}};
}

TEST(ConservationMomentum, MutualAttractionConservesMomentumAndAngularMomentum) {
  // 30 bodies; 10^4 steps of the book's update, 1000 of Verlet and RK4 (each
  // of their steps evaluates the forces 2 and 4 times). Checked every 500
  // steps. |P(t) - P(0)| / sum m |v(0)| <= 1e-12 (rounding only; measured
  // ~1e-14). Angular momentum about the origin likewise for the two
  // symplectic methods, relative to sum m |x| |v|.
  const struct {
    Integrator integrator;
    int steps;
  } runs[] = {{Integrator::semi_implicit_euler, 10000},
              {Integrator::velocity_verlet, 1000},
              {Integrator::rk4, 1000}};
  for (const MomentumCase& c : momentum_cases()) {
    for (const auto& run : runs) {
      World world(WorldDef{.dt = c.dt, .integrator = run.integrator});
      world.add(calder::MutualAttraction{.law = c.law});
      add_random_bodies(world, 7, 30);
      const Vec2 p0 = calder::linear_momentum(world);
      const double l0 = calder::angular_momentum(world);
      const double p_scale = momentum_scale(world);
      const double l_scale = angular_scale(world);
      double max_l_error = 0.0;
      for (int done = 0; done < run.steps; done += 500) {
        world.step(500);
        const double p_error = (calder::linear_momentum(world) - p0).mag() / p_scale;
        ASSERT_LE(p_error, 1e-12) << c.law_name << ", " << calder::integrator_name(run.integrator)
                                  << ", step " << done + 500;
        max_l_error =
            std::max(max_l_error, std::abs(calder::angular_momentum(world) - l0) / l_scale);
      }
      if (run.integrator == Integrator::rk4) {
        // Not a symplectic composition of kicks and drifts: L drifts by its
        // truncation error, far above rounding. This shows the measurement
        // above can detect a change in L.
        EXPECT_GT(max_l_error, 1e-10) << c.law_name;
      } else {
        EXPECT_LE(max_l_error, 1e-12)
            << c.law_name << ", " << calder::integrator_name(run.integrator);
      }
      // The bodies really interacted: the velocities changed by O(1).
      EXPECT_GT(std::abs(momentum_scale(world) - p_scale), 0.1 * p_scale) << c.law_name;
    }
  }
}

TEST(ConservationMomentum, SequentialOrderDoesNotConserveMomentum) {
  // Example 2.9 as the book runs it: body i moves before body i + 1 feels the
  // forces, so the pair forces of one step come from different states and no
  // longer cancel: momentum changes by O(dt) amounts. The simultaneous update
  // of the same world conserves it to rounding. 10 bodies at rest, masses in
  // [0.1, 2), G = 1, d clamped to [5, 25], dt = 1 frame.
  const auto make = [](UpdateOrder order) {
    World world(WorldDef{.update_order = order, .seed = 5});
    world.add(calder::MutualAttraction{.law = AttractionLaw::book()});
    for (int i = 0; i < 10; ++i) {
      const double x = world.random().random(640.0);
      const double y = world.random().random(240.0);
      const double m = world.random().random(0.1, 2.0);
      world.add_body({.position = {x, y}, .mass = m});
    }
    return world;
  };
  World sequential = make(UpdateOrder::sequential);
  World simultaneous = make(UpdateOrder::simultaneous);
  ASSERT_EQ(calder::state_hash(sequential), calder::state_hash(simultaneous));
  double max_sequential = 0.0;
  double max_simultaneous = 0.0;
  for (int k = 0; k < 20; ++k) {
    sequential.step(10);
    simultaneous.step(10);
    // Both start at rest (P = 0); measure against the current sum m |v|.
    max_sequential = std::max(
        max_sequential, calder::linear_momentum(sequential).mag() / momentum_scale(sequential));
    max_simultaneous = std::max(max_simultaneous, calder::linear_momentum(simultaneous).mag() /
                                                      momentum_scale(simultaneous));
  }
  EXPECT_LE(max_simultaneous, 1e-12);
  EXPECT_GT(max_sequential, 1e-2);  // measured ~0.25
  EXPECT_NE(calder::state_hash(sequential), calder::state_hash(simultaneous));
}

TEST(ConservationAngularMomentum, KeplerOrbitAboutFixedAttractor) {
  // A central force about a fixed attractor: L about the attractor is
  // conserved. Eccentric orbit (e = 0.5, mu = 1, a = 1: periapsis 0.5, speed
  // sqrt(3) there) with a coarse 200 steps per period over 20 periods; Verlet
  // and Euler keep L to rounding although their energy and orbit are off by
  // far more.
  const Vec2 centre{3.0, -2.0};
  const double period = 2.0 * 3.141592653589793;
  for (const Integrator integrator :
       {Integrator::semi_implicit_euler, Integrator::velocity_verlet}) {
    World world(WorldDef{.dt = period / 200.0, .integrator = integrator});
    world.add(
        calder::Attractor{.position = centre, .mass = 1.0, .law = AttractionLaw::newtonian(1.0)});
    world.add_body(
        {.position = centre + Vec2{0.5, 0.0}, .velocity = {0.0, std::sqrt(3.0)}, .mass = 2.0});
    const double l0 = calder::angular_momentum(world, centre);
    EXPECT_NEAR(l0, 2.0 * 0.5 * std::sqrt(3.0), 1e-15);  // m r v at periapsis
    double max_error = 0.0;
    for (int k = 0; k < 4000; ++k) {
      world.step();
      max_error = std::max(max_error, std::abs(calder::angular_momentum(world, centre) - l0));
    }
    EXPECT_LE(max_error / l0, 1e-13) << calder::integrator_name(integrator);
  }
}

// ===================================================================== energy ===

// Signed force magnitude toward the source at distance d (along +x).
double force_toward_source(double d, double source_mass, double target_mass,
                           const AttractionLaw& law) {
  const Vec2 f = calder::attraction({0.0, 0.0}, source_mass, {d, 0.0}, target_mass, law);
  return -f.x;
}

TEST(ConservationEnergy, PotentialDerivativeIsTheForce) {
  // F(d) = dU/dd (the force toward the source is the slope of the potential)
  // in all three regimes of the clamped laws: U'(d) = G M m / c(d)^2 with c(d)
  // the clamped distance. Central differences, h = 1e-5 d: truncation
  // (h / d)^2 = 1e-10 relative (exact for -k / d: k / (d^2 - h^2)), rounding
  // ~ 1e-16 |U| / (h F) <= 1e-10.
  AttractionLaw squared = AttractionLaw::book(1.0, 100.0, 1000.0, MassProduct::masses_first);
  squared.clamp = DistanceClamp::squared_distance;
  const struct {
    const char* name;
    AttractionLaw law;
    double lo;  // clamp range of the distance (0, inf for no clamp)
    double hi;
    std::vector<double> distances;
  } cases[] = {
      {"book",
       AttractionLaw::book(1.5, 5.0, 25.0),
       5.0,
       25.0,
       {0.5, 2.0, 4.5, 6.0, 10.0, 24.0, 30.0, 400.0}},
      {"book repulsive", AttractionLaw::book(-1.0, 5.0, 25.0), 5.0, 25.0, {3.0, 10.0, 50.0}},
      {"squared", squared, 10.0, std::sqrt(1000.0), {2.0, 9.0, 12.0, 20.0, 31.0, 40.0, 200.0}},
      {"newtonian", AttractionLaw::newtonian(2.0), 0.0, 1e300, {0.5, 3.0, 10.0, 50.0}},
  };
  const double M = 20.0;
  const double m = 2.0;
  for (const auto& c : cases) {
    for (const double d : c.distances) {
      const double h = 1e-5 * d;
      const double slope = (calder::attraction_potential(d + h, M, m, c.law) -
                            calder::attraction_potential(d - h, M, m, c.law)) /
                           (2.0 * h);
      const double clamped = std::clamp(d, c.lo, c.hi);
      const double expected = c.law.G * M * m / (clamped * clamped);
      EXPECT_NEAR(slope, expected, 1e-8 * std::abs(expected)) << c.name << ", d " << d;
      EXPECT_NEAR(force_toward_source(d, M, m, c.law), expected, 1e-13 * std::abs(expected))
          << c.name << ", d " << d;
    }
  }
  // Plummer: U = -G M m / sqrt(d^2 + eps^2), U' = G M m d / (d^2 + eps^2)^(3/2).
  const AttractionLaw plummer = AttractionLaw::newtonian(2.0, 3.0);
  for (const double d : {0.1, 1.0, 3.0, 10.0, 100.0}) {
    const double h = 1e-5 * d;
    const double slope = (calder::attraction_potential(d + h, M, m, plummer) -
                          calder::attraction_potential(d - h, M, m, plummer)) /
                         (2.0 * h);
    EXPECT_NEAR(slope, force_toward_source(d, M, m, plummer), 1e-8 * slope) << "plummer, d " << d;
  }
  // Newton's potential is -G M m / d, zero at infinity; the clamped ones are
  // -G M m / d inside the clamp and continuous at its ends.
  EXPECT_DOUBLE_EQ(calder::attraction_potential(8.0, M, m, AttractionLaw::newtonian(2.0)),
                   -2.0 * M * m / 8.0);
  const AttractionLaw book = AttractionLaw::book();
  EXPECT_DOUBLE_EQ(calder::attraction_potential(10.0, M, m, book), -M * m / 10.0);
  for (const double edge : {5.0, 25.0}) {
    EXPECT_NEAR(calder::attraction_potential(edge * (1.0 - 1e-12), M, m, book),
                calder::attraction_potential(edge * (1.0 + 1e-12), M, m, book), 1e-9);
  }
}

struct ThreeBodyRun {
  double max_relative_error = 0.0;  // max |E - E0| / (K0 + |U0|)
  double min_distance = 1e300;
  double max_distance = 0.0;
};

ThreeBodyRun three_body(double dt, double duration) {
  World world(WorldDef{.dt = dt, .integrator = Integrator::velocity_verlet});
  world.add(calder::MutualAttraction{.law = AttractionLaw::book()});
  // Zero total momentum: 8 v1 + 6 v2 + 4 v3 = 0.
  const Vec2 v1{-0.25, -0.1};
  const Vec2 v2{0.05, 0.0};
  world.add_body({.position = {0.0, 0.0}, .velocity = v1, .mass = 8.0});
  world.add_body({.position = {40.0, 0.0}, .velocity = v2, .mass = 6.0});
  world.add_body({.position = {15.0, 30.0}, .velocity = -(v1 * 8.0 + v2 * 6.0) / 4.0, .mass = 4.0});
  const double e0 = calder::total_energy(world);
  const double scale = calder::kinetic_energy(world) +
                       std::abs(calder::potential_energy(world, AttractionLaw::book()));
  ThreeBodyRun run;
  const int steps = static_cast<int>(duration / dt);
  for (int k = 0; k < steps; ++k) {
    world.step();
    run.max_relative_error =
        std::max(run.max_relative_error, std::abs(calder::total_energy(world) - e0) / scale);
    for (std::size_t i = 0; i < 3; ++i) {
      for (std::size_t j = i + 1; j < 3; ++j) {
        const double d = world.position(world.body(i)).dist(world.position(world.body(j)));
        run.min_distance = std::min(run.min_distance, d);
        run.max_distance = std::max(run.max_distance, d);
      }
    }
  }
  return run;
}

TEST(ConservationEnergy, ClampedThreeBodyWithVerlet) {
  // Three bodies under the book's law (d clamped to [5, 25]) that pass below
  // 5 and beyond 25. The clamped force is continuous, the potential is its
  // integral (C^1), so Verlet's energy error is O(dt^2): halving dt divides it
  // by ~4. A potential inconsistent with the clamped force (e.g. -G M m / d
  // everywhere) would leave an O(1) error that does not shrink with dt.
  // (The close passages dominate: ~1e-5 at dt = 0.01; ~1e-6 would need
  // dt ~ 0.003.)
  const ThreeBodyRun coarse = three_body(0.02, 200.0);
  const ThreeBodyRun fine = three_body(0.01, 200.0);
  EXPECT_LT(fine.min_distance, 5.0) << "the run must enter the inner clamp";
  EXPECT_GT(fine.max_distance, 25.0) << "the run must leave the outer clamp";
  EXPECT_LT(fine.max_relative_error, 3e-5);
  const double ratio = coarse.max_relative_error / fine.max_relative_error;
  EXPECT_GT(ratio, 3.0);
  EXPECT_LT(ratio, 5.5);
}

// ================================================================ determinism ===

// A small world with most kinds of state: 12 random bodies from the world's
// own generator, mutual attraction, an attractor, drag in a liquid, wind.
World make_world(std::uint32_t seed) {
  World world(WorldDef{.integrator = Integrator::velocity_verlet, .seed = seed});
  world.add(calder::MutualAttraction{.law = AttractionLaw::book(0.5)});
  world.add(calder::Attractor{.position = {320.0, 120.0}, .mass = 20.0});
  world.add(calder::Liquid{});
  world.add(calder::NoiseWind{.strength = 0.05});
  calder::Random& rng = world.random();
  for (int i = 0; i < 12; ++i) {
    const double x = rng.random(640.0);
    const double y = rng.random(240.0);
    const double m = rng.random(0.5, 3.0);
    world.add_body(
        {.position = {x, y}, .velocity = Vec2::random2d(rng), .mass = m, .radius = m * 8.0});
  }
  return world;
}

// The error a run reports is measured from its scene's first frame, also
// when the run was resumed part-way (the start is built again, same bits).
TEST(ConservationEnergy, ARunsStartEnergyIsItsFirstFramesEvenWhenResumed) {
  calder::Simulation run(calder::builtin_scene("figure-eight"));
  const double first = calder::total_energy(run.world());
  EXPECT_EQ(calder::start_energy(run), first);
  for (int k = 0; k < 50; ++k) run.step();
  ASSERT_EQ(run.frame(), 50);  // start_energy builds the start again
  EXPECT_EQ(calder::start_energy(run), first);
  // The book's wind and bounces change the energy on purpose: nothing to measure.
  EXPECT_TRUE(
      std::isnan(calder::start_energy(calder::Simulation(calder::builtin_scene("example-2.1")))));
}

TEST(ConservationEnergy, RelativeErrorIsTheChangeOverTheStart) {
  EXPECT_EQ(calder::relative_energy_error(10.0, 9.0), 0.1);
  EXPECT_EQ(calder::relative_energy_error(-4.0, -3.0), 0.25);
  EXPECT_EQ(calder::relative_energy_error(-4.0, -4.0), 0.0);
  EXPECT_EQ(calder::relative_energy_error(0.0, 2.0), 2.0);  // no scale: the change itself
  EXPECT_TRUE(std::isnan(calder::relative_energy_error(1.0, std::nan(""))));
}

TEST(ConservationDeterminism, SameSeedSameHash) {
  World a = make_world(11);
  World b = make_world(11);
  EXPECT_EQ(calder::state_hash(a), calder::state_hash(b));
  a.step(300);
  b.step(300);
  EXPECT_EQ(calder::state_hash(a), calder::state_hash(b));
  for (std::size_t i = 0; i < a.body_count(); ++i) {
    ASSERT_EQ(a.position(a.body(i)), b.position(b.body(i)));
    ASSERT_EQ(a.velocity(a.body(i)), b.velocity(b.body(i)));
  }
  // The state really moved (the hash is not of the initial state).
  EXPECT_NE(calder::state_hash(a), calder::state_hash(make_world(11)));
}

TEST(ConservationDeterminism, DifferentSeedsDifferentHash) {
  EXPECT_NE(calder::state_hash(make_world(11)), calder::state_hash(make_world(12)));
  EXPECT_NE(calder::state_hash(make_world(0)), calder::state_hash(make_world(1)));
}

TEST(ConservationDeterminism, OneBitChangesTheHash) {
  // Every hashed quantity, one ulp away in one body, and the body count.
  const World base = make_world(3);
  const std::uint64_t h = calder::state_hash(base);
  const BodyId id = base.body(5);
  const auto changed = [&](auto mutate) {
    World w = base;
    mutate(w);
    return calder::state_hash(w);
  };
  const Vec2 p = base.position(id);
  const Vec2 v = base.velocity(id);
  EXPECT_NE(h, changed([&](World& w) { w.set_position(id, {std::nextafter(p.x, 1e9), p.y}); }));
  EXPECT_NE(h, changed([&](World& w) { w.set_position(id, {p.x, std::nextafter(p.y, -1e9)}); }));
  EXPECT_NE(h, changed([&](World& w) { w.set_velocity(id, {std::nextafter(v.x, 1e9), v.y}); }));
  EXPECT_NE(h, changed([&](World& w) { w.set_velocity(id, {v.x, std::nextafter(v.y, 1e9)}); }));
  EXPECT_NE(h, changed([&](World& w) { w.set_mass(id, std::nextafter(base.mass(id), 1e9)); }));
  EXPECT_NE(h, changed([&](World& w) { w.set_radius(id, std::nextafter(base.radius(id), 1e9)); }));
  EXPECT_NE(h, changed([&](World& w) { w.add_body({}); }));
  // Unchanged values leave it unchanged.
  EXPECT_EQ(h, changed([&](World& w) { w.set_position(id, p); }));
  // Bit for bit: 0.0 and -0.0 are different states to the hash.
  World zero = base;
  zero.set_velocity(id, {0.0, 0.0});
  World minus_zero = base;
  minus_zero.set_velocity(id, {-0.0, 0.0});
  EXPECT_NE(calder::state_hash(zero), calder::state_hash(minus_zero));
}

TEST(ConservationDeterminism, CopiesAreIndependentAndStepIdentically) {
  World original = make_world(21);
  original.step(50);
  World copy = original;
  EXPECT_EQ(calder::state_hash(copy), calder::state_hash(original));
  EXPECT_EQ(copy.time(), original.time());
  EXPECT_EQ(copy.step_count(), original.step_count());
  // The generators are copied too: the same draws follow.
  EXPECT_EQ(copy.random().random(), original.random().random());
  copy.step(200);
  original.step(200);
  EXPECT_EQ(calder::state_hash(copy), calder::state_hash(original));
  // A copy is a value: stepping or changing one leaves the other alone.
  World other = original;
  other.step();
  EXPECT_NE(calder::state_hash(other), calder::state_hash(original));
  const std::uint64_t before = calder::state_hash(original);
  World no_fields = original;
  no_fields.clear_fields();
  no_fields.step(10);
  original.step(10);
  EXPECT_NE(calder::state_hash(no_fields), calder::state_hash(original));
  EXPECT_NE(calder::state_hash(original), before);
  EXPECT_EQ(original.fields().size(), 4U) << "clearing the copy's fields left the original's";
}

}  // namespace
