// SPDX-License-Identifier: MIT
// The classic problems of celestial mechanics as built-in scenes, held by
// ias15 to the literature: Burrau's Pythagorean three-body problem
// (Szebehely and Peters 1967: the lightest body escapes, the other two stay
// bound), the figure-eight choreography (Chenciner and Montgomery 2000: back
// to its start after whole periods), a Kepler orbit (back at its pericentre)
// and a softened cluster (energy). Snapshots resume an ias15 run bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "calder/diagnostics.hpp"
#include "calder/scene.hpp"
#include "calder/snapshot.hpp"
#include "calder/world.hpp"

namespace {

using calder::Scene;
using calder::Simulation;
using calder::Vec2;
using calder::World;

double relative_energy_error(const World& world, double e0) {
  return std::fabs((calder::total_energy(world) - e0) / e0);
}

// The two-body energy of bodies i and j alone (their relative motion), under G.
double pair_energy(const World& w, std::size_t i, std::size_t j, double G) {
  const double mi = w.mass(w.body(i));
  const double mj = w.mass(w.body(j));
  const Vec2 r = w.position(w.body(j)) - w.position(w.body(i));
  const Vec2 v = w.velocity(w.body(j)) - w.velocity(w.body(i));
  const double mu = mi * mj / (mi + mj);
  return 0.5 * mu * v.mag_sq() - G * mi * mj / r.mag();
}

TEST(ClassicProblems, PythagoreanLightestEscapesTheOthersStayBound) {
  constexpr double kUnit = 40.0;  // pixels to the problem's unit (the scene's comment)
  constexpr double G = kUnit * kUnit * kUnit;
  Simulation sim(calder::builtin_scene("pythagorean"));
  World& world = sim.world();
  EXPECT_EQ(world.integrator(), calder::Integrator::ias15);
  const double e0 = calder::total_energy(world);
  EXPECT_NEAR(e0 / (kUnit * kUnit), -769.0 / 60.0, 1e-12);  // the literature's energy
  double worst = 0.0;
  while (sim.frame() < sim.scene().frames) {
    sim.step();
    worst = std::max(worst, relative_energy_error(world, e0));
  }
  EXPECT_EQ(world.time(), 70.0);
  EXPECT_LT(worst, 1e-9);
  // Masses 4 and 5 (bodies 1 and 2) form a binary; mass 3 leaves it: its
  // energy relative to the binary's centre of mass is positive, and it is
  // far away and moving out.
  EXPECT_LT(pair_energy(world, 1, 2, G), 0.0);
  const double m12 = world.mass(world.body(1)) + world.mass(world.body(2));
  const Vec2 com = (world.position(world.body(1)) * world.mass(world.body(1)) +
                    world.position(world.body(2)) * world.mass(world.body(2))) /
                   m12;
  const Vec2 vcom = (world.velocity(world.body(1)) * world.mass(world.body(1)) +
                     world.velocity(world.body(2)) * world.mass(world.body(2))) /
                    m12;
  const Vec2 r = world.position(world.body(0)) - com;
  const Vec2 v = world.velocity(world.body(0)) - vcom;
  const double m0 = world.mass(world.body(0));
  const double mu = m0 * m12 / (m0 + m12);
  EXPECT_GT(0.5 * mu * v.mag_sq() - G * m0 * m12 / r.mag(), 0.0);
  EXPECT_GT(r.mag(), 10.0 * kUnit);
  EXPECT_GT(r.dot(v), 0.0);
  // The closest approach of the literature (4.1e-4 at t = 15.83, REBOUND's
  // IAS15 measuring as this does: at the ends of internal steps).
  const calder::AdaptiveStats& stats = world.adaptive_stats();
  EXPECT_NEAR(stats.closest_approach / kUnit, 4.1e-4, 0.3e-4);
  EXPECT_NEAR(stats.closest_approach_time, 15.83, 0.01);
}

TEST(ClassicProblems, FigureEightReturnsToItsStartAfterTenPeriods) {
  constexpr double kUnit = 100.0;
  Simulation sim(calder::builtin_scene("figure-eight"));
  World& world = sim.world();
  std::vector<Vec2> start;
  std::vector<Vec2> start_velocity;
  for (std::size_t i = 0; i < 3; ++i) {
    start.push_back(world.position(world.body(i)));
    start_velocity.push_back(world.velocity(world.body(i)));
  }
  const double e0 = calder::total_energy(world);
  while (sim.frame() < sim.scene().frames) sim.step();  // ten periods
  EXPECT_NEAR(world.time(), 10 * 6.32591398, 1e-12);
  // Initial conditions and period are given to 8 digits: back within a few
  // 1e-7 of the unit (REBOUND's IAS15: 4e-7).
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_LT((world.position(world.body(i)) - start[i]).mag() / kUnit, 1e-6) << "body " << i;
    EXPECT_LT((world.velocity(world.body(i)) - start_velocity[i]).mag() / kUnit, 1e-6)
        << "body " << i;
  }
  EXPECT_LT(relative_energy_error(world, e0), 1e-13);
}

TEST(ClassicProblems, KeplerSceneReturnsToPericentreEachOrbit) {
  Simulation sim(calder::builtin_scene("kepler"));
  World& world = sim.world();
  const double e0 = calder::total_energy(world);
  EXPECT_NEAR(e0, -0.5 * 1e4, 1e-9);  // -G M m / (2 a), a = 100 px, G = 100^3
  for (int orbit = 1; orbit <= 10; ++orbit) {
    for (int k = 0; k < 60; ++k) sim.step();
    const Vec2 p = world.position(world.body(0));
    EXPECT_NEAR(p.x, 10.0, 1e-9) << "orbit " << orbit;
    EXPECT_NEAR(p.y, 0.0, 1e-8) << "orbit " << orbit;
  }
  EXPECT_LT(relative_energy_error(world, e0), 1e-13);
}

TEST(ClassicProblems, SoftenedClusterConservesEnergyAndMomentum) {
  Simulation sim(calder::builtin_scene("plummer-cluster"));
  World& world = sim.world();
  const double e0 = calder::total_energy(world);
  const Vec2 p0 = calder::linear_momentum(world);
  while (sim.frame() < sim.scene().frames) sim.step();
  EXPECT_LT(relative_energy_error(world, e0), 1e-9);
  EXPECT_LT((calder::linear_momentum(world) - p0).mag(), 1e-9);
}

// A run saved at frame 157 and resumed gives the bits of the run that went on.
TEST(ClassicProblems, AnIas15RunResumesFromItsSnapshotBitForBit) {
  for (const char* name : {"pythagorean", "plummer-cluster"}) {
    Simulation through(calder::builtin_scene(name));
    for (int k = 0; k < 157; ++k) through.step();
    const calder::Bytes bytes = calder::to_snapshot(through);
    EXPECT_EQ(bytes[8], 2U) << "an adaptive state makes the snapshot format version 2";
    Simulation resumed = calder::simulation_from_snapshot(bytes, "test.snap");
    EXPECT_EQ(resumed.world().adaptive_state().next_step,
              through.world().adaptive_state().next_step);
    for (int k = 0; k < 150; ++k) {
      through.step();
      resumed.step();
    }
    EXPECT_EQ(calder::state_hash(resumed.world()), calder::state_hash(through.world())) << name;
    EXPECT_EQ(resumed.world().time(), through.world().time()) << name;
    EXPECT_EQ(resumed.world().adaptive_stats().steps, through.world().adaptive_stats().steps);
  }
  // Without ias15 a snapshot stays version 1, readable by a calder of version 1.
  Simulation book(calder::builtin_scene("example-2.1"));
  book.step();
  EXPECT_EQ(calder::to_snapshot(book)[8], 1U);
}

TEST(ClassicProblems, ASnapshotKeepsTheTolerance) {
  Scene scene = calder::builtin_scene("kepler");
  scene.world.tolerance = 1e-11;
  Simulation sim(scene);
  sim.step();
  const Simulation back = calder::simulation_from_snapshot(calder::to_snapshot(sim), "t.snap");
  EXPECT_EQ(back.scene().world.tolerance, 1e-11);
  EXPECT_EQ(back.world().tolerance(), 1e-11);
  const World world_back = calder::world_from_snapshot(calder::to_snapshot(sim.world()), "w.snap");
  EXPECT_EQ(world_back.tolerance(), 1e-11);
}

}  // namespace
