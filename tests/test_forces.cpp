// SPDX-License-Identifier: MIT
// Tests of the force laws of calder/forces.hpp, each against values worked by
// hand, the p5.js order of operations of shared/spec/chapter2.md, or a law of
// physics (direction, falloff, Newton's third law).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <ostream>
#include <string>

#include "calder/error.hpp"
#include "calder/forces.hpp"
#include "calder/random.hpp"
#include "calder/vec2.hpp"
#include "support/test_support.hpp"

namespace {

using calder::AttractionLaw;
using calder::DistanceClamp;
using calder::Error;
using calder::MassProduct;
using calder::Vec2;
using calder::test::expect_error;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool is_zero(Vec2 v) { return v.x == 0.0 && v.y == 0.0; }

// ------------------------------------------------------------------ gravity ---

TEST(Gravity, UnscaledIsTheVectorItself) {
  EXPECT_EQ(calder::gravity({0.0, 0.1}, 10.0, false), (Vec2{0.0, 0.1}));
  EXPECT_EQ(calder::gravity({0.25, -3.0}, 0.5, false), (Vec2{0.25, -3.0}));
}

TEST(Gravity, ScaledByMassIsComponentwiseProduct) {
  // p5.Vector.mult(gravity, m) = (0 * m, 0.1 * m), component by component.
  for (const double m : {1.0, 2.0, 3.0, 0.7, 10.0, 2.9e-3}) {
    const Vec2 g = calder::gravity({0.0, 0.1}, m, true);
    EXPECT_EQ(g.x, 0.0 * m);
    EXPECT_EQ(g.y, 0.1 * m) << "m = " << m;
  }
  // 0.1 * 3 = 0.30000000000000004, not 0.3: the product is not rounded away.
  EXPECT_EQ(calder::gravity({0.0, 0.1}, 3.0, true).y, 0.30000000000000004);
}

TEST(Helium, PointsUpWithTheGivenStrength) {
  // y points down, so "up" is negative y.
  EXPECT_EQ(calder::helium(0.3), (Vec2{0.0, -0.3}));
  EXPECT_EQ(calder::helium(0.0).y, 0.0);
  EXPECT_EQ(calder::helium(-2.0), (Vec2{0.0, 2.0}));
}

// ---------------------------------------------------------------- noise wind ---

TEST(NoiseWind, IsTheMappedNoiseValueAtOffsetPlusTimeTimesRate) {
  const calder::Noise noise(42);
  const double strength = 0.25;
  const double rate = 0.013;
  const double offset = 7.5;
  for (const double t : {0.0, 1.0, 17.0, 250.0, 1234.5}) {
    const double n = noise.noise(offset + t * rate);
    // p5 map(n, 0, 1, -s, s) = (n - 0) / (1 - 0) * (s - -s) + -s.
    const double expected = (n - 0.0) / (1.0 - 0.0) * (strength - -strength) + -strength;
    const Vec2 w = calder::noise_wind(noise, t, strength, rate, offset);
    EXPECT_EQ(w.x, expected) << "t = " << t;
    EXPECT_EQ(w.y, 0.0);
  }
}

TEST(NoiseWind, DefaultRateAndOffset) {
  const calder::Noise noise(3);
  const double n = noise.noise(0.0 + 40.0 * 0.01);
  EXPECT_EQ(calder::noise_wind(noise, 40.0, 1.0).x, n * 2.0 - 1.0);
}

TEST(NoiseWind, StaysWithinPlusMinusStrengthAndVaries) {
  const calder::Noise noise(1);
  const double strength = 0.5;
  double lo = strength;
  double hi = -strength;
  for (int t = 0; t < 2000; ++t) {
    const double x = calder::noise_wind(noise, t, strength, 0.05).x;
    EXPECT_GE(x, -strength);
    EXPECT_LE(x, strength);
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  // Noise is not constant: over 100 units of noise space the wind changes sign.
  EXPECT_LT(lo, 0.0);
  EXPECT_GT(hi, 0.0);
}

// ----------------------------------------------------------------------- fan ---

TEST(Fan, BlowsAwayFromTheFanWithLinearFalloff) {
  // Body at (130, 140), fan at (100, 100): away = (30, 40), d = 50, reach 100:
  // |F| = 2 * (1 - 50/100) = 1 along (0.6, 0.8).
  const Vec2 f = calder::fan({100.0, 100.0}, {130.0, 140.0}, 2.0, 100.0);
  EXPECT_NEAR(f.x, 0.6, 1e-15);
  EXPECT_NEAR(f.y, 0.8, 1e-15);
  // Falloff along +x: strength * (1 - d / reach) at d = 10, 20, ..., 90.
  double previous = 3.0;
  for (int k = 1; k < 10; ++k) {
    const double d = 10.0 * k;
    const Vec2 g = calder::fan({0.0, 0.0}, {d, 0.0}, 3.0, 100.0);
    EXPECT_NEAR(g.x, 3.0 * (1.0 - d / 100.0), 1e-14) << "d = " << d;
    EXPECT_EQ(g.y, 0.0);
    EXPECT_LT(g.x, previous);
    previous = g.x;
  }
  // Blows left when the body is to the left.
  EXPECT_NEAR(calder::fan({50.0, 0.0}, {25.0, 0.0}, 1.0, 100.0).x, -0.75, 1e-15);
}

TEST(Fan, ZeroAtAndBeyondReachAndAtTheCentre) {
  EXPECT_TRUE(is_zero(calder::fan({0.0, 0.0}, {100.0, 0.0}, 2.0, 100.0)));
  EXPECT_TRUE(is_zero(calder::fan({0.0, 0.0}, {60.0, 80.0}, 2.0, 100.0)));  // d = 100
  EXPECT_TRUE(is_zero(calder::fan({0.0, 0.0}, {300.0, -5.0}, 2.0, 100.0)));
  const Vec2 centre = calder::fan({7.0, 9.0}, {7.0, 9.0}, 2.0, 100.0);
  EXPECT_TRUE(is_zero(centre));
  EXPECT_TRUE(centre.is_finite());
}

// ---------------------------------------------------------------- edge force ---

TEST(EdgeForce, ZeroInTheMiddle) {
  EXPECT_TRUE(is_zero(calder::edge_force({320.0, 120.0}, 640.0, 240.0, 2.0, 50.0)));
  // At exactly the margin the push is strength * 0 / margin = 0.
  EXPECT_TRUE(is_zero(calder::edge_force({50.0, 50.0}, 640.0, 240.0, 2.0, 50.0)));
  EXPECT_TRUE(is_zero(calder::edge_force({590.0, 190.0}, 640.0, 240.0, 2.0, 50.0)));
}

TEST(EdgeForce, PushesInwardNearEachEdge) {
  // strength 2, margin 50, 10 px from an edge: 2 * (50 - 10) / 50 = 1.6.
  const double s = 2.0;
  const double m = 50.0;
  EXPECT_EQ(calder::edge_force({10.0, 120.0}, 640.0, 240.0, s, m), (Vec2{1.6, 0.0}));
  EXPECT_EQ(calder::edge_force({630.0, 120.0}, 640.0, 240.0, s, m), (Vec2{-1.6, 0.0}));
  EXPECT_EQ(calder::edge_force({320.0, 10.0}, 640.0, 240.0, s, m), (Vec2{0.0, 1.6}));
  EXPECT_EQ(calder::edge_force({320.0, 230.0}, 640.0, 240.0, s, m), (Vec2{0.0, -1.6}));
}

TEST(EdgeForce, StrongerCloserAndPastTheEdge) {
  const auto left = [](double x) {
    return calder::edge_force({x, 120.0}, 640.0, 240.0, 2.0, 50.0).x;
  };
  EXPECT_GT(left(5.0), left(10.0));
  EXPECT_GT(left(10.0), left(40.0));
  EXPECT_GT(left(40.0), 0.0);
  EXPECT_EQ(left(0.0), 2.0);                           // strength at the edge
  EXPECT_NEAR(left(-10.0), 2.0 * 60.0 / 50.0, 1e-15);  // past it: 2.4
}

TEST(EdgeForce, CornersAdd) {
  EXPECT_EQ(calder::edge_force({10.0, 10.0}, 640.0, 240.0, 2.0, 50.0), (Vec2{1.6, 1.6}));
  EXPECT_EQ(calder::edge_force({630.0, 230.0}, 640.0, 240.0, 2.0, 50.0), (Vec2{-1.6, -1.6}));
  // 20 px from the right, 10 px from the top: (-2 * 30 / 50, 2 * 40 / 50).
  const Vec2 f = calder::edge_force({620.0, 10.0}, 640.0, 240.0, 2.0, 50.0);
  EXPECT_NEAR(f.x, -1.2, 1e-15);
  EXPECT_NEAR(f.y, 1.6, 1e-15);
}

// ------------------------------------------------------------------ friction ---

TEST(Friction, BitsOfTheBookComputation) {
  // friction = v.copy(); friction.mult(-1); friction.setMag(c): mult by -1,
  // normalize multiplies by 1 / |v| = 1 / 5, then mult(0.1 * N) with N = 1.
  const Vec2 f = calder::friction({3.0, 4.0}, 0.1);
  EXPECT_EQ(f.x, -3.0 * (1.0 / 5.0) * 0.1);
  EXPECT_EQ(f.y, -4.0 * (1.0 / 5.0) * 0.1);
  EXPECT_NEAR(f.mag(), 0.1, 1e-16);
}

TEST(Friction, NormalForceScalesTheMagnitude) {
  // setMag(mu * N) = 0.1 * 2 = 0.2 along -v.
  const Vec2 f = calder::friction({0.0, -2.0}, 0.1, 2.0);
  EXPECT_EQ(f.x, 0.0);
  EXPECT_EQ(f.y, 2.0 * (1.0 / 2.0) * (0.1 * 2.0));
  EXPECT_GT(f.y, 0.0);
}

TEST(Friction, ZeroVelocityGivesZeroFriction) {
  const Vec2 f = calder::friction({0.0, 0.0}, 0.1);
  EXPECT_TRUE(is_zero(f));
  EXPECT_TRUE(f.is_finite());
}

// ---------------------------------------------------------------------- drag ---

TEST(Drag, MagnitudeIsCSpeedSpeedAreaAgainstTheVelocity) {
  const double c = 0.1;
  const Vec2 v{3.0, 4.0};
  const double speed = std::sqrt(3.0 * 3.0 + 4.0 * 4.0);  // 5
  const double magnitude = (c * speed) * speed * 1.0;     // 2.5
  const Vec2 f = calder::drag(v, c);
  // -v, normalized by 1 / speed, times the magnitude.
  EXPECT_EQ(f.x, -3.0 * (1.0 / speed) * magnitude);
  EXPECT_EQ(f.y, -4.0 * (1.0 / speed) * magnitude);
  EXPECT_NEAR(f.mag(), 2.5, 1e-15);
  EXPECT_DOUBLE_EQ(f.dot(v) / (f.mag() * v.mag()), -1.0);
}

TEST(Drag, GroupingIsCTimesSpeedThenSpeed) {
  // v = (2.3, 0): speed 2.3; (0.7 * 2.3) * 2.3 = 3.7029999999999994 but
  // 0.7 * (2.3 * 2.3) = 3.702999999999999.
  const double c = 0.7;
  const double speed = 2.3;
  ASSERT_NE((c * speed) * speed, c * (speed * speed));
  const Vec2 f = calder::drag({speed, 0.0}, c);
  // normalize: 2.3 * (1 / 2.3), then times the magnitude.
  EXPECT_EQ(f.x, -speed * (1.0 / speed) * ((c * speed) * speed));
}

TEST(Drag, AreaScalesLinearly) {
  const Vec2 v{0.0, 6.0};
  const Vec2 f1 = calder::drag(v, 0.05, 1.0);
  const Vec2 f2 = calder::drag(v, 0.05, 2.0);
  EXPECT_NEAR(f1.y, -0.05 * 36.0, 1e-15);
  EXPECT_NEAR(f2.y, -0.05 * 36.0 * 2.0, 1e-15);
  EXPECT_TRUE(is_zero(calder::drag(v, 0.05, 0.0)));
}

TEST(Drag, ZeroAtRest) {
  const Vec2 f = calder::drag({0.0, 0.0}, 0.1);
  EXPECT_TRUE(is_zero(f));
  EXPECT_TRUE(f.is_finite());
}

// ---------------------------------------------------------------- limit drag ---

TEST(LimitDrag, WeakDragIsUnchanged) {
  const Vec2 v{3.0, 4.0};
  const Vec2 f = calder::drag(v, 0.01);  // |F| = 0.25 < m |v| / dt = 10
  EXPECT_EQ(calder::limit_drag(f, v, 2.0, 1.0), f);
}

TEST(LimitDrag, StrongDragStopsButNeverReverses) {
  // v = (3, 4), m = 2, dt = 1: the limit is m |v| / dt = 10; drag c = 10 gives 250.
  const Vec2 v{3.0, 4.0};
  const Vec2 f = calder::limit_drag(calder::drag(v, 10.0), v, 2.0, 1.0);
  EXPECT_NEAR(f.mag(), 10.0, 1e-13);
  EXPECT_NEAR(f.x, -6.0, 1e-13);
  EXPECT_NEAR(f.y, -8.0, 1e-13);
  const Vec2 after = v + f / 2.0 * 1.0;
  EXPECT_NEAR(after.mag(), 0.0, 1e-14);
}

TEST(LimitDrag, NeverReversesOverManyVelocitiesMassesAndSteps) {
  calder::Random rng(5);
  for (int k = 0; k < 500; ++k) {
    const Vec2 v{rng.random(-20.0, 20.0), rng.random(-20.0, 20.0)};
    const double mass = rng.random(0.1, 5.0);
    const double dt = rng.random(0.01, 2.0);
    const double c = rng.random(0.0, 50.0);
    const Vec2 f = calder::limit_drag(calder::drag(v, c), v, mass, dt);
    const Vec2 after = v + f / mass * dt;
    // Same direction as v, or (up to rounding of |v|) at rest: never reversed.
    const double scale = v.mag_sq();
    EXPECT_GE(after.dot(v), -1e-14 * scale) << "k = " << k;
    EXPECT_LE(after.mag(), v.mag() * (1.0 + 1e-15)) << "k = " << k;
    EXPECT_NEAR(after.cross(v), 0.0, 1e-12 * scale) << "k = " << k;
  }
}

TEST(LimitDrag, AtRestStaysZero) {
  const Vec2 f = calder::limit_drag(calder::drag({0.0, 0.0}, 10.0), {0.0, 0.0}, 1.0, 1.0);
  EXPECT_TRUE(is_zero(f));
}

// ---------------------------------------------------------------------- lift ---

TEST(Lift, PerpendicularWithMagnitudeCTimesSpeedSquared) {
  const Vec2 v{3.0, 4.0};
  const Vec2 f = calder::lift(v, 0.01);  // |F| = 0.01 * 25 = 0.25
  EXPECT_NEAR(f.mag(), 0.25, 1e-16);
  EXPECT_NEAR(f.dot(v), 0.0, 1e-15);
  // Left of the motion in a y-down canvas: (vy, -vx) direction = (0.8, -0.6).
  EXPECT_NEAR(f.x, 0.2, 1e-16);
  EXPECT_NEAR(f.y, -0.15, 1e-16);
}

TEST(Lift, MovingRightIsLiftedUp) {
  const Vec2 f = calder::lift({2.0, 0.0}, 0.01);  // 0.01 * 4 = 0.04 upward
  EXPECT_NEAR(f.x, 0.0, 1e-18);
  EXPECT_NEAR(f.y, -0.04, 1e-17);
  EXPECT_LT(f.y, 0.0);
  // A negative coefficient pushes down instead.
  EXPECT_GT(calder::lift({2.0, 0.0}, -0.01).y, 0.0);
}

TEST(Lift, PerpendicularForManyVelocitiesAndZeroAtRest) {
  calder::Random rng(11);
  for (int k = 0; k < 200; ++k) {
    const Vec2 v{rng.random(-10.0, 10.0), rng.random(-10.0, 10.0)};
    const Vec2 f = calder::lift(v, 0.3);
    EXPECT_NEAR(f.dot(v), 0.0, 1e-13 * v.mag_sq() * v.mag());
    EXPECT_NEAR(f.mag(), 0.3 * v.mag_sq(), 1e-13 * v.mag_sq());
    // Always on the same side: f = k (vy, -vx) gives f x v = k |v|^2 > 0.
    EXPECT_GT(f.cross(v), 0.0);
  }
  EXPECT_TRUE(is_zero(calder::lift({0.0, 0.0}, 0.3)));
}

// ---------------------------------------------------------------- attraction ---

TEST(Attraction, InsideTheClampIsGMmOverDSquaredTowardTheSource) {
  // Source at the origin, mass 10; target at (0, 10), mass 3; G = 1, d = 10:
  // |F| = 1 * 10 * 3 / 100 = 0.3, pointing from the target to the source (-y).
  const AttractionLaw law = AttractionLaw::book(1.0, 5.0, 25.0);
  const Vec2 f = calder::attraction({0.0, 0.0}, 10.0, {0.0, 10.0}, 3.0, law);
  EXPECT_EQ(f.x, 0.0);
  EXPECT_EQ(f.y, -10.0 * (1.0 / 10.0) * (1.0 * 10.0 * 3.0 / (10.0 * 10.0)));
  EXPECT_NEAR(f.y, -0.3, 1e-16);
  // (6, 8) from the source: d = 10, direction (-0.6, -0.8).
  const Vec2 g = calder::attraction({0.0, 0.0}, 10.0, {6.0, 8.0}, 3.0, law);
  EXPECT_NEAR(g.x, -0.18, 1e-16);
  EXPECT_NEAR(g.y, -0.24, 1e-16);
}

TEST(Attraction, DistanceClampLowAndHigh) {
  const AttractionLaw law = AttractionLaw::book(1.0, 5.0, 25.0);
  // d = 2 is clamped up to 5: 30 / 25 = 1.2.
  const Vec2 near = calder::attraction({0.0, 0.0}, 10.0, {0.0, 2.0}, 3.0, law);
  EXPECT_EQ(near.y, -2.0 * (1.0 / 2.0) * (30.0 / 25.0));
  // d = 100 is clamped down to 25: 30 / 625 = 0.048.
  const Vec2 far = calder::attraction({0.0, 0.0}, 10.0, {100.0, 0.0}, 3.0, law);
  EXPECT_EQ(far.x, -100.0 * (1.0 / 100.0) * (30.0 / 625.0));
  EXPECT_EQ(far.y, 0.0);
  // Every distance below 5 feels the same force.
  EXPECT_EQ(calder::attraction({0.0, 0.0}, 10.0, {0.0, 0.5}, 3.0, law).y, near.y);
}

TEST(Attraction, SquaredDistanceClamp) {
  AttractionLaw law;
  law.clamp = DistanceClamp::squared_distance;
  law.min = 100.0;
  law.max = 1000.0;
  law.product = MassProduct::masses_first;
  // dsq = 25 -> 100; dsq = 400 stays; dsq = 2500 -> 1000. G (M m) / dsq, M m = 30.
  EXPECT_NEAR(calder::attraction({0.0, 0.0}, 10.0, {0.0, 5.0}, 3.0, law).y, -0.3, 1e-16);
  EXPECT_NEAR(calder::attraction({0.0, 0.0}, 10.0, {0.0, 20.0}, 3.0, law).y, -0.075, 1e-16);
  EXPECT_NEAR(calder::attraction({0.0, 0.0}, 10.0, {0.0, 50.0}, 3.0, law).y, -0.03, 1e-16);
}

TEST(Attraction, MassGroupingFollowsTheSketch) {
  // G = 0.7, M = 1.1, m = 2.3: (G M) m = 1.771 but G (M m) = 1.7709999999999997.
  const double G = 0.7;
  const double M = 1.1;
  const double m = 2.3;
  ASSERT_NE((G * M) * m, G * (M * m));
  // Target 10 below the source: -y, normalize gives 10 * (1 / 10) = 1 exactly.
  ASSERT_EQ(10.0 * (1.0 / 10.0), 1.0);
  AttractionLaw ltr = AttractionLaw::book(G, 5.0, 25.0, MassProduct::left_to_right);
  AttractionLaw first = AttractionLaw::book(G, 5.0, 25.0, MassProduct::masses_first);
  EXPECT_EQ(calder::attraction({0.0, 0.0}, M, {0.0, 10.0}, m, ltr).y,
            -((G * M) * m / (10.0 * 10.0)));
  EXPECT_EQ(calder::attraction({0.0, 0.0}, M, {0.0, 10.0}, m, first).y,
            -(G * (M * m) / (10.0 * 10.0)));
  // The default law is the book's left-to-right grouping.
  const AttractionLaw defaults;
  EXPECT_EQ(defaults.product, MassProduct::left_to_right);
  EXPECT_EQ(defaults.min, 5.0);
  EXPECT_EQ(defaults.max, 25.0);
}

TEST(Attraction, NewtonsThirdLawExactlyWithMassesFirst) {
  // G (M m) commutes exactly, and source - target flips sign exactly.
  const AttractionLaw law = AttractionLaw::book(0.7, 5.0, 25.0, MassProduct::masses_first);
  calder::Random rng(3);
  for (int k = 0; k < 100; ++k) {
    const Vec2 a{rng.random(640.0), rng.random(240.0)};
    const Vec2 b{rng.random(640.0), rng.random(240.0)};
    const double ma = rng.random(0.1, 5.0);
    const double mb = rng.random(0.1, 5.0);
    const Vec2 on_b = calder::attraction(a, ma, b, mb, law);
    const Vec2 on_a = calder::attraction(b, mb, a, ma, law);
    EXPECT_EQ(on_a, -on_b) << "k = " << k;
    // Attraction: the force on b points toward a.
    EXPECT_GT(on_b.dot(a - b), 0.0);
  }
}

TEST(Attraction, NegativeGRepels) {
  const Vec2 f = calder::attraction({0.0, 0.0}, 10.0, {0.0, 10.0}, 3.0, AttractionLaw::book(-1.0));
  EXPECT_NEAR(f.y, 0.3, 1e-16);
}

TEST(Attraction, NewtonianWithAndWithoutSoftening) {
  // No clamp: G M m / d^2 at d = 2: 1 * 10 * 3 / 4 = 7.5.
  EXPECT_NEAR(calder::attraction({0.0, 0.0}, 10.0, {0.0, 2.0}, 3.0, AttractionLaw::newtonian()).y,
              -7.5, 1e-14);
  // Plummer, eps = 1.5, d = 2: G M m d / (d^2 + eps^2)^(3/2) = 30 * 2 / 6.25^1.5 = 3.84.
  EXPECT_NEAR(
      calder::attraction({0.0, 0.0}, 10.0, {0.0, 2.0}, 3.0, AttractionLaw::newtonian(1.0, 1.5)).y,
      -3.84, 1e-14);
}

TEST(Attraction, CustomLawSignAndArguments) {
  double seen_d = 0.0;
  double seen_source = 0.0;
  double seen_target = 0.0;
  const AttractionLaw toward = AttractionLaw::from([&](double d, double ms, double mt) {
    seen_d = d;
    seen_source = ms;
    seen_target = mt;
    return 0.5;
  });
  // Target at (0, 10), source at the origin (mass 4), target mass 2.
  const Vec2 t = calder::attraction({0.0, 0.0}, 4.0, {0.0, 10.0}, 2.0, toward);
  EXPECT_EQ(seen_d, 10.0);
  EXPECT_EQ(seen_source, 4.0);
  EXPECT_EQ(seen_target, 2.0);
  EXPECT_NEAR(t.y, -0.5, 1e-16);  // positive: toward the source
  const AttractionLaw away = AttractionLaw::from([](double, double, double) { return -0.5; });
  const Vec2 a = calder::attraction({0.0, 0.0}, 4.0, {0.0, 10.0}, 2.0, away);
  EXPECT_NEAR(a.y, 0.5, 1e-16);  // negative: away from the source
  EXPECT_EQ(a.x, 0.0);
}

TEST(Attraction, CustomLawReturningNaNOrInfThrows) {
  const AttractionLaw nan_law = AttractionLaw::from([](double, double, double) { return kNaN; });
  expect_error(
      [&] {
        (void)calder::attraction({0.0, 0.0}, 1.0, {3.0, 4.0}, 1.0, nan_law);
      },
      {"attraction", "custom"});
  const AttractionLaw inf_law = AttractionLaw::from(
      [](double, double, double) { return std::numeric_limits<double>::infinity(); });
  EXPECT_THROW((void)calder::attraction({0.0, 0.0}, 1.0, {3.0, 4.0}, 1.0, inf_law), Error);
}

TEST(Attraction, CoincidentPositionsGiveZeroForceAndNoNaN) {
  AttractionLaw squared;
  squared.clamp = DistanceClamp::squared_distance;
  squared.min = 100.0;
  squared.max = 1000.0;
  bool called = false;
  const AttractionLaw custom = AttractionLaw::from([&](double, double, double) {
    called = true;
    return kNaN;  // would throw if it were asked at distance 0
  });
  for (const AttractionLaw& law : {AttractionLaw::book(), squared, AttractionLaw::newtonian(),
                                   AttractionLaw::newtonian(1.0, 2.0), custom}) {
    const Vec2 f = calder::attraction({5.0, 5.0}, 10.0, {5.0, 5.0}, 3.0, law);
    EXPECT_TRUE(f.is_finite());
    EXPECT_TRUE(is_zero(f));
  }
  EXPECT_FALSE(called);
}

TEST(AttractionLaw, ValidateRejectsBadParameters) {
  AttractionLaw swapped = AttractionLaw::book(1.0, 30.0, 25.0);
  expect_error([&] { swapped.validate("here"); }, {"here", "min", "max"});
  AttractionLaw nan_g = AttractionLaw::book(kNaN);
  expect_error([&] { nan_g.validate("there"); }, {"there", "G"});
  AttractionLaw zero_min = AttractionLaw::book(1.0, 0.0, 25.0);
  expect_error([&] { zero_min.validate("w"); }, {"min"});
  AttractionLaw negative_softening = AttractionLaw::newtonian(1.0, -1.0);
  expect_error([&] { negative_softening.validate("w"); }, {"softening"});
  // Softening with a clamp would be silently unused: an error naming it.
  AttractionLaw clamped_softening = AttractionLaw::book();
  clamped_softening.softening = 4.0;
  expect_error([&] { clamped_softening.validate("w"); }, {"softening", "clamp \"none\""});
  clamped_softening.clamp = DistanceClamp::squared_distance;
  expect_error([&] { clamped_softening.validate("w"); }, {"softening", "clamp \"none\""});
  // Valid laws pass; the book's, the physical one, a custom one.
  EXPECT_NO_THROW(AttractionLaw::book().validate("w"));
  EXPECT_NO_THROW(AttractionLaw::newtonian(6.674e-11, 0.1).validate("w"));
  EXPECT_NO_THROW(AttractionLaw::book(-1.0).validate("w"));  // repulsion is allowed
  EXPECT_NO_THROW(
      AttractionLaw::from([](double d, double, double) { return 1.0 / d; }).validate("w"));
}

TEST(AttractionPotential, InverseDistanceAndContinuousAtTheClamp) {
  // Unclamped: -G M m / d = -1 * 10 * 3 / 6 = -5.
  EXPECT_NEAR(calder::attraction_potential(6.0, 10.0, 3.0, AttractionLaw::newtonian()), -5.0,
              1e-15);
  // Clamped to [5, 25]: continuous at both clamp distances.
  const AttractionLaw law = AttractionLaw::book();
  for (const double d : {5.0, 25.0}) {
    const double u_in = -30.0 / d;
    EXPECT_NEAR(calder::attraction_potential(d - 1e-9, 10.0, 3.0, law), u_in, 1e-8);
    EXPECT_NEAR(calder::attraction_potential(d + 1e-9, 10.0, 3.0, law), u_in, 1e-8);
  }
  // Below the clamp the force is constant 30 / 25 = 1.2, so U grows linearly.
  EXPECT_NEAR(calder::attraction_potential(3.0, 10.0, 3.0, law), -6.0 + 1.2 * (3.0 - 5.0), 1e-14);
  EXPECT_THROW((void)calder::attraction_potential(
                   1.0, 1.0, 1.0, AttractionLaw::from([](double, double, double) { return 1.0; })),
               Error);
}

}  // namespace
