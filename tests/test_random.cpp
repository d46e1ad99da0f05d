// SPDX-License-Identifier: MIT
// Tests of calder/random.hpp (and the error helpers of calder/error.hpp).
//
// Truth comes from three independent places:
//  - the LCG recurrence worked by hand (in comments) or re-run by TestLcg below,
//    a ten-line generator that shares no code with src/random.cpp;
//  - formulas of the spec applied by hand to TestLcg's draws;
//  - values printed by p5.js 2.3.4 itself (its math/random.js and math/noise.js
//    run under Node 20), marked "p5.js:" below.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include "calder/error.hpp"
#include "calder/random.hpp"
#include "calder/vec2.hpp"
#include "support/test_support.hpp"

namespace {

using calder::Error;
using calder::Noise;
using calder::Random;
using calder::Vec2;
using calder::test::expect_error;

constexpr double kTwoPow32 = 4294967296.0;
constexpr double kPi = 3.141592653589793;
const double kNan = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

// An independent LCG: state = (1664525 * state + 1013904223) mod 2^32.
struct TestLcg {
  std::uint64_t state;
  double next() {
    state = (1664525u * state + 1013904223u) % 4294967296u;
    return static_cast<double>(state) / kTwoPow32;
  }
};

// The 4096-entry noise table that noiseSeed(seed) makes.
std::vector<double> noise_table(std::uint32_t seed) {
  TestLcg lcg{seed};
  std::vector<double> table(4096);
  for (double& value : table) value = lcg.next();
  return table;
}

// ----------------------------------------------------------- random() ---

TEST(Random, FirstDrawsAfterSeed1AreTheLcgWorkedByHand) {
  Random rng(1);
  // state1 = 1664525 * 1 + 1013904223 = 1015568748 (< 2^32, no wrap)
  EXPECT_EQ(rng.random(), 1015568748.0 / kTwoPow32);
  EXPECT_EQ(rng.state(), 1015568748u);
  // 1664525 * 1015568748 + 1013904223 = 1690440584168923
  //   = 393586 * 2^32 + 1586005467  ->  state2 = 1586005467
  EXPECT_EQ(rng.random(), 1586005467.0 / kTwoPow32);
  // 1664525 * 1586005467 + 1013904223 = 2639946763862398
  //   = 614660 * 2^32 + 2165703038  ->  state3 = 2165703038
  EXPECT_EQ(rng.random(), 2165703038.0 / kTwoPow32);
  EXPECT_EQ(rng.state(), 2165703038u);
}

TEST(Random, MatchesP5AfterSeed1) {
  Random rng;
  rng.random_seed(1u);
  // p5.js: randomSeed(1); random(), random(), random()
  EXPECT_EQ(rng.random(), 0.23645552527159452);
  EXPECT_EQ(rng.random(), 0.3692706737201661);
  EXPECT_EQ(rng.random(), 0.5042420323006809);
}

TEST(Random, DefaultSeedIsZero) {
  Random rng;
  EXPECT_EQ(rng.state(), 0u);
  // 1664525 * 0 + 1013904223 = 1013904223
  EXPECT_EQ(rng.random(), 1013904223.0 / kTwoPow32);
}

TEST(Random, FollowsTheIndependentLcgForManyDraws) {
  Random rng(123456789u);
  TestLcg lcg{123456789u};
  for (int i = 0; i < 10000; ++i) ASSERT_EQ(rng.random(), lcg.next()) << "draw " << i;
  EXPECT_EQ(rng.state(), lcg.state);
}

TEST(Random, StateWrapsAtTheTopOfTheRange) {
  // 1664525 * (2^32 - 1) + 1013904223 = 7149081450614098 = 1664525 * 2^32 + 1012239698
  Random rng(4294967295u);
  EXPECT_EQ(rng.random(), 1012239698.0 / kTwoPow32);
}

TEST(Random, ScaledAndRangedDraws) {
  Random rng(7u);
  TestLcg lcg{7u};
  EXPECT_EQ(rng.random(640.0), lcg.next() * 640.0);
  EXPECT_EQ(rng.random(0.5, 3.0), lcg.next() * (3.0 - 0.5) + 0.5);
  EXPECT_EQ(rng.random(-2.0, 5.0), lcg.next() * (5.0 - -2.0) + -2.0);
  EXPECT_EQ(rng.random(-1.0), lcg.next() * -1.0);
}

TEST(Random, SwappedBoundsGiveTheSameDraw) {
  Random a(99u);
  Random b(99u);
  for (int i = 0; i < 100; ++i) ASSERT_EQ(a.random(0.1, 2.0), b.random(2.0, 0.1));
}

TEST(Random, MatchesP5ForTheBookArguments) {
  // p5.js: randomSeed(42); random(640), random(240), random(0.5, 3), random(3, 0.5)
  Random rng(42u);
  EXPECT_EQ(rng.random(640.0), 161.5009118616581);
  EXPECT_EQ(rng.random(240.0), 21.150010898709297);
  EXPECT_EQ(rng.random(0.5, 3.0), 1.9432029955787584);
  EXPECT_EQ(rng.random(3.0, 0.5), 1.05638566496782);
}

TEST(Random, DrawsStayInRange) {
  Random rng(2024u);
  double lowest = 1.0;
  double highest = 0.0;
  for (int i = 0; i < 100000; ++i) {
    const double u = rng.random();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    lowest = std::fmin(lowest, u);
    highest = std::fmax(highest, u);
    const double r = rng.random(-3.0, 7.0);
    ASSERT_GE(r, -3.0);
    ASSERT_LT(r, 7.0);
  }
  // Uniform: 1e5 draws come close to both ends.
  EXPECT_LT(lowest, 0.001);
  EXPECT_GT(highest, 0.999);
}

TEST(Random, TheLargestDrawIsBelowOne) {
  // A state of 2^32 - 1 gives the largest possible draw, still below 1.
  const double largest = 4294967295.0 / kTwoPow32;
  EXPECT_LT(largest, 1.0);
  // Find the state that precedes 2^32 - 1 by inverting the LCG: a^-1 mod 2^32.
  // 1664525 * 4276115653 = 1 mod 2^32 (checked below).
  const std::uint64_t a_inverse = 4276115653u;
  ASSERT_EQ((1664525u * a_inverse) % 4294967296u, 1u);
  const std::uint64_t previous =
      ((4294967295u + 4294967296u - 1013904223u) % 4294967296u) * a_inverse % 4294967296u;
  Random rng(static_cast<std::uint32_t>(previous));
  EXPECT_EQ(rng.random(), largest);
}

TEST(Random, SeedFromDoubleConvertsLikeJavaScriptUnsignedShift) {
  Random rng;
  // p5.js: randomSeed(-1) leaves state 4294967295, and so on.
  rng.random_seed(-1.0);
  EXPECT_EQ(rng.state(), 4294967295u);
  rng.random_seed(4294967296.0 + 5.0);
  EXPECT_EQ(rng.state(), 5u);
  rng.random_seed(3.9);
  EXPECT_EQ(rng.state(), 3u);
  rng.random_seed(-3.9);  // truncates to -3, then wraps
  EXPECT_EQ(rng.state(), 4294967293u);
  rng.random_seed(-0.5);
  EXPECT_EQ(rng.state(), 0u);
  rng.random_seed(1e20);  // 10^20 mod 2^32 = 1661992960
  EXPECT_EQ(rng.state(), 1661992960u);
  rng.random_seed(1.0);
  EXPECT_EQ(rng.random(), 0.23645552527159452);
}

TEST(Random, NonFiniteSeedThrows) {
  Random rng(5u);
  expect_error([&] { rng.random_seed(kNan); }, "random_seed");
  expect_error([&] { rng.random_seed(kInf); }, "must be finite");
  expect_error([&] { rng.random_seed(-kInf); }, "got -inf");
  EXPECT_EQ(rng.state(), 5u);  // unchanged
}

TEST(Random, NonFiniteArgumentsThrow) {
  Random rng(5u);
  expect_error([&] { (void)rng.random(kNan); }, "random");
  expect_error([&] { (void)rng.random(kInf); }, "max");
  expect_error([&] { (void)rng.random(kNan, 1.0); }, "min");
  expect_error([&] { (void)rng.random(0.0, kInf); }, "max");
  expect_error([&] { (void)rng.random_gaussian(kNan, 1.0); }, "mean");
  expect_error([&] { (void)rng.random_gaussian(0.0, kInf); }, "sd");
}

// --------------------------------------------------- random_gaussian() ---

// One polar Box-Muller pair computed by hand from TestLcg (the spec's algorithm).
struct GaussianPair {
  double first;
  double second;
};
GaussianPair gaussian_pair_by_hand(TestLcg& lcg) {
  double x1 = 0.0;
  double x2 = 0.0;
  double w = 0.0;
  do {
    x1 = lcg.next() * 2.0 - 1.0;
    x2 = lcg.next() * 2.0 - 1.0;
    w = x1 * x1 + x2 * x2;
  } while (w >= 1.0);
  const double scale = std::sqrt(-2.0 * std::log(w) / w);
  return {x1 * scale, x2 * scale};
}

TEST(RandomGaussian, FirstPairAfterSeed1ByHand) {
  // Seed 1 draws 0.23645552527159452 and 0.3692706737201661:
  // x1 = 2 * 0.2364... - 1 = -0.527088949456811, x2 = -0.2614586525596678,
  // w = x1^2 + x2^2 = 0.3462... < 1, accepted on the first try.
  TestLcg lcg{1};
  const double x1 = lcg.next() * 2.0 - 1.0;
  const double x2 = lcg.next() * 2.0 - 1.0;
  const double w = x1 * x1 + x2 * x2;
  ASSERT_LT(w, 1.0);
  const double scale = std::sqrt(-2.0 * std::log(w) / w);

  Random rng(1u);
  EXPECT_EQ(rng.random_gaussian(), x1 * scale);
  EXPECT_EQ(rng.state(), 1586005467u);  // exactly two draws used
  // The second call returns the kept value and draws nothing.
  EXPECT_EQ(rng.random_gaussian(), x2 * scale);
  EXPECT_EQ(rng.state(), 1586005467u);
  // The third call starts a new pair.
  TestLcg rest{1586005467u};
  const GaussianPair next = gaussian_pair_by_hand(rest);
  EXPECT_EQ(rng.random_gaussian(), next.first);
  EXPECT_EQ(rng.state(), rest.state);
}

TEST(RandomGaussian, MatchesP5) {
  // p5.js: randomSeed(1); randomGaussian() three times. Bit for bit: p5 takes
  // log from V8 (fdlibm), calder from the C library; they agree here on glibc.
  // A failure on another platform means its log differs in the last bit.
  Random rng(1u);
  EXPECT_EQ(rng.random_gaussian(), -1.3048476699656055);
  EXPECT_EQ(rng.random_gaussian(), -0.6472602279680005);
  EXPECT_EQ(rng.random_gaussian(), 0.03909988738161074);
  // p5.js: randomSeed(42); randomGaussian(10, 2) twice.
  rng.random_seed(42u);
  EXPECT_EQ(rng.random_gaussian(10.0, 2.0), 9.589934791200637);
  EXPECT_EQ(rng.random_gaussian(10.0, 2.0), 9.318020195628202);
}

TEST(RandomGaussian, AppliesMeanAndSdAsYTimesSdPlusMean) {
  TestLcg lcg{42};
  const GaussianPair pair = gaussian_pair_by_hand(lcg);
  Random rng(42u);
  EXPECT_EQ(rng.random_gaussian(10.0, 2.0), pair.first * 2.0 + 10.0);
  EXPECT_EQ(rng.random_gaussian(-3.0, 0.5), pair.second * 0.5 + -3.0);
}

TEST(RandomGaussian, RejectsPairsOutsideTheUnitCircle) {
  // Find a seed whose first pair lies outside the unit circle.
  std::uint32_t seed = 0;
  for (;; ++seed) {
    TestLcg probe{seed};
    const double x1 = probe.next() * 2.0 - 1.0;
    const double x2 = probe.next() * 2.0 - 1.0;
    if (x1 * x1 + x2 * x2 >= 1.0) break;
  }
  TestLcg lcg{seed};
  lcg.next();
  lcg.next();  // the rejected pair
  const GaussianPair pair = gaussian_pair_by_hand(lcg);
  Random rng(seed);
  EXPECT_EQ(rng.random_gaussian(), pair.first);
  EXPECT_EQ(rng.random_gaussian(), pair.second);
  EXPECT_EQ(rng.state(), lcg.state);
}

TEST(RandomGaussian, ReseedingForgetsTheKeptValue) {
  Random rng(1u);
  const double first = rng.random_gaussian();
  const double kept = rng.random_gaussian();
  ASSERT_NE(first, kept);

  rng.random_seed(1u);
  EXPECT_EQ(rng.random_gaussian(), first);
  rng.random_seed(1u);  // the kept value must not come back after a reseed
  EXPECT_EQ(rng.random_gaussian(), first);
  rng.random_seed(1.0);  // nor after a reseed from a double
  EXPECT_EQ(rng.random_gaussian(), first);
  EXPECT_EQ(rng.random_gaussian(), kept);
}

TEST(RandomGaussian, SampleMeanAndStandardDeviation) {
  Random rng(31337u);
  constexpr int n = 100000;
  double sum = 0.0;
  double sum_sq = 0.0;
  for (int i = 0; i < n; ++i) {
    const double g = rng.random_gaussian(5.0, 3.0);
    ASSERT_TRUE(std::isfinite(g));
    sum += g;
    sum_sq += g * g;
  }
  const double mean = sum / n;
  const double sd = std::sqrt(sum_sq / n - mean * mean);
  // Standard error of the mean: 3 / sqrt(1e5) ~ 0.0095; of the sd: ~ 0.0067.
  EXPECT_NEAR(mean, 5.0, 0.05);
  EXPECT_NEAR(sd, 3.0, 0.035);
}

// ----------------------------------------------------------- random2d ---

TEST(Random2d, IsTheUnitVectorAtDrawTimesTwoPi) {
  TestLcg lcg{8};
  Random rng(8u);
  for (int i = 0; i < 100; ++i) {
    const double angle = lcg.next() * (kPi * 2.0);
    const Vec2 v = rng.random2d();
    ASSERT_EQ(v.x, calder::math::cos(angle));  // p5's Math.cos, calder's own
    ASSERT_EQ(v.y, calder::math::sin(angle));
    ASSERT_NEAR(v.mag(), 1.0, 1e-15);
  }
}

TEST(Random2d, StaticFormsDrawFromTheGivenOrDefaultGenerator) {
  Random a(77u);
  Random b(77u);
  EXPECT_EQ(Vec2::random2d(a), b.random2d());
  EXPECT_EQ(a.state(), b.state());

  calder::random_seed(77u);
  const Vec2 from_default = Vec2::random2d();
  EXPECT_EQ(from_default, Random(77u).random2d());
  EXPECT_EQ(calder::default_random().state(), a.state());
}

// ----------------------------------------------------------- globals ---

TEST(Globals, UseOneProcessWideGenerator) {
  EXPECT_EQ(&calder::default_random(), &calder::default_random());
  EXPECT_EQ(&calder::default_noise(), &calder::default_noise());

  calder::random_seed(1u);
  EXPECT_EQ(calder::random(), 0.23645552527159452);
  EXPECT_EQ(calder::default_random().state(), 1015568748u);
  EXPECT_EQ(calder::random(10.0), 0.3692706737201661 * 10.0);
  EXPECT_EQ(calder::random(2.0, 1.0), 0.5042420323006809 * (2.0 - 1.0) + 1.0);

  calder::random_seed(1u);
  EXPECT_EQ(calder::random_gaussian(), Random(1u).random_gaussian());

  calder::noise_seed(3u);
  calder::noise_detail(4, 0.5);
  EXPECT_EQ(calder::noise(1.5, 2.5, 3.5), Noise(3u).noise(1.5, 2.5, 3.5));
  calder::noise_detail(2, 0.25);
  Noise local(3u);
  local.noise_detail(2, 0.25);
  EXPECT_EQ(calder::noise(1.5, 2.5, 3.5), local.noise(1.5, 2.5, 3.5));
  calder::noise_detail(4, 0.5);  // leave the defaults for other tests
}

// ------------------------------------------------------------- noise ---

TEST(Noise, AtTheOriginEveryOctaveReadsTheFirstTableEntry) {
  // At integer coordinates every fraction is 0, so each octave's blends have
  // weight 0.5 * (1 - cos 0) = 0 and return T[offset]. At (0, 0, 0) every
  // octave's offset is 0, so noise = T[0] * (0.5 + 0.25 + 0.125 + 0.0625).
  // T[0] is the first draw after seeding 1: 1015568748 / 2^32.
  Noise noise(1u);
  const double t0 = 1015568748.0 / kTwoPow32;
  EXPECT_EQ(noise.noise(0.0, 0.0, 0.0), t0 * 0.9375);  // exact: t0 has 30 bits
  EXPECT_EQ(noise.noise(0.0), 0.22167705494211987);    // p5.js: noiseSeed(1); noise(0)
}

TEST(Noise, AtIntegerPointsOctaveKReadsTheScaledOffset) {
  // Octave k sees integer parts xi << k (fractions stay 0), so its offset is
  // (xi + 16 yi + 256 zi) << k.
  const std::vector<double> t = noise_table(1u);
  Noise noise(1u);
  EXPECT_EQ(noise.noise(1.0, 0.0, 0.0), t[1] * 0.5 + t[2] * 0.25 + t[4] * 0.125 + t[8] * 0.0625);
  EXPECT_EQ(noise.noise(0.0, 1.0, 0.0),
            t[16] * 0.5 + t[32] * 0.25 + t[64] * 0.125 + t[128] * 0.0625);
  EXPECT_EQ(noise.noise(0.0, 0.0, 1.0),
            t[256] * 0.5 + t[512] * 0.25 + t[1024] * 0.125 + t[2048] * 0.0625);
  // (3, 2, 1): offset 3 + 32 + 256 = 291, then 582, 1164, 2328.
  EXPECT_EQ(noise.noise(3.0, 2.0, 1.0),
            t[291] * 0.5 + t[582] * 0.25 + t[1164] * 0.125 + t[2328] * 0.0625);
  // (0, 0, 9): offsets 2304, 4608 & 4095 = 512, 1024, 2048 (the table wraps).
  EXPECT_EQ(noise.noise(0.0, 0.0, 9.0),
            t[2304] * 0.5 + t[512] * 0.25 + t[1024] * 0.125 + t[2048] * 0.0625);
  // p5.js: noiseSeed(1); noise(1,0,0), noise(0,1,0), noise(0,0,1)
  EXPECT_EQ(noise.noise(1.0, 0.0, 0.0), 0.3180446257465519);
  EXPECT_EQ(noise.noise(0.0, 1.0, 0.0), 0.6483961020712741);
  EXPECT_EQ(noise.noise(0.0, 0.0, 1.0), 0.4392317433957942);
}

TEST(Noise, OneOctaveInOneDimensionIsACosineBlendOfNeighbours) {
  // With one octave and y = z = 0 (weights 0), noise(x) reduces to
  // 0.5 * (T[i] + f * (T[i+1] - T[i])), i = floor(x), f = 0.5 (1 - cos(frac * pi)).
  const std::vector<double> t = noise_table(5u);
  Noise noise(5u);
  noise.noise_detail(1, 0.5);
  for (const double x : {0.25, 0.5, 1.75, 17.3, 4094.6}) {
    const auto i = static_cast<std::size_t>(std::floor(x));
    const double f = 0.5 * (1.0 - std::cos((x - std::floor(x)) * kPi));
    double n = t[i];
    n += f * (t[i + 1] - n);
    EXPECT_EQ(noise.noise(x), n * 0.5) << "x = " << x;
  }
  // 4095.5 blends T[4095] with T[4096 & 4095] = T[0].
  const double f = 0.5 * (1.0 - std::cos(0.5 * kPi));
  EXPECT_EQ(noise.noise(4095.5), (t[4095] + f * (t[0] - t[4095])) * 0.5);
}

TEST(Noise, MatchesP5AtFractionalPoints) {
  // Bit for bit: p5 blends with V8's Math.cos (fdlibm), calder with the C
  // library's cos; they agree here on glibc. A failure on another platform
  // means its cos differs in the last bit.
  Noise noise(1u);
  EXPECT_EQ(noise.noise(0.5), 0.3099384490051307);
  EXPECT_EQ(noise.noise(1.25, 2.75), 0.61011057807676);
  EXPECT_EQ(noise.noise(3.3, 4.4, 5.5), 0.2821602119597615);
  EXPECT_EQ(noise.noise(-3.3, -4.4, -5.5), 0.2821602119597615);
  EXPECT_EQ(noise.noise(100.123, 0.001, 7.0), 0.3758912365230302);
  EXPECT_EQ(noise.noise(1e6 + 0.37, 12345.678), 0.4313696455023899);
  // Coordinates past 2^31 and 2^32 (JavaScript's 32-bit shifts wrap).
  EXPECT_EQ(noise.noise(2147483647.5, 0.0, 0.0), 0.3585938132018782);
  EXPECT_EQ(noise.noise(4294967296.25, 3.0, 0.0), 0.5623382203953942);
  EXPECT_EQ(noise.noise(123456789012.7, 5.5, 1.0), 0.5069831674001323);

  Noise other(99u);
  EXPECT_EQ(other.noise(0.1), 0.25508358018631005);
  EXPECT_EQ(other.noise(10.5, 20.25), 0.4428100043935073);
  EXPECT_EQ(other.noise(0.9, 0.9, 0.9), 0.5035174711579301);
}

TEST(Noise, MatchesP5WithMoreOctaves) {
  // p5.js: noiseSeed(1); noiseDetail(8, 0.65); noise(...)
  Noise noise(1u);
  noise.noise_detail(8, 0.65);
  EXPECT_EQ(noise.noise(0.5), 0.46839126462089636);
  EXPECT_EQ(noise.noise(1.25, 2.75), 0.8456987680208128);
  EXPECT_EQ(noise.noise(3.3, 4.4, 5.5), 0.444922848455082);
}

TEST(Noise, IsContinuous) {
  Noise noise(11u);
  for (double x = 0.0; x < 20.0; x += 0.37) {
    const double y = x * 0.7 + 0.1;
    const double a = noise.noise(x, y, 1.3);
    const double b = noise.noise(x + 1e-9, y, 1.3);
    EXPECT_NEAR(a, b, 1e-7) << "x = " << x;
    // Across an integer boundary as well.
    const double k = std::floor(x) + 1.0;
    EXPECT_NEAR(noise.noise(k - 1e-9, y), noise.noise(k, y), 1e-7) << "k = " << k;
  }
}

TEST(Noise, StaysInTheUnitInterval) {
  Noise noise(12u);
  Random rng(12u);
  for (int i = 0; i < 20000; ++i) {
    const double value =
        noise.noise(rng.random(-1000.0, 1000.0), rng.random(-50.0, 50.0), rng.random(0.0, 5.0));
    ASSERT_GE(value, 0.0);
    ASSERT_LT(value, 1.0);
  }
}

TEST(Noise, IsSymmetricInTheSignOfEachCoordinate) {
  Noise noise(13u);
  for (double x = 0.05; x < 10.0; x += 0.731) {
    const double y = 2.0 * x + 0.3;
    const double z = x / 3.0;
    const double value = noise.noise(x, y, z);
    EXPECT_EQ(noise.noise(-x, y, z), value);
    EXPECT_EQ(noise.noise(x, -y, z), value);
    EXPECT_EQ(noise.noise(x, y, -z), value);
    EXPECT_EQ(noise.noise(-x, -y, -z), value);
  }
}

TEST(Noise, RepeatsWithTheTablePeriod) {
  // Offsets wrap modulo 4096: x repeats every 4096, y every 256, z every 16
  // (exact here because the fractions are dyadic and survive the shift).
  Noise noise(14u);
  const double value = noise.noise(0.25, 1.5, 2.75);
  EXPECT_EQ(noise.noise(4096.25, 1.5, 2.75), value);
  EXPECT_EQ(noise.noise(0.25, 257.5, 2.75), value);
  EXPECT_EQ(noise.noise(0.25, 1.5, 18.75), value);
  EXPECT_NE(noise.noise(1.25, 1.5, 2.75), value);
}

TEST(Noise, IsDeterministicAndDependsOnTheSeed) {
  Noise a(20u);
  Noise b(20u);
  Noise c(21u);
  int differences = 0;
  for (double x = 0.0; x < 50.0; x += 1.3) {
    EXPECT_EQ(a.noise(x, 0.5), b.noise(x, 0.5));
    EXPECT_EQ(a.noise(x, 0.5), a.noise(x, 0.5));
    if (a.noise(x, 0.5) != c.noise(x, 0.5)) ++differences;
  }
  EXPECT_GT(differences, 30);

  // Reseeding refills the table.
  c.noise_seed(20u);
  EXPECT_EQ(c.noise(3.7, 1.1, 0.2), a.noise(3.7, 1.1, 0.2));
}

TEST(Noise, DefaultSeedIsZero) {
  Noise by_default;
  Noise zero(0u);
  EXPECT_EQ(by_default.noise(0.0), (1013904223.0 / kTwoPow32) * 0.9375);
  EXPECT_EQ(by_default.noise(5.5, 6.5), zero.noise(5.5, 6.5));
}

TEST(Noise, DetailChangesTheResult) {
  Noise noise(15u);
  const double four = noise.noise(2.3, 4.6);
  noise.noise_detail(1, 0.5);
  const double one = noise.noise(2.3, 4.6);
  noise.noise_detail(4, 0.25);
  const double low_falloff = noise.noise(2.3, 4.6);
  EXPECT_NE(four, one);
  EXPECT_NE(four, low_falloff);
  EXPECT_NE(one, low_falloff);
  noise.noise_detail(4, 0.5);
  EXPECT_EQ(noise.noise(2.3, 4.6), four);

  // Octave amplitudes at the origin: T0 * (0.5 + 0.5 f + 0.5 f^2) for 3 octaves.
  noise.noise_detail(3, 0.25);
  const double t0 = noise_table(15u)[0];
  EXPECT_EQ(noise.noise(0.0), t0 * 0.5 + t0 * 0.125 + t0 * 0.03125);
}

// The most octaves allowed: every one sampled, the sum still in [0, 1).
TEST(Noise, TakesUpToTheMostOctaves) {
  Noise noise(1u);
  noise.noise_detail(Noise::kMaxOctaves, 0.5);
  EXPECT_EQ(noise.octaves(), Noise::kMaxOctaves);
  const double value = noise.noise(0.3, 0.7, 0.1);
  EXPECT_GE(value, 0.0);
  EXPECT_LT(value, 1.0);
  noise.noise_detail(4, 0.5);
  EXPECT_NE(noise.noise(0.3, 0.7, 0.1), value);  // the octaves past 4 counted
}

TEST(Noise, RejectsInvalidInput) {
  Noise noise(1u);
  expect_error([&] { (void)noise.noise(kNan); }, "noise");
  expect_error([&] { (void)noise.noise(0.0, kInf); }, "must be finite");
  expect_error([&] { (void)noise.noise(0.0, 0.0, -kInf); }, "noise");
  expect_error([&] { noise.noise_detail(0, 0.5); }, "noise_detail");
  expect_error([&] { noise.noise_detail(-3, 0.5); }, "octaves");
  // A sample costs a pass an octave: a count from a file can't make it hang.
  expect_error([&] { noise.noise_detail(Noise::kMaxOctaves + 1, 0.5); }, "octaves");
  expect_error([&] { noise.noise_detail(std::numeric_limits<int>::max(), 0.5); }, "octaves");
  expect_error([&] { noise.noise_detail(4, kNan); }, "falloff");
  expect_error([&] { (void)calder::noise(kNan); }, "noise");
  // A rejected call leaves the settings alone.
  EXPECT_EQ(noise.noise(0.0), (1015568748.0 / kTwoPow32) * 0.9375);
}

// ------------------------------------------------ map_range, constrain ---

TEST(MapRange, UsesP5Grouping) {
  EXPECT_EQ(calder::map_range(5.0, 0.0, 10.0, 0.0, 100.0), 50.0);
  EXPECT_EQ(calder::map_range(0.0, 0.0, 10.0, 20.0, 30.0), 20.0);
  EXPECT_EQ(calder::map_range(10.0, 0.0, 10.0, 20.0, 30.0), 30.0);
  // Not clamped: extrapolates past the ranges.
  EXPECT_EQ(calder::map_range(15.0, 0.0, 10.0, 0.0, 100.0), 150.0);
  // Reversed output range.
  EXPECT_EQ(calder::map_range(2.5, 0.0, 10.0, 1.0, 0.0), 0.75);
  // The exact grouping decides the last bits: (v - a) / (b - a) * (d - c) + c.
  const double v = 0.1;
  const double a = 0.3;
  const double b = 0.7;
  const double c = 3.0;
  const double d = 11.0;
  EXPECT_EQ(calder::map_range(v, a, b, c, d), (v - a) / (b - a) * (d - c) + c);
  EXPECT_EQ(calder::map_range(1.0, 0.0, 3.0, 0.0, 1.0), 1.0 / 3.0);
}

TEST(MapRange, RejectsInputThatWouldGiveNan) {
  expect_error([] { (void)calder::map_range(1.0, 2.0, 2.0, 0.0, 1.0); }, "map_range");
  expect_error([] { (void)calder::map_range(kNan, 0.0, 1.0, 0.0, 1.0); }, "value");
  expect_error([] { (void)calder::map_range(0.5, 0.0, 1.0, 0.0, kInf); }, "stop2");
}

TEST(Constrain, ClampsLikeMaxOfMin) {
  EXPECT_EQ(calder::constrain(5.0, 0.0, 10.0), 5.0);
  EXPECT_EQ(calder::constrain(-5.0, 0.0, 10.0), 0.0);
  EXPECT_EQ(calder::constrain(15.0, 0.0, 10.0), 10.0);
  EXPECT_EQ(calder::constrain(0.0, 0.0, 10.0), 0.0);
  EXPECT_EQ(calder::constrain(10.0, 0.0, 10.0), 10.0);
  // low > high: max(min(n, high), low) is always low.
  EXPECT_EQ(calder::constrain(5.0, 10.0, 0.0), 10.0);
  EXPECT_EQ(calder::constrain(-5.0, 10.0, 0.0), 10.0);
  // Infinite bounds are allowed.
  EXPECT_EQ(calder::constrain(1e300, 0.0, std::numeric_limits<double>::infinity()), 1e300);
  EXPECT_EQ(calder::constrain(-kInf, -1.0, 1.0), -1.0);
  // Signed zeros as JavaScript's Math.min/Math.max treat them.
  EXPECT_TRUE(std::signbit(calder::constrain(-0.0, -0.0, 0.0)));
  EXPECT_FALSE(std::signbit(calder::constrain(-0.0, 0.0, 1.0)));
}

TEST(Constrain, RejectsNan) {
  expect_error([] { (void)calder::constrain(kNan, 0.0, 1.0); }, "constrain");
  expect_error([] { (void)calder::constrain(0.5, kNan, 1.0); }, "low");
  expect_error([] { (void)calder::constrain(0.5, 0.0, kNan); }, "high");
}

// ------------------------------------------------------ error helpers ---

TEST(ErrorDetail, FormatsNumbersInShortestRoundTripForm) {
  using calder::detail::format_number;
  EXPECT_EQ(format_number(-1.0), "-1");
  EXPECT_EQ(format_number(0.0), "0");
  EXPECT_EQ(format_number(0.1), "0.1");
  EXPECT_EQ(format_number(2.5), "2.5");
  EXPECT_EQ(format_number(100.0), "100");
  EXPECT_EQ(format_number(0.23645552527159452), "0.23645552527159452");
  EXPECT_EQ(format_number(kNan), "nan");
  EXPECT_EQ(format_number(-kNan), "nan");
  EXPECT_EQ(format_number(kInf), "inf");
  EXPECT_EQ(format_number(-kInf), "-inf");
  for (const double value : {1e-300, 1.0 / 3.0, 6.02214076e23, -123456.789, 5e-324}) {
    EXPECT_EQ(std::strtod(format_number(value).c_str(), nullptr), value) << format_number(value);
  }
}

TEST(ErrorDetail, MessagesNameTheFunctionTheArgumentAndTheValue) {
  using calder::detail::require_finite;
  using calder::detail::require_non_negative;
  using calder::detail::require_positive;
  auto message = [](auto f) -> std::string {
    try {
      f();
    } catch (const Error& e) {
      return e.what();
    }
    return "(no error)";
  };
  EXPECT_EQ(message([] { require_positive(-1.0, "World::add_body", "mass"); }),
            "World::add_body: mass must be > 0 (got -1)");
  EXPECT_EQ(message([] { require_positive(0.0, "World::step", "dt"); }),
            "World::step: dt must be > 0 (got 0)");
  EXPECT_EQ(message([] { require_positive(kNan, "World::step", "dt"); }),
            "World::step: dt must be finite (got nan)");
  EXPECT_EQ(message([] { require_finite(kInf, "f", "x"); }), "f: x must be finite (got inf)");
  EXPECT_EQ(message([] { require_non_negative(-0.5, "drag", "c"); }),
            "drag: c must be >= 0 (got -0.5)");
  EXPECT_EQ(message([] { require_non_negative(-kInf, "drag", "c"); }),
            "drag: c must be finite (got -inf)");
  // Valid values pass silently.
  EXPECT_EQ(message([] { require_finite(-3.0, "f", "x"); }), "(no error)");
  EXPECT_EQ(message([] { require_positive(1e-300, "f", "x"); }), "(no error)");
  EXPECT_EQ(message([] { require_non_negative(0.0, "f", "x"); }), "(no error)");
  // Error is an std::invalid_argument.
  EXPECT_THROW(require_finite(kNan, "f", "x"), std::invalid_argument);
}

}  // namespace
