// SPDX-License-Identifier: MIT
// Tests of calder's dynamics against closed-form physics: free fall, terminal
// velocity under quadratic drag, a body stopped by kinetic friction, circular
// orbits, and the attraction laws themselves.
//
// Every expected number below comes from a formula worked out in the comments
// (never from running calder). Where the formula is exact in binary floating
// point (small integers times powers of two), the check is exact.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <ostream>
#include <vector>

#include "calder/diagnostics.hpp"
#include "calder/error.hpp"
#include "calder/fields.hpp"
#include "calder/forces.hpp"
#include "calder/random.hpp"
#include "calder/vec2.hpp"
#include "calder/world.hpp"
#include "support/test_support.hpp"

namespace {

using calder::AttractionLaw;
using calder::BodyId;
using calder::DistanceClamp;
using calder::Integrator;
using calder::MassProduct;
using calder::Vec2;
using calder::World;
using calder::WorldDef;

constexpr double kPi = 3.141592653589793;

constexpr Integrator kIntegrators[] = {Integrator::semi_implicit_euler, Integrator::velocity_verlet,
                                       Integrator::rk4};

// |a - b| <= rel * |b| in both components (rel relative to the length of b).
void expect_vec_near(Vec2 actual, Vec2 expected, double rel) {
  const double tol = rel * expected.mag();
  EXPECT_NEAR(actual.x, expected.x, tol) << "actual (" << actual.x << ", " << actual.y << ")";
  EXPECT_NEAR(actual.y, expected.y, tol) << "actual (" << actual.x << ", " << actual.y << ")";
}

// ===================================================================== free fall ===
//
// Semi-implicit Euler under a constant acceleration a, from x0 with v0:
//   v_{k+1} = v_k + a dt                  =>  v_n = v0 + n a dt
//   x_{k+1} = x_k + v_{k+1} dt            =>  x_n = x0 + dt * sum_{k=1..n} (v0 + k a dt)
//                                               = x0 + n v0 dt + a dt^2 n (n + 1) / 2.
// With a, v0, x0 and dt small dyadic rationals (0.5, 0.25, ...) every
// intermediate value is a dyadic rational with a few significant bits, so the
// floating-point recursion is exact and so is the closed form: EXPECT_EQ.

struct FreeFallCase {
  Vec2 x0{10.0, 20.0};
  Vec2 v0{1.0, -0.5};
  Vec2 a{-0.25, 0.5};
  double dt = 0.25;
};

Vec2 euler_closed_form(const FreeFallCase& c, int n) {
  const double nd = n;
  return c.x0 + c.v0 * (nd * c.dt) + c.a * (c.dt * c.dt * nd * (nd + 1.0) / 2.0);
}

TEST(AnalyticFreeFall, GravityFieldMatchesClosedFormExactly) {
  const FreeFallCase c;
  World world(WorldDef{.dt = c.dt});
  // Unscaled gravity is a force g, so a = g / m: g = 2 a on a body of mass 2.
  world.add(calder::Gravity{.g = c.a * 2.0});
  const BodyId body = world.add_body({.position = c.x0, .velocity = c.v0, .mass = 2.0});
  for (int n = 1; n <= 400; ++n) {
    world.step();
    ASSERT_EQ(world.velocity(body), c.v0 + c.a * (n * c.dt)) << "step " << n;
    ASSERT_EQ(world.position(body), euler_closed_form(c, n)) << "step " << n;
  }
  EXPECT_EQ(world.time(), 400 * c.dt);
}

TEST(AnalyticFreeFall, MassScaledGravityFallsTheSameForEveryMass) {
  // Gravity scaled by mass is a force m g, so a = (m g) / m = g for any m
  // (example 2.3). m = 3: (-0.25 * 3) / 3 and (0.5 * 3) / 3 are exact.
  const FreeFallCase c;
  World world(WorldDef{.dt = c.dt});
  world.add(calder::Gravity{.g = c.a, .scale_by_mass = true});
  const BodyId light = world.add_body({.position = c.x0, .velocity = c.v0, .mass = 3.0});
  const BodyId heavy = world.add_body({.position = c.x0, .velocity = c.v0, .mass = 12.0});
  for (int n = 1; n <= 400; ++n) {
    world.step();
    ASSERT_EQ(world.position(light), euler_closed_form(c, n)) << "step " << n;
    ASSERT_EQ(world.position(heavy), euler_closed_form(c, n)) << "step " << n;
  }
}

TEST(AnalyticFreeFall, MoverApplyForceUpdateMatchesClosedFormExactly) {
  // The book's loop: apply_force(F) then update(); F = m a with m = 4.
  const FreeFallCase c;
  World world(WorldDef{.dt = c.dt});
  calder::Mover mover = world.add_mover({.position = c.x0, .velocity = c.v0, .mass = 4.0});
  const Vec2 force = c.a * 4.0;
  for (int n = 1; n <= 400; ++n) {
    mover.apply_force(force);
    EXPECT_EQ(mover.acceleration(), c.a);
    mover.update();
    EXPECT_EQ(mover.acceleration(), Vec2{}) << "update() clears the acceleration";
    ASSERT_EQ(mover.velocity(), c.v0 + c.a * (n * c.dt)) << "step " << n;
    ASSERT_EQ(mover.position(), euler_closed_form(c, n)) << "step " << n;
  }
  EXPECT_EQ(force, c.a * 4.0) << "apply_force never changes the caller's vector";
}

TEST(AnalyticFreeFall, ConvergesToContinuousSolutionLinearlyInDt) {
  // At a fixed time T = n dt the closed form gives
  //   x_n = x0 + v0 T + a T^2 / 2 + a T dt / 2,
  // i.e. the error against the continuous x(T) = x0 + v0 T + a T^2 / 2 is
  // exactly a T dt / 2: first order, halving with dt. All values dyadic: exact.
  const FreeFallCase c;
  const double T = 4.0;
  double previous_error = 0.0;
  for (double dt = 0.25; dt >= 1.0 / 1024.0; dt /= 2.0) {
    World world(WorldDef{.dt = dt});
    world.add(calder::Gravity{.g = c.a, .scale_by_mass = true});
    const BodyId body = world.add_body({.position = c.x0, .velocity = c.v0, .mass = 1.0});
    const int n = static_cast<int>(T / dt);
    world.step(n);
    ASSERT_EQ(world.time(), T);
    const Vec2 continuous = c.x0 + c.v0 * T + c.a * (T * T / 2.0);
    const Vec2 error = world.position(body) - continuous;
    EXPECT_EQ(error, c.a * (T * dt / 2.0)) << "dt " << dt;
    if (previous_error != 0.0) {
      EXPECT_EQ(previous_error / error.y, 2.0) << "dt " << dt;
    }
    previous_error = error.y;
  }
}

// ============================================================= terminal velocity ===
//
// Falling under gravity m g (scaled by mass) and quadratic drag c |v|^2 against
// the motion: m dv/dt = m g - c v^2, so the speed tends to the terminal
// velocity v_t = sqrt(m g / c), where the two forces balance. v_t is also an
// exact fixed point of every integrator's step (the net force is zero there),
// so the discrete speed converges to v_t itself, not to an O(dt) neighbour.
// The approach is v(t) = v_t tanh(t / tau), tau = sqrt(m / (c g)); after t the
// relative gap is about 2 exp(-2 t / tau) (< 1e-8 at t = 256, tau <= 6.4).

TEST(AnalyticDrag, TerminalVelocityInAir) {
  const double g = 1.0;
  const double c = 0.1;
  for (const Integrator integrator : kIntegrators) {
    for (const double m : {1.0, 4.0}) {
      World world(WorldDef{.dt = 1.0 / 16.0, .integrator = integrator});
      world.add(calder::Gravity{.g = {0.0, g}, .scale_by_mass = true});
      world.add(calder::Drag{.c = c});
      const BodyId body = world.add_body({.position = {320.0, 0.0}, .mass = m});
      world.step(4096);  // t = 256
      const double terminal = std::sqrt(m * g / c);
      EXPECT_NEAR(world.velocity(body).y, terminal, 1e-6 * terminal)
          << "integrator " << static_cast<int>(integrator) << ", mass " << m;
      EXPECT_EQ(world.velocity(body).x, 0.0);
    }
  }
}

TEST(AnalyticDrag, TerminalVelocityInsideLiquidOnly) {
  // The same balance inside a Liquid region (example 2.5); above it the body
  // falls freely: with dt = 1/16 and g = 1, v_n = n / 16 exactly (dyadic).
  const double g = 1.0;
  const double c = 0.1;
  const double surface = 100.0;
  for (const double m : {1.0, 4.0}) {
    World world(WorldDef{.dt = 1.0 / 16.0});
    world.add(calder::Gravity{.g = {0.0, g}, .scale_by_mass = true});
    world.add(calder::Liquid{.region = {0.0, surface, 640.0, 1e6}, .c = c});
    const BodyId body = world.add_body({.position = {320.0, 0.0}, .mass = m});
    int n = 0;
    while (world.position(body).y <= surface) {
      world.step();
      ++n;
      if (world.position(body).y <= surface) {
        ASSERT_EQ(world.velocity(body).y, n * g / 16.0) << "free fall above the liquid";
      }
    }
    // Entry speed sqrt(2 g h) ~ 14 exceeds v_t: the liquid slows the body down to v_t.
    EXPECT_GT(world.velocity(body).y, std::sqrt(m * g / c));
    world.step(4096);
    ASSERT_GT(world.position(body).y, surface);
    const double terminal = std::sqrt(m * g / c);
    EXPECT_NEAR(world.velocity(body).y, terminal, 1e-6 * terminal) << "mass " << m;
  }
}

// ====================================================================== friction ===
//
// A body sliding on the floor with speed v0 feels kinetic friction mu N
// against its motion: deceleration b = mu N / m. Continuous: it stops after
// the distance D = v0^2 / (2 b) = v0^2 m / (2 mu N).
//
// Semi-implicit Euler: v_k = v0 - k b dt while positive. Let K be the number
// of steps with v_k > 0, s = v0 / (b dt) and theta = s - K in (0, 1]. The
// farthest point is x_K - x0 = dt sum_{k=1..K} v_k, which simplifies to
//   D_dt = v0^2 / (2 b) - v0 dt / 2 + b dt^2 theta (1 - theta) / 2,
// so |D_dt - (D - v0 dt / 2)| <= b dt^2 / 8: first order, error ~ v0 dt / 2.
//
// After that the book's friction (a constant-magnitude force -mu N v-hat)
// cannot hold the body still: with 0 < u = v_K <= b dt, the next step gives
// w = u - b dt <= 0; friction then points the other way and restores u. The
// velocity alternates between u and w, so |v| <= b dt from then on, and the
// mean velocity (u + w) / 2 = u - b dt / 2 lies in (-b dt / 2, b dt / 2]: the
// body may creep at most b dt / 2 per unit time. It only comes to rest if a
// step lands exactly on v = 0, and only stays put on average if u = b dt / 2:
// kinetic friction with no static regime and no never-reverse limit (the
// worst case, u -> 0 or u -> b dt, is reached e.g. when v0 / (b dt) is an
// integer, as for dt = 0.1 below: the body creeps forward at b dt / 2).

struct SlideResult {
  double stop_distance = 0.0;  // farthest point reached, from the start
  double max_speed_after = 0.0;
  double drift_after = 0.0;  // |x(end) - x(stop)|
  double time_after = 0.0;
};

SlideResult slide(double dt, double v0, double mu, double normal, double mass, int steps_after) {
  const double height = 240.0;
  const double radius = 10.0;
  World world(WorldDef{.height = height, .dt = dt});
  world.add(calder::Friction{.mu = mu, .normal = normal});
  // Touching the floor: y = height - r > height - r - tolerance.
  const BodyId body = world.add_body({.position = {100.0, height - radius},
                                      .velocity = {v0, 0.0},
                                      .mass = mass,
                                      .radius = radius});
  EXPECT_TRUE(world.touching(body, calder::Edge::bottom));
  SlideResult r;
  double x_max = 100.0;
  for (int k = 0;; ++k) {
    if (k > 1000000) {
      ADD_FAILURE() << "the body never stopped";
      break;
    }
    world.step();
    if (world.velocity(body).x <= 0.0) break;
    x_max = world.position(body).x;
  }
  r.stop_distance = x_max - 100.0;
  const double x_stop = world.position(body).x;
  for (int k = 0; k < steps_after; ++k) {
    world.step();
    r.max_speed_after = std::max(r.max_speed_after, world.velocity(body).mag());
    EXPECT_EQ(world.velocity(body).y, 0.0);
    EXPECT_EQ(world.position(body).y, height - radius);
  }
  r.drift_after = std::abs(world.position(body).x - x_stop);
  r.time_after = steps_after * dt;
  return r;
}

TEST(AnalyticFriction, SlidingBodyStopsAtClosedFormDistance) {
  const double v0 = 2.0;
  const double mu = 0.2;
  const double normal = 1.5;
  const double mass = 3.0;
  const double b = mu * normal / mass;            // 0.1
  const double continuous = v0 * v0 / (2.0 * b);  // 20
  double previous_error = 0.0;
  for (const double dt : {0.1, 0.05, 0.025, 0.0125}) {
    const SlideResult r = slide(dt, v0, mu, normal, mass, 2000);
    // The discrete closed form, up to the theta term and rounding.
    EXPECT_NEAR(r.stop_distance, continuous - v0 * dt / 2.0, b * dt * dt / 8.0 + 1e-9)
        << "dt " << dt;
    const double error = std::abs(r.stop_distance - continuous);
    EXPECT_LT(error / continuous, 1e-2) << "dt " << dt;
    if (previous_error > 0.0) {
      // First order: halving dt halves the error (v0 dt / 2 dominates b dt^2 / 8).
      EXPECT_NEAR(previous_error / error, 2.0, 0.05) << "dt " << dt;
    }
    previous_error = error;
    // After the stop the speed never exceeds one step's worth of friction...
    EXPECT_LE(r.max_speed_after, b * dt * (1.0 + 1e-9)) << "dt " << dt;
    // ...and the mean creep speed is at most b dt / 2 (plus one step's motion).
    EXPECT_LE(r.drift_after, b * dt / 2.0 * r.time_after + b * dt * dt) << "dt " << dt;
  }
}

TEST(AnalyticFriction, NeverReverseBringsTheBodyToRestAndKeepsItThere) {
  // With never_reverse, one step's friction is limited to m |v| / dt, so the
  // step that would overshoot lands exactly on v = 0 (v - (m v / dt) / m dt,
  // up to rounding) and a body at rest feels no friction (zero direction).
  // The stop distance keeps the closed form of the book's friction up to that
  // last step: |D_dt - (D - v0 dt / 2)| <= b dt^2 / 8 + the last step's v dt.
  const double v0 = 2.0;
  const double mu = 0.2;
  const double mass = 3.0;
  const double dt = 0.1;
  const double b = mu / mass;
  World world(WorldDef{.height = 240.0, .dt = dt});
  world.add(calder::Friction{.mu = mu, .never_reverse = true});
  const BodyId body = world.add_body(
      {.position = {100.0, 230.0}, .velocity = {v0, 0.0}, .mass = mass, .radius = 10.0});
  double previous_x = 100.0;
  for (int k = 0; k < 2000; ++k) {
    world.step();
    EXPECT_GE(world.velocity(body).x, -1e-15) << "step " << k;  // never reverses
    EXPECT_GE(world.position(body).x, previous_x - 1e-12) << "step " << k;
    previous_x = world.position(body).x;
  }
  EXPECT_NEAR(world.velocity(body).x, 0.0, 1e-15);
  const double stop_distance = world.position(body).x - 100.0;
  EXPECT_NEAR(stop_distance, v0 * v0 / (2.0 * b) - v0 * dt / 2.0, b * dt * dt / 8.0 + b * dt * dt);
  // And it stays put: 1000 more steps move it by (almost) nothing.
  const double x_rest = world.position(body).x;
  world.step(1000);
  EXPECT_NEAR(world.position(body).x, x_rest, 1e-12);
}

TEST(AnalyticFriction, OwnCoefficientReplacesFieldMu) {
  // Exercise 2.6: a body's own mu replaces the field's. Deceleration b = mu N / m;
  // one step from v0 gives v0 - b dt (b = 0.25 * 1 / 2 = 0.125, dt = 1: exact up
  // to the 1/|v| rounding of set_mag).
  World world(WorldDef{.height = 240.0, .dt = 1.0});
  world.add(calder::Friction{.mu = 0.01});
  const BodyId body = world.add_body({.position = {100.0, 230.0},
                                      .velocity = {-3.0, 0.0},
                                      .mass = 2.0,
                                      .radius = 10.0,
                                      .friction = 0.25});
  world.step();
  EXPECT_DOUBLE_EQ(world.velocity(body).x, -3.0 + 0.125);
}

// ============================================================= circular orbits ===

// Times at which the angle of p(t) - centre crosses zero upward (y from < 0 to
// >= 0 with x > 0), by linear interpolation between steps. Near the crossing
// y(t) ~ r sin(omega (t - t0)) has no curvature, so the interpolation error is
// O(omega^2 dt^3), far below the tolerances used.
template <class Relative>
std::vector<double> angle_wraps(World& world, int steps, Relative relative) {
  std::vector<double> wraps;
  Vec2 prev = relative();
  for (int k = 0; k < steps; ++k) {
    const double t_prev = world.time();
    world.step();
    const Vec2 now = relative();
    if (prev.y < 0.0 && now.y >= 0.0 && now.x > 0.0) {
      wraps.push_back(t_prev + world.dt() * (-prev.y) / (now.y - prev.y));
    }
    prev = now;
  }
  return wraps;
}

TEST(AnalyticOrbit, CircularOrbitAroundFixedAttractor) {
  // Test body around a fixed mass M with Newton's unclamped law: circular speed
  // v = sqrt(G M / r), period T = 2 pi sqrt(r^3 / (G M)).
  const double G = 2.0;
  const double M = 500.0;
  const double r = 100.0;
  const Vec2 centre{320.0, 120.0};
  const double v = std::sqrt(G * M / r);
  const double period = 2.0 * kPi * std::sqrt(r * r * r / (G * M));  // ~198.7
  World world(WorldDef{.dt = 0.1, .integrator = Integrator::rk4});
  world.add(calder::Attractor{.position = centre, .mass = M, .law = AttractionLaw::newtonian(G)});
  // Start below the centre's axis (angle -0.3) so the first wrap is a true crossing.
  const double a0 = -0.3;
  const BodyId body = world.add_body({.position = centre + Vec2::from_angle(a0, r),
                                      .velocity = Vec2::from_angle(a0 + kPi / 2.0, v),
                                      .mass = 0.5});
  double max_radius_error = 0.0;
  const auto relative = [&] {
    max_radius_error = std::max(max_radius_error, std::abs(world.position(body).dist(centre) - r));
    return world.position(body) - centre;
  };
  const std::vector<double> wraps =
      angle_wraps(world, static_cast<int>(3.0 * period / world.dt()), relative);
  ASSERT_EQ(wraps.size(), 3U);
  // The first wrap comes after the angle went from a0 to 0: t = -a0 / omega.
  const double omega = 2.0 * kPi / period;
  EXPECT_NEAR(wraps[0], -a0 / omega, 1e-8 * period);
  for (std::size_t k = 1; k < wraps.size(); ++k) {
    EXPECT_NEAR(wraps[k] - wraps[k - 1], period, 1e-8 * period) << "orbit " << k;
  }
  EXPECT_LT(max_radius_error / r, 1e-8);
}

TEST(AnalyticOrbit, CircularTwoBodyOrbitAboutCentreOfMass) {
  // Two bodies M and m at separation r, each on a circle about the centre of
  // mass: relative speed v_rel = sqrt(G (M + m) / r), split in the ratio of the
  // masses so the total momentum is zero; T = 2 pi sqrt(r^3 / (G (M + m))).
  const double G = 1.0;
  const double M = 3.0;
  const double m = 1.0;
  const double r = 10.0;
  const double total = M + m;
  const double v_rel = std::sqrt(G * total / r);
  const double period = 2.0 * kPi * std::sqrt(r * r * r / (G * total));  // ~99.3
  const Vec2 com{320.0, 120.0};
  const double a0 = -0.2;
  const Vec2 dir = Vec2::from_angle(a0);
  const Vec2 perp = Vec2::from_angle(a0 + kPi / 2.0);
  World world(WorldDef{.dt = 0.05, .integrator = Integrator::rk4});
  world.add(calder::MutualAttraction{.law = AttractionLaw::newtonian(G)});
  const BodyId heavy = world.add_body({.position = com - dir * (r * m / total),
                                       .velocity = perp * (-v_rel * m / total),
                                       .mass = M});
  const BodyId light = world.add_body(
      {.position = com + dir * (r * M / total), .velocity = perp * (v_rel * M / total), .mass = m});
  double max_separation_error = 0.0;
  const auto relative = [&] {
    const Vec2 d = world.position(light) - world.position(heavy);
    max_separation_error = std::max(max_separation_error, std::abs(d.mag() - r));
    return d;
  };
  const std::vector<double> wraps =
      angle_wraps(world, static_cast<int>(2.0 * period / world.dt()), relative);
  ASSERT_EQ(wraps.size(), 2U);
  EXPECT_NEAR(wraps[0], -a0 / (2.0 * kPi / period), 1e-8 * period);
  EXPECT_NEAR(wraps[1] - wraps[0], period, 1e-8 * period);
  EXPECT_LT(max_separation_error / r, 1e-8);
  // The centre of mass does not move (zero total momentum).
  expect_vec_near(calder::center_of_mass(world), com, 1e-12);
}

// ================================================================ attraction law ===

TEST(AnalyticAttraction, BookLawInverseSquareInsideClamp) {
  // |F| = G M m / d^2 for d in [5, 25], directed from the target toward the
  // source. Source (10, 20), target (16, 28): r = source - target = (-6, -8), d = 10.
  const AttractionLaw law = AttractionLaw::book(1.5);
  const double M = 20.0;
  const double m = 2.0;
  const Vec2 f = calder::attraction({10.0, 20.0}, M, {16.0, 28.0}, m, law);
  const double magnitude = 1.5 * M * m / 100.0;  // 0.6
  expect_vec_near(f, Vec2{-6.0, -8.0} * (magnitude / 10.0), 1e-15);
  // Other distances inside the clamp, along a diagonal.
  for (const double d : {5.0, 7.5, 12.0, 24.0, 25.0}) {
    const Vec2 target = Vec2{100.0, 100.0} + Vec2::from_angle(0.7, d);
    const Vec2 force = calder::attraction({100.0, 100.0}, M, target, m, law);
    EXPECT_NEAR(force.mag(), 1.5 * M * m / (d * d), 1e-14 * force.mag()) << "d " << d;
    // Toward the source: antiparallel to the target's offset.
    EXPECT_NEAR(force.dot(target - Vec2{100.0, 100.0}), -force.mag() * d, 1e-12) << "d " << d;
  }
}

TEST(AnalyticAttraction, BookLawConstantOutsideClamp) {
  // d is constrained to [min, max] = [5, 25] before the inverse square: the
  // magnitude is G M m / 25 below 5 and G M m / 625 above 25.
  const AttractionLaw law = AttractionLaw::book(1.0, 5.0, 25.0);
  const double gmm = 1.0 * 20.0 * 2.0;
  for (const double d : {0.001, 1.0, 4.9}) {
    const Vec2 f = calder::attraction({0.0, 0.0}, 20.0, {d, 0.0}, 2.0, law);
    EXPECT_NEAR(f.x, -gmm / 25.0, 1e-15) << "d " << d;
    EXPECT_EQ(f.y, 0.0);
  }
  for (const double d : {25.1, 100.0, 1e6}) {
    const Vec2 f = calder::attraction({0.0, 0.0}, 20.0, {0.0, -d}, 2.0, law);
    EXPECT_EQ(f.x, 0.0);
    EXPECT_NEAR(f.y, gmm / 625.0, 1e-16) << "d " << d;
  }
  // Coincident positions: no direction, no force.
  EXPECT_EQ(calder::attraction({3.0, 4.0}, 20.0, {3.0, 4.0}, 2.0, law), Vec2{});
}

TEST(AnalyticAttraction, ThirdLawIsExactWithMassesFirst) {
  // With the masses_first grouping the strength G * (m1 * m2) is symmetric in
  // the masses, r_ab = -r_ba exactly, and set_mag is sign-symmetric: the force
  // of a on b is bit for bit minus the force of b on a, for every law.
  AttractionLaw book = AttractionLaw::book(1.0, 5.0, 25.0, MassProduct::masses_first);
  AttractionLaw squared = AttractionLaw::book(1.0, 100.0, 1000.0, MassProduct::masses_first);
  squared.clamp = DistanceClamp::squared_distance;
  AttractionLaw plummer = AttractionLaw::newtonian(0.7, 2.0);
  plummer.product = MassProduct::masses_first;
  AttractionLaw newton = AttractionLaw::newtonian(3.0);
  newton.product = MassProduct::masses_first;
  calder::Random rng(2024);
  for (const AttractionLaw* law : {&book, &squared, &plummer, &newton}) {
    for (int k = 0; k < 500; ++k) {
      const Vec2 a{rng.random(-50.0, 50.0), rng.random(-50.0, 50.0)};
      const Vec2 b{rng.random(-50.0, 50.0), rng.random(-50.0, 50.0)};
      const double ma = rng.random(0.1, 10.0);
      const double mb = rng.random(0.1, 10.0);
      const Vec2 on_b = calder::attraction(a, ma, b, mb, *law);
      const Vec2 on_a = calder::attraction(b, mb, a, ma, *law);
      ASSERT_EQ(on_b, -on_a) << "sample " << k;
      ASSERT_NE(on_b, Vec2{});
    }
  }
}

TEST(AnalyticAttraction, PlummerSoftening) {
  // Softened Newton: |F| = G M m d / (d^2 + eps^2)^(3/2), finite and -> 0 at d -> 0,
  // and -> G M m / d^2 for d >> eps.
  const double G = 2.0;
  const double eps = 3.0;
  const double M = 5.0;
  const double m = 7.0;
  const AttractionLaw law = AttractionLaw::newtonian(G, eps);
  for (const double d : {1e-6, 0.5, 3.0, 10.0, 40.0, 1e4}) {
    // Source at the origin so that the offset (0.6 d, 0.8 d) has length d to rounding.
    const Vec2 f = calder::attraction({0.0, 0.0}, M, Vec2{0.6 * d, 0.8 * d}, m, law);
    const double expected = G * M * m * d / std::pow(d * d + eps * eps, 1.5);
    EXPECT_NEAR(f.mag(), expected, 1e-13 * expected) << "d " << d;
    expect_vec_near(f, Vec2{-0.6, -0.8} * expected, 1e-13);
  }
  const Vec2 far = calder::attraction({0.0, 0.0}, M, {1e4, 0.0}, m, law);
  EXPECT_NEAR(-far.x, G * M * m / 1e8, 1e-6 * G * M * m / 1e8);
  // Unsoftened: exactly the inverse square at any distance.
  const Vec2 near = calder::attraction({0.0, 0.0}, M, {0.0, 0.25}, m, AttractionLaw::newtonian(G));
  EXPECT_DOUBLE_EQ(near.y, -G * M * m / 0.0625);
}

TEST(AnalyticAttraction, SquaredDistanceClamp) {
  // Exercise 2.16: dsq = constrain(d^2, 100, 1000); |F| = G (M m) / dsq.
  AttractionLaw law = AttractionLaw::book(1.0, 100.0, 1000.0, MassProduct::masses_first);
  law.clamp = DistanceClamp::squared_distance;
  const double gmm = 500.0 * 12.0;
  const struct {
    double d;
    double dsq;
  } cases[] = {{2.0, 100.0},  {5.0, 100.0},   {10.0, 100.0},  {20.0, 400.0},
               {30.0, 900.0}, {40.0, 1000.0}, {300.0, 1000.0}};
  for (const auto& c : cases) {
    const Vec2 f = calder::attraction({0.0, 0.0}, 500.0, {0.0, c.d}, 12.0, law);
    EXPECT_EQ(f.x, 0.0);
    EXPECT_DOUBLE_EQ(f.y, -gmm / c.dsq) << "d " << c.d;
  }
}

TEST(AnalyticAttraction, NegativeGRepels) {
  // G < 0: the same magnitude |G| M m / d^2, pointing away from the source.
  const AttractionLaw repel = AttractionLaw::book(-2.0);
  const AttractionLaw attract = AttractionLaw::book(2.0);
  const Vec2 source{50.0, 50.0};
  const Vec2 target{50.0 + 9.0, 50.0 + 12.0};  // d = 15
  const Vec2 f = calder::attraction(source, 4.0, target, 3.0, repel);
  expect_vec_near(f, Vec2{9.0, 12.0} * (2.0 * 4.0 * 3.0 / 225.0 / 15.0), 1e-15);
  EXPECT_EQ(f, -calder::attraction(source, 4.0, target, 3.0, attract));
  // A repelling Attractor field pushes a body at rest away: one Euler step
  // from rest moves it by a dt^2 along +r-hat.
  World world(WorldDef{.dt = 1.0});
  world.add(calder::Attractor{.position = source, .mass = 4.0, .law = repel});
  const BodyId body = world.add_body({.position = target, .mass = 3.0});
  world.step();
  EXPECT_GT((world.position(body) - target).dot(target - source), 0.0);
  expect_vec_near(world.velocity(body), f / 3.0, 1e-15);
}

TEST(AnalyticAttraction, CustomLawSignedMagnitude) {
  // Exercise 2.13: a custom law returns the signed magnitude, positive toward
  // the source. k (d - 10): attracts beyond d = 10, repels inside.
  const AttractionLaw law =
      AttractionLaw::from([](double d, double, double) { return 0.5 * (d - 10.0); });
  const Vec2 far = calder::attraction({0.0, 0.0}, 1.0, {30.0, 40.0}, 1.0, law);  // d = 50
  expect_vec_near(far, Vec2{-30.0, -40.0} * (20.0 / 50.0), 1e-15);
  const Vec2 near = calder::attraction({0.0, 0.0}, 1.0, {3.0, 4.0}, 1.0, law);  // d = 5
  expect_vec_near(near, Vec2{3.0, 4.0} * (2.5 / 5.0), 1e-15);
  EXPECT_THROW((void)calder::attraction_potential(5.0, 1.0, 1.0, law), calder::Error);
}

}  // namespace
