// SPDX-License-Identifier: MIT
// Tests of the adaptive integrator, IAS15, against exact solutions: a Kepler
// orbit of eccentricity 0.9 over 1,000 orbits (energy, and the pericentre
// where the two-body problem puts it), quadratic drag (closed form: a force
// of the velocity, resolved through the predictor-corrector iterations),
// frames that end exactly on dt, bits on any thread count, and the errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "calder/adaptive.hpp"
#include "calder/diagnostics.hpp"
#include "calder/error.hpp"
#include "calder/fields.hpp"
#include "calder/world.hpp"
#include "support/test_support.hpp"

namespace {

using calder::AttractionLaw;
using calder::Integrator;
using calder::Vec2;
using calder::World;
using calder::WorldDef;

constexpr double kPi = 3.141592653589793;

// A body of unit mass on a Kepler orbit of semi-major axis 1 around a fixed
// unit mass (G = 1): period 2 pi, starting at pericentre (1 - e, 0) with the
// vis-viva speed sqrt((1 + e) / (1 - e)).
World kepler_world(double e, double frame) {
  World world({.width = 10, .height = 10, .dt = frame, .integrator = Integrator::ias15});
  world.add(calder::Attractor{.position = {0, 0}, .mass = 1.0, .law = AttractionLaw::newtonian()});
  world.add_body({.position = {1 - e, 0}, .velocity = {0, std::sqrt((1 + e) / (1 - e))}});
  return world;
}

TEST(Ias15, KeplerEccentricity09Over1000OrbitsKeepsEnergyAndPericentre) {
  const double e = 0.9;
  World world = kepler_world(e, 2 * kPi);  // one frame per orbit
  const double e0 = calder::total_energy(world);
  EXPECT_DOUBLE_EQ(e0, -0.5);  // -G M m / (2 a)
  double worst = 0.0;
  for (int orbit = 0; orbit < 1000; ++orbit) {
    world.step();
    worst = std::max(worst, std::fabs((calder::total_energy(world) - e0) / e0));
  }
  EXPECT_LT(worst, 1e-12);
  // After whole periods the body is back at pericentre: (1 - e, 0), moving up.
  const Vec2 p = world.position(world.body(0));
  const Vec2 v = world.velocity(world.body(0));
  EXPECT_NEAR(p.x, 1 - e, 1e-9);
  EXPECT_NEAR(p.y, 0.0, 1e-8);  // the phase: 1e-8 / 4.4 per unit speed
  // The eccentricity vector (v x (r x v)) / GM - r / |r| points at the
  // pericentre: no precession beyond rounding.
  const double h = p.x * v.y - p.y * v.x;
  const Vec2 ecc{v.y * h - p.x / p.mag(), -v.x * h - p.y / p.mag()};
  EXPECT_NEAR(ecc.mag(), e, 1e-11);
  EXPECT_NEAR(std::atan2(ecc.y, ecc.x), 0.0, 1e-11);
  // Close to the published cost (about 98 steps an orbit at this tolerance).
  EXPECT_GT(world.adaptive_stats().steps, 50'000);
  EXPECT_LT(world.adaptive_stats().steps, 200'000);
}

TEST(Ias15, AFrameEndsExactlyOnDtAndTheStepCarriesOver) {
  World world = kepler_world(0.5, 0.1);
  for (int k = 1; k <= 100; ++k) {
    world.step();
    EXPECT_EQ(world.step_count(), k);
  }
  EXPECT_NEAR(world.time(), 10.0, 1e-14);
  const calder::AdaptiveStats& stats = world.adaptive_stats();
  EXPECT_GE(stats.steps, 100);  // at least one internal step a frame
  EXPECT_GT(world.adaptive_state().next_step, 0.0);
  // Ten frames of 0.1 and one of 1.0 end at the same state to the integrator's accuracy.
  World fine = kepler_world(0.5, 0.1);
  World coarse = kepler_world(0.5, 1.0);
  fine.step(10);
  coarse.step();
  const Vec2 a = fine.position(fine.body(0));
  const Vec2 b = coarse.position(coarse.body(0));
  EXPECT_NEAR(a.x, b.x, 1e-13);
  EXPECT_NEAR(a.y, b.y, 1e-13);
}

TEST(Ias15, TheClockIsSummedWithCompensation) {
  World world({.dt = 0.1, .integrator = Integrator::ias15});
  world.step(700);
  EXPECT_EQ(world.time(), 70.0);  // 700 naive additions of 0.1 give 70.00000000000136
}

// Quadratic drag alone, a force of the velocity: m v' = -c v^2, so
// v(t) = v0 / (1 + c v0 t / m) and x(t) = (m / c) ln(1 + c v0 t / m).
TEST(Ias15, QuadraticDragFollowsItsClosedForm) {
  const double c = 0.3;
  const double m = 2.0;
  const double v0 = 5.0;
  World world({.width = 1e3, .height = 1e3, .dt = 0.5, .integrator = Integrator::ias15});
  world.add(calder::Drag{.c = c});
  world.add_body({.position = {0, 0}, .velocity = {v0, 0}, .mass = m});
  world.step(20);
  const double t = 10.0;
  const Vec2 v = world.velocity(world.body(0));
  const Vec2 x = world.position(world.body(0));
  EXPECT_NEAR(v.x, v0 / (1 + c * v0 * t / m), 1e-14);
  EXPECT_NEAR(x.x, m / c * std::log(1 + c * v0 * t / m), 1e-13);
}

// Five bodies under direct-summation mutual attraction: the same bits on 1,
// 2 and 4 threads.
TEST(Ias15, TheSameBitsOnAnyThreadCount) {
  std::vector<std::uint64_t> hashes;
  for (const int threads : {1, 2, 4}) {
    World world({.width = 10, .height = 10, .dt = 0.25, .integrator = Integrator::ias15});
    calder::MutualAttraction mutual{.law = AttractionLaw::newtonian(1.0, 0.01)};
    mutual.method = calder::NBodyMethod::direct;
    mutual.threads = threads;
    world.add(mutual);
    for (int i = 0; i < 5; ++i) {
      world.add_body({.position = {std::cos(i * 1.3) * (1 + 0.1 * i), std::sin(i * 1.3)},
                      .velocity = {-0.3 * std::sin(i * 1.3), 0.3 * std::cos(i * 1.3)},
                      .mass = 1.0 + 0.2 * i});
    }
    world.step(40);
    hashes.push_back(calder::state_hash(world));
  }
  EXPECT_EQ(hashes[0], hashes[1]);
  EXPECT_EQ(hashes[0], hashes[2]);
}

TEST(Ias15, RefusesBarnesHutAndABadTolerance) {
  World world({.integrator = Integrator::ias15});
  calder::MutualAttraction mutual{.law = AttractionLaw::newtonian()};
  mutual.method = calder::NBodyMethod::barnes_hut;
  world.add(mutual);
  world.add_body({.position = {1, 1}});
  world.add_body({.position = {2, 1}});
  calder::test::expect_error([&] { world.step(); }, {"ias15", "Barnes-Hut"});
  EXPECT_EQ(world.step_count(), 0);
  calder::test::expect_error([&] { world.set_tolerance(0.0); }, {"tolerance"});
  World bad({.integrator = Integrator::ias15, .tolerance = -1.0});
  bad.add_body({});
  calder::test::expect_error([&] { bad.step(); }, {"tolerance"});
}

// Two point masses falling straight into each other: the step shrinks until
// it can't, and the world says so instead of returning a NaN.
TEST(Ias15, AHeadOnCollisionOfPointMassesIsAnErrorNotANaN) {
  World world({.width = 10, .height = 10, .dt = 10.0, .integrator = Integrator::ias15});
  world.add(calder::MutualAttraction{.law = AttractionLaw::newtonian()});
  world.add_body({.position = {0, 0}});
  world.add_body({.position = {1, 0}});
  EXPECT_THROW(world.step(), calder::RunError);
  EXPECT_EQ(world.position(world.body(1)).x, 1.0);  // left as it was
  EXPECT_EQ(world.step_count(), 0);
}

// A frame far too long for a bound orbit: an error after 100,000 internal
// steps, not a hang.
TEST(Ias15, AFrameThatNeedsTooManyStepsIsAnError) {
  World world = kepler_world(0.5, 1e300);
  calder::test::expect_error([&] { world.step(); }, {"internal steps", "smaller dt"});
  EXPECT_EQ(world.step_count(), 0);
  EXPECT_EQ(world.position(world.body(0)).x, 0.5);
}

}  // namespace
