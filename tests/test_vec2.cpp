// SPDX-License-Identifier: MIT
// Tests of calder/vec2.hpp against values worked by hand, and against values
// printed by p5.js 2.3.4's p5.Vector under Node 20 (marked "p5.js:").
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <ostream>
#include <string>

#include "calder/error.hpp"
#include "calder/random.hpp"
#include "calder/vec2.hpp"
#include "support/test_support.hpp"

namespace {

using calder::Error;
using calder::Vec2;
using calder::test::expect_error;

constexpr double kPi = 3.141592653589793;

// --- constexpr use: the value operations work at compile time ---
constexpr Vec2 kSum = Vec2{1.0, 2.0} + Vec2{3.0, 4.5};
static_assert(kSum.x == 4.0 && kSum.y == 6.5);
static_assert(Vec2{5.0, 1.0} - Vec2{2.0, 3.0} == Vec2{3.0, -2.0});
static_assert(Vec2{1.5, -2.0} * 2.0 == Vec2{3.0, -4.0});
static_assert(2.0 * Vec2{1.5, -2.0} == Vec2{3.0, -4.0});
static_assert(-Vec2{1.0, -2.0} == Vec2{-1.0, 2.0});
static_assert(Vec2{3.0, 4.0}.mag_sq() == 25.0);
static_assert(Vec2{1.0, 2.0}.dot(Vec2{3.0, 4.0}) == 11.0);
static_assert(Vec2{1.0, 2.0}.cross(Vec2{3.0, 4.0}) == -2.0);
static_assert(calder::add(Vec2{1.0, 1.0}, Vec2{2.0, 3.0}) == Vec2{3.0, 4.0});
static_assert(calder::lerp(Vec2{0.0, 0.0}, Vec2{4.0, 8.0}, 0.25) == Vec2{1.0, 2.0});
static_assert(Vec2{}.x == 0.0 && Vec2{}.y == 0.0);
static_assert(Vec2{1.0, 2.0} != Vec2{1.0, 3.0});
constexpr Vec2 chained() {
  Vec2 v{1.0, 2.0};
  v.add({1.0, 1.0}).mult(3.0).sub({1.0, 0.0});
  return v;
}
static_assert(chained() == Vec2{5.0, 9.0});

// ------------------------------------------------------ arithmetic ---

TEST(Vec2, DefaultIsZero) {
  const Vec2 v;
  EXPECT_EQ(v.x, 0.0);
  EXPECT_EQ(v.y, 0.0);
}

TEST(Vec2, InPlaceArithmeticChangesAndReturnsThis) {
  Vec2 v{1.0, 2.0};
  Vec2& r = v.add({0.5, -4.0});
  EXPECT_EQ(&r, &v);
  EXPECT_EQ(v, (Vec2{1.5, -2.0}));
  EXPECT_EQ(&v.sub({1.0, 1.0}), &v);
  EXPECT_EQ(v, (Vec2{0.5, -3.0}));
  EXPECT_EQ(&v.mult(4.0), &v);
  EXPECT_EQ(v, (Vec2{2.0, -12.0}));
  EXPECT_EQ(&v.div(8.0), &v);
  EXPECT_EQ(v, (Vec2{0.25, -1.5}));
  EXPECT_EQ(&v.set(7.0, -7.0), &v);
  EXPECT_EQ(v, (Vec2{7.0, -7.0}));
}

TEST(Vec2, DivDividesRatherThanMultipliesByTheReciprocal) {
  // 0.1 / 10 = 0.01 but 0.1 * (1 / 10) = 0.010000000000000002: div must divide.
  ASSERT_NE(0.1 / 10.0, 0.1 * (1.0 / 10.0));
  Vec2 v{0.1, 5.0};
  v.div(10.0);
  EXPECT_EQ(v.x, 0.01);
  EXPECT_EQ(v.y, 0.5);
  EXPECT_EQ((Vec2{5.0, 0.1} / 10.0).y, 0.01);
  EXPECT_EQ(calder::div(Vec2{0.1, 0.1}, 10.0).x, 0.01);
}

TEST(Vec2, DivisionByZeroThrowsAndLeavesTheVectorAlone) {
  Vec2 v{1.0, 2.0};
  expect_error([&] { v.div(0.0); }, "Vec2::div");
  expect_error([&] { v.div(-0.0); }, "division by zero");
  EXPECT_EQ(v, (Vec2{1.0, 2.0}));
  EXPECT_THROW((void)(v / 0.0), Error);
  EXPECT_THROW(v /= 0.0, Error);
  EXPECT_THROW((void)calder::div(v, 0.0), Error);
  EXPECT_EQ(v, (Vec2{1.0, 2.0}));
}

TEST(Vec2, OperatorsReturnNewValuesAndLeaveOperandsAlone) {
  const Vec2 a{1.0, 2.0};
  const Vec2 b{10.0, 20.0};
  EXPECT_EQ(a + b, (Vec2{11.0, 22.0}));
  EXPECT_EQ(b - a, (Vec2{9.0, 18.0}));
  EXPECT_EQ(a * 3.0, (Vec2{3.0, 6.0}));
  EXPECT_EQ(3.0 * a, (Vec2{3.0, 6.0}));
  EXPECT_EQ(b / 4.0, (Vec2{2.5, 5.0}));
  EXPECT_EQ(-a, (Vec2{-1.0, -2.0}));
  EXPECT_EQ(a, (Vec2{1.0, 2.0}));
  EXPECT_EQ(b, (Vec2{10.0, 20.0}));

  Vec2 c = a;
  c += b;
  EXPECT_EQ(c, (Vec2{11.0, 22.0}));
  c -= a;
  EXPECT_EQ(c, b);
  c *= 0.5;
  EXPECT_EQ(c, (Vec2{5.0, 10.0}));
  c /= 5.0;
  EXPECT_EQ(c, a);
  EXPECT_EQ(a, (Vec2{1.0, 2.0}));
}

TEST(Vec2, StaticFormsReturnNewVectors) {
  const Vec2 a{3.0, 4.0};
  const Vec2 b{-1.0, 0.5};
  EXPECT_EQ(calder::add(a, b), (Vec2{2.0, 4.5}));
  EXPECT_EQ(calder::sub(a, b), (Vec2{4.0, 3.5}));
  EXPECT_EQ(calder::mult(a, 2.0), (Vec2{6.0, 8.0}));
  EXPECT_EQ(calder::div(a, 2.0), (Vec2{1.5, 2.0}));
  EXPECT_EQ(calder::dist(a, b), std::sqrt(4.0 * 4.0 + 3.5 * 3.5));
  EXPECT_EQ(calder::dot(a, b), -3.0 + 2.0);
  EXPECT_EQ(calder::cross(a, b), 3.0 * 0.5 - 4.0 * -1.0);
  EXPECT_EQ(calder::lerp(a, b, 0.5), (Vec2{1.0, 2.25}));
  EXPECT_EQ(a, (Vec2{3.0, 4.0}));
  EXPECT_EQ(b, (Vec2{-1.0, 0.5}));
}

TEST(Vec2, CopyIsIndependent) {
  Vec2 a{1.0, 2.0};
  Vec2 b = a.copy();
  b.mult(10.0);
  EXPECT_EQ(a, (Vec2{1.0, 2.0}));
  EXPECT_EQ(b, (Vec2{10.0, 20.0}));
}

TEST(Vec2, ChainsLikeP5) {
  // p5: v.add(w).mult(2).limit(5)
  Vec2 v{1.0, 1.0};
  v.add({2.0, 3.0}).mult(2.0).limit(5.0);
  // (3, 4) * 2 = (6, 8), |v| = 10 > 5: (6 / 10 * 5, 8 / 10 * 5) = (3, 4)
  EXPECT_EQ(v, (Vec2{6.0 / 10.0 * 5.0, 8.0 / 10.0 * 5.0}));
  Vec2 w{0.0, 2.0};
  w.normalize().mult(3.0).sub({0.0, 1.0}).lerp({4.0, 2.0}, 0.5).set_mag(5.0);
  // (0, 1) * 3 - (0, 1) = (0, 2); halfway to (4, 2) is (2, 2); length 5 along it.
  EXPECT_EQ(w, (Vec2{2.0, 2.0}.normalize().mult(5.0)));
  Vec2 turned{0.0, 2.0};
  turned.rotate(-kPi / 2.0).add({1.0, 0.0});  // (2, 0) then (3, 0), up to rounding
  EXPECT_NEAR(turned.x, 3.0, 1e-15);
  EXPECT_NEAR(turned.y, 0.0, 1e-15);
}

// ------------------------------------------------------- lengths ---

TEST(Vec2, MagAndMagSq) {
  EXPECT_EQ((Vec2{3.0, 4.0}).mag(), 5.0);
  EXPECT_EQ((Vec2{-3.0, -4.0}).mag(), 5.0);
  EXPECT_EQ((Vec2{3.0, 4.0}).mag_sq(), 25.0);
  EXPECT_EQ((Vec2{0.0, 0.0}).mag(), 0.0);
  EXPECT_EQ((Vec2{5.0, 12.0}).mag(), 13.0);
  // sqrt(x*x + y*y), not hypot: (0.1, 0.2) shows which.
  const double x = 0.1;
  const double y = 0.2;
  EXPECT_EQ((Vec2{x, y}).mag(), std::sqrt(x * x + y * y));
  EXPECT_EQ((Vec2{x, y}).mag_sq(), x * x + y * y);
  // Overflows like p5 (x * x is inf) instead of hypot's finite answer.
  EXPECT_EQ((Vec2{1e200, 0.0}).mag(), std::numeric_limits<double>::infinity());
}

TEST(Vec2, NormalizeMultipliesByTheReciprocal) {
  Vec2 v{3.0, 4.0};
  Vec2& r = v.normalize();
  EXPECT_EQ(&r, &v);
  EXPECT_EQ(v.x, 3.0 * (1.0 / 5.0));  // 0.6000000000000001, not 3 / 5 = 0.6
  EXPECT_EQ(v.y, 4.0 * (1.0 / 5.0));
  EXPECT_NE(v.x, 3.0 / 5.0);
  // p5.js: new p5.Vector(3, 4).normalize()
  EXPECT_EQ(v, (Vec2{0.6000000000000001, 0.8}));
  Vec2 diagonal{1.0, 1.0};
  diagonal.normalize();
  EXPECT_EQ(diagonal, (Vec2{0.7071067811865475, 0.7071067811865475}));  // p5.js
}

TEST(Vec2, NormalizeAndSetMagKeepZeroAtZero) {
  Vec2 zero;
  zero.normalize();
  EXPECT_EQ(zero, Vec2{});
  EXPECT_TRUE(zero.is_finite());
  zero.set_mag(5.0);
  EXPECT_EQ(zero, Vec2{});
  EXPECT_TRUE(zero.is_finite());
}

TEST(Vec2, SetMagIsNormalizeThenMult) {
  Vec2 v{1.0, 2.0};
  const double len = std::sqrt(1.0 * 1.0 + 2.0 * 2.0);
  Vec2& r = v.set_mag(3.0);
  EXPECT_EQ(&r, &v);
  EXPECT_EQ(v.x, 1.0 * (1.0 / len) * 3.0);
  EXPECT_EQ(v.y, 2.0 * (1.0 / len) * 3.0);
  // p5.js: new p5.Vector(1, 2).setMag(3)
  EXPECT_EQ(v, (Vec2{1.3416407864998738, 2.6832815729997477}));
  Vec2 w{3.0, 4.0};
  w.set_mag(-10.0);  // a negative length flips the direction
  EXPECT_NEAR(w.x, -6.0, 1e-15);
  EXPECT_NEAR(w.y, -8.0, 1e-15);
}

TEST(Vec2, LimitShortensOnlyLongerVectors) {
  Vec2 longer{30.0, 40.0};
  Vec2& r = longer.limit(10.0);
  EXPECT_EQ(&r, &longer);
  // Divide by sqrt(2500) = 50, then multiply by 10 (p5's order).
  EXPECT_EQ(longer, (Vec2{30.0 / 50.0 * 10.0, 40.0 / 50.0 * 10.0}));
  EXPECT_EQ(longer, (Vec2{6.0, 8.0}));  // p5.js: new p5.Vector(30, 40).limit(10)

  Vec2 shorter{1.0, 2.0};
  shorter.limit(7.0);
  EXPECT_EQ(shorter, (Vec2{1.0, 2.0}));

  Vec2 exact{3.0, 4.0};  // |v| == max: unchanged (strictly longer only)
  exact.limit(5.0);
  EXPECT_EQ(exact, (Vec2{3.0, 4.0}));

  // The order decides the bits: (x / len) * max, not x * (max / len).
  const double x = 0.7;
  const double y = 2.9;
  const double len = std::sqrt(x * x + y * y);
  const double max = 0.3;
  Vec2 v{x, y};
  v.limit(max);
  EXPECT_EQ(v.x, x / len * max);
  EXPECT_EQ(v.y, y / len * max);
  EXPECT_NEAR(v.mag(), max, 1e-15);

  Vec2 zero;
  zero.limit(0.0);
  EXPECT_EQ(zero, Vec2{});
}

// ------------------------------------------------------- angles ---

TEST(Vec2, Heading) {
  EXPECT_EQ((Vec2{1.0, 0.0}).heading(), 0.0);
  EXPECT_EQ((Vec2{0.0, 1.0}).heading(), kPi / 2.0);
  EXPECT_EQ((Vec2{-1.0, 0.0}).heading(), kPi);
  EXPECT_EQ((Vec2{0.0, -2.0}).heading(), -kPi / 2.0);
  EXPECT_EQ((Vec2{-1.0, 1.0}).heading(), 2.356194490192345);  // p5.js, 3 pi / 4
  EXPECT_EQ((Vec2{3.0, 4.0}).heading(), calder::math::atan2(4.0, 3.0));
}

TEST(Vec2, RotateKeepsLengthAndTurnsByTheAngle) {
  Vec2 v{3.0, 4.0};
  Vec2& r = v.rotate(kPi / 2.0);
  EXPECT_EQ(&r, &v);
  // A quarter turn counterclockwise (in y-up terms) of (3, 4) is (-4, 3).
  EXPECT_NEAR(v.x, -4.0, 1e-14);
  EXPECT_NEAR(v.y, 3.0, 1e-14);
  EXPECT_NEAR(v.dot({3.0, 4.0}), 0.0, 1e-13);  // perpendicular
  EXPECT_NEAR(v.mag(), 5.0, 1e-14);

  // p5's formula: (cos(heading + a) * len, sin(heading + a) * len).
  Vec2 w{1.5, -0.5};
  const double heading = calder::math::atan2(-0.5, 1.5);
  const double len = std::sqrt(1.5 * 1.5 + 0.5 * 0.5);
  w.rotate(0.3);
  EXPECT_EQ(w.x, calder::math::cos(heading + 0.3) * len);
  EXPECT_EQ(w.y, calder::math::sin(heading + 0.3) * len);

  Vec2 unit{1.0, 0.0};
  unit.rotate(1.0);  // p5.js: new p5.Vector(1, 0).rotate(1)
  EXPECT_DOUBLE_EQ(unit.x, 0.5403023058681398);
  EXPECT_DOUBLE_EQ(unit.y, 0.8414709848078965);

  Vec2 full{2.0, 7.0};
  full.rotate(2.0 * kPi);
  EXPECT_NEAR(full.x, 2.0, 1e-14);
  EXPECT_NEAR(full.y, 7.0, 1e-14);
}

TEST(Vec2, FromAngle) {
  const Vec2 unit = Vec2::from_angle(0.0);
  EXPECT_EQ(unit, (Vec2{1.0, 0.0}));
  const Vec2 up = Vec2::from_angle(kPi / 2.0);
  EXPECT_NEAR(up.x, 0.0, 1e-16);
  EXPECT_EQ(up.y, 1.0);
  const Vec2 v = Vec2::from_angle(1.2, 3.0);
  EXPECT_EQ(v.x, 3.0 * calder::math::cos(1.2));
  EXPECT_EQ(v.y, 3.0 * calder::math::sin(1.2));
  // p5.js: p5.Vector.fromAngle(1.2, 3)
  EXPECT_DOUBLE_EQ(v.x, 1.0870732634300209);
  EXPECT_DOUBLE_EQ(v.y, 2.796117257901679);
  EXPECT_NEAR(v.mag(), 3.0, 1e-15);
  EXPECT_NEAR(v.heading(), 1.2, 1e-15);
}

// ---------------------------------------------------- products, dist ---

TEST(Vec2, DotCrossDist) {
  const Vec2 a{2.0, 3.0};
  const Vec2 b{-4.0, 5.0};
  EXPECT_EQ(a.dot(b), 2.0 * -4.0 + 3.0 * 5.0);
  EXPECT_EQ(a.dot(b), 7.0);
  EXPECT_EQ(a.cross(b), 2.0 * 5.0 - 3.0 * -4.0);
  EXPECT_EQ(a.cross(b), 22.0);
  EXPECT_EQ(b.cross(a), -22.0);
  EXPECT_EQ((Vec2{1.0, 0.0}).cross({0.0, 1.0}), 1.0);
  EXPECT_EQ((Vec2{1.0, 0.0}).dot({0.0, 1.0}), 0.0);

  EXPECT_EQ((Vec2{1.0, 1.0}).dist({4.0, 5.0}), 5.0);
  EXPECT_EQ((Vec2{4.0, 5.0}).dist({1.0, 1.0}), 5.0);
  EXPECT_EQ(a.dist(a), 0.0);
  // p5.js: new p5.Vector(1, 2).dist(new p5.Vector(4.5, -3))
  EXPECT_EQ((Vec2{1.0, 2.0}).dist({4.5, -3.0}), 6.103277807866851);
}

TEST(Vec2, StaticDistMatchesMember) {
  const Vec2 a{3.0, 4.0};
  const Vec2 b{-1.0, 0.5};
  // (-4, -3.5): sqrt(16 + 12.25) = sqrt(28.25)
  EXPECT_EQ(calder::dist(a, b), std::sqrt(28.25));
  EXPECT_EQ(calder::dist(a, b), a.dist(b));
}

// ------------------------------------------------------------ lerp ---

TEST(Vec2, Lerp) {
  Vec2 v{1.0, 2.0};
  Vec2& r = v.lerp({4.0, 8.0}, 0.3);
  EXPECT_EQ(&r, &v);
  EXPECT_EQ(v.x, 1.0 + (4.0 - 1.0) * 0.3);
  EXPECT_EQ(v.y, 2.0 + (8.0 - 2.0) * 0.3);
  EXPECT_EQ(v, (Vec2{1.9, 3.8}));  // p5.js: new p5.Vector(1, 2).lerp(new p5.Vector(4, 8), 0.3)

  Vec2 start{-1.0, 3.0};
  start.lerp({5.0, -3.0}, 0.0);
  EXPECT_EQ(start, (Vec2{-1.0, 3.0}));
  start.lerp({5.0, -3.0}, 1.0);
  EXPECT_EQ(start, (Vec2{5.0, -3.0}));
}

// --------------------------------------------------------- is_finite ---

TEST(Vec2, IsFinite) {
  EXPECT_TRUE((Vec2{1.0, -1e300}).is_finite());
  EXPECT_FALSE((Vec2{std::numeric_limits<double>::quiet_NaN(), 0.0}).is_finite());
  EXPECT_FALSE((Vec2{0.0, -std::numeric_limits<double>::infinity()}).is_finite());
}

// -------------------------------------------------------- random2d ---

TEST(Vec2, Random2dIsAUnitVectorFromTheGenerator) {
  calder::Random a(2024u);
  calder::Random b(2024u);
  for (int i = 0; i < 1000; ++i) {
    const Vec2 v = Vec2::random2d(a);
    ASSERT_NEAR(v.mag(), 1.0, 1e-15);
    ASSERT_EQ(v, Vec2::random2d(b));  // same seed, same vectors
  }
  calder::Random c(2025u);
  EXPECT_NE(Vec2::random2d(a), Vec2::random2d(c));

  // One draw per vector, at angle draw * 2 pi.
  calder::Random d(5u);
  calder::Random e(5u);
  const Vec2 v = Vec2::random2d(d);
  const double angle = e.random() * (2.0 * kPi);
  EXPECT_EQ(v, Vec2::from_angle(angle));
  EXPECT_EQ(d.state(), e.state());
}

TEST(Vec2, Random2dCoversAllDirections) {
  calder::Random rng(9u);
  int quadrants[4] = {0, 0, 0, 0};
  Vec2 sum;
  constexpr int n = 20000;
  for (int i = 0; i < n; ++i) {
    const Vec2 v = Vec2::random2d(rng);
    ++quadrants[(v.x >= 0.0 ? 0 : 1) + (v.y >= 0.0 ? 0 : 2)];
    sum += v;
  }
  for (const int count : quadrants) EXPECT_NEAR(count, n / 4, n / 40);
  EXPECT_LT((sum / n).mag(), 0.03);  // mean direction near zero
}

TEST(Vec2, Random2dWithoutGeneratorUsesTheDefault) {
  calder::random_seed(4321u);
  const Vec2 first = Vec2::random2d();
  const Vec2 second = Vec2::random2d();
  calder::random_seed(4321u);
  EXPECT_EQ(Vec2::random2d(), first);
  EXPECT_EQ(Vec2::random2d(), second);
  calder::Random same(4321u);
  EXPECT_EQ(Vec2::random2d(same), first);
}

}  // namespace
