// SPDX-License-Identifier: MIT
// Tests of the Box2D benchmark peer (bench/peers/box2d_rain.hpp): its run of
// the rain scene must be the same motion as calder's rules, so that timing it
// against calder's kernels compares like with like. The truth here is
// independent of both: the closed form of free fall under semi-implicit Euler,
// and a plain double-precision loop of the rain rules written from the spec.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "peers/box2d_rain.hpp"

namespace {

using calder::peers::Box2dBodies;
using calder::peers::Box2dRain;
using calder::peers::RainParams;

// Bodies in calder units, as a structure of arrays (the peer's input).
struct Bodies {
  std::vector<double> x, y, vx, vy, mass, radius;

  void add(double x0, double y0, double vx0, double vy0, double m, double r) {
    x.push_back(x0);
    y.push_back(y0);
    vx.push_back(vx0);
    vy.push_back(vy0);
    mass.push_back(m);
    radius.push_back(r);
  }
  std::size_t size() const { return x.size(); }
};

Box2dRain make_peer(const Bodies& b, const RainParams& params, Box2dBodies kind) {
  return Box2dRain(b.x, b.y, b.vx, b.vy, b.mass, b.radius, params, kind);
}

// One frame of the rain rules, in double, written from the spec: forces
// (gravity scaled by mass, quadratic drag), acceleration F/m, semi-implicit
// Euler with dt = 1 frame, then the bounce on the radius off the left, right
// and bottom walls. Returns how many bounces there were.
int reference_step(Bodies& b, const RainParams& p) {
  int bounces = 0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    const double m = b.mass[i];
    const double speed = std::hypot(b.vx[i], b.vy[i]);
    const double fx = -p.drag * speed * b.vx[i];
    const double fy = p.gravity * m - p.drag * speed * b.vy[i];
    b.vx[i] += fx / m;
    b.vy[i] += fy / m;
    b.x[i] += b.vx[i];
    b.y[i] += b.vy[i];
    const double r = b.radius[i];
    if (b.x[i] > p.width - r) {
      b.x[i] = p.width - r;
      b.vx[i] *= -p.restitution;
      ++bounces;
    } else if (b.x[i] < r) {
      b.x[i] = r;
      b.vx[i] *= -p.restitution;
      ++bounces;
    }
    if (b.y[i] > p.height - r) {
      b.y[i] = p.height - r;
      b.vy[i] *= -p.restitution;
      ++bounces;
    }
  }
  return bounces;
}

// Box2D computes in float: positions of up to 6.4 m carry an ulp of 4.8e-7 m
// = 4.8e-5 px, and the unit conversions (0.01 m/px, 0.6, 36) are themselves
// rounded to float, a relative 6e-8 each. Measured over the 60 frames below:
// free fall within 3.5e-6 of the fall (6.5e-5 px), drag within 4.9e-5 px and
// a relative 5e-6 in velocity. So 1e-4 relative (at least 1e-3 px absolute)
// bounds float rounding with margin and still fails on any error of the
// rules (a missing drag, a wrong unit factor or a frame off changes the
// displacement by percents).
constexpr double kRelative = 1e-4;
constexpr double kAbsolute = 1e-3;

double tolerance(double displacement) {
  return std::max(kAbsolute, kRelative * std::abs(displacement));
}

TEST(Box2dPeer, FreeFallMatchesTheDiscreteClosedForm) {
  // No drag: semi-implicit Euler from rest gives v_k = g k and
  // y_k = y_0 + g (1 + 2 + ... + k) = y_0 + g k (k + 1) / 2.
  RainParams params;
  params.drag = 0.0;
  Bodies b;
  b.add(320.0, 10.0, 0.0, 0.0, 2.0, 4.0);
  Box2dRain peer = make_peer(b, params, Box2dBodies::circles);
  ASSERT_EQ(peer.size(), 1u);
  // 60 frames fall 183 px: from y = 10 to 193, above the floor at 240 - 4.
  for (int k = 1; k <= 60; ++k) {
    peer.step();
    const double fall = params.gravity * k * (k + 1) / 2.0;
    ASSERT_NEAR(peer.y(0), 10.0 + fall, tolerance(fall)) << "frame " << k;
    ASSERT_NEAR(peer.vy(0), params.gravity * k, tolerance(params.gravity * k)) << "frame " << k;
    ASSERT_NEAR(peer.x(0), 320.0, kAbsolute) << "frame " << k;
    ASSERT_EQ(peer.vx(0), 0.0) << "frame " << k;
  }
}

TEST(Box2dPeer, DragMatchesThePlainLoopAwayFromTheWalls) {
  // Drag couples x and y through |v|: a body thrown sideways and up, heavy
  // and light, away from every wall for these 60 frames.
  const RainParams params;
  Bodies b;
  b.add(100.0, 120.0, 4.0, -3.0, 0.5, 1.0);
  b.add(300.0, 50.0, -6.0, 0.0, 3.0, 6.0);
  b.add(500.0, 20.0, 0.0, 0.0, 1.0, 2.0);
  for (Box2dBodies kind : {Box2dBodies::circles, Box2dBodies::points}) {
    Box2dRain peer = make_peer(b, params, kind);
    Bodies ref = b;
    for (int k = 1; k <= 60; ++k) {
      peer.step();
      reference_step(ref, params);
      for (std::size_t i = 0; i < b.size(); ++i) {
        // The rule is what is under test: no wall may have been hit.
        ASSERT_GT(ref.x[i], ref.radius[i]);
        ASSERT_LT(ref.x[i], params.width - ref.radius[i]);
        ASSERT_LT(ref.y[i], params.height - ref.radius[i]);
        ASSERT_NEAR(peer.x(i), ref.x[i], tolerance(ref.x[i] - b.x[i])) << i << " frame " << k;
        ASSERT_NEAR(peer.y(i), ref.y[i], tolerance(ref.y[i] - b.y[i])) << i << " frame " << k;
        ASSERT_NEAR(peer.vx(i), ref.vx[i], tolerance(ref.vx[i])) << i << " frame " << k;
        ASSERT_NEAR(peer.vy(i), ref.vy[i], tolerance(ref.vy[i])) << i << " frame " << k;
      }
    }
  }
  // Sanity of the reference itself: drag slows a body thrown at 6 px/frame.
  Bodies ref = b;
  reference_step(ref, params);
  EXPECT_LT(std::abs(ref.vx[1]), 6.0);
}

// Bodies over the upper half of the canvas, rain-like: mass in [0.5, 3],
// radius 2 px per unit of mass (bench_run's rain), velocities up to 3 px/frame.
Bodies random_rain(std::size_t n, unsigned seed, const RainParams& params) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Bodies b;
  for (std::size_t i = 0; i < n; ++i) {
    // One draw per statement: the order of evaluation of arguments is unspecified.
    const double m = 0.5 + 2.5 * unit(rng);
    const double r = 2.0 * m;
    const double x = r + (params.width - 2.0 * r) * unit(rng);
    const double y = params.height / 2.0 * unit(rng);
    const double vx = -3.0 + 6.0 * unit(rng);
    const double vy = -3.0 + 6.0 * unit(rng);
    b.add(x, y, vx, vy, m, r);
  }
  return b;
}

TEST(Box2dPeer, RandomRainFollowsThePlainLoopWithBounces) {
  // Float rounding is harmless in flight (the drag test above: < 1e-4 px)
  // but a bounce is a threshold: a body resting on the floor makes ever
  // smaller bounces, and when float rounding puts a step on the other side of
  // y = H - r than the double loop does, that body bounces a frame early or
  // late and its path shifts by up to about its speed (1 + e) times, a few px
  // at the rain's terminal speeds (~5.5 px/frame for m = 3). Measured over
  // 300 seeds of this setup (200 bodies, 300 frames): at most 2 bodies per
  // seed ever differ by more than 0.01 px (in 18 seeds of 300), the worst by
  // 4.4 px; every other body stays within 1.5e-3 px. Hence: all but 2% of
  // the bodies within 5e-3 px, and all within 10 px. A wrong rule fails both
  // (restitution 1 instead of 0.9 puts most bodies 10 to 40 px off).
  const RainParams params;
  const Bodies start = random_rain(200, 7, params);
  for (Box2dBodies kind : {Box2dBodies::circles, Box2dBodies::points}) {
    Box2dRain peer = make_peer(start, params, kind);
    Bodies ref = start;
    std::vector<double> worst(start.size(), 0.0);  // per body, over all frames
    int bounces = 0;
    for (int k = 1; k <= 300; ++k) {
      peer.step();
      bounces += reference_step(ref, params);
      for (std::size_t i = 0; i < start.size(); ++i) {
        worst[i] =
            std::max({worst[i], std::abs(peer.x(i) - ref.x[i]), std::abs(peer.y(i) - ref.y[i])});
        // Inside the walls, up to the float rounding of the wall itself
        // ((W - r) * 0.01 m as a float is within 3e-5 px of W - r).
        const double r = start.radius[i];
        ASSERT_GE(peer.x(i), r - kAbsolute) << i << " frame " << k;
        ASSERT_LE(peer.x(i), params.width - r + kAbsolute) << i << " frame " << k;
        ASSERT_LE(peer.y(i), params.height - r + kAbsolute) << i << " frame " << k;
      }
    }
    // The scene does exercise the bounce: bodies land on the floor and bounce there.
    EXPECT_GT(bounces, 1000);
    const std::size_t diverged = static_cast<std::size_t>(
        std::count_if(worst.begin(), worst.end(), [](double d) { return d > 5e-3; }));
    const double max_diff = *std::max_element(worst.begin(), worst.end());
    const char* name = kind == Box2dBodies::circles ? "circles" : "points";
    RecordProperty(std::string("max_diff_px_") + name, std::to_string(max_diff));
    RecordProperty(std::string("diverged_bodies_") + name, std::to_string(diverged));
    EXPECT_LE(diverged, start.size() / 50) << name;
    EXPECT_LT(max_diff, 10.0) << name;
  }
}

TEST(Box2dPeer, CirclesNeverCollideAndMoveLikePoints) {
  // 50 circles of radius 10 px packed within 2 px of one point: any contact
  // would push them apart by up to 20 px. Filtered, they move exactly like
  // bodies without fixtures: the same float operations, bit for bit.
  const RainParams params;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> jitter(-1.0, 1.0);
  Bodies b;
  for (int i = 0; i < 50; ++i) {
    b.add(320.0 + jitter(rng), 100.0 + jitter(rng), jitter(rng), jitter(rng),
          1.0 + 0.5 * (jitter(rng) + 1.0), 10.0);
  }
  // Two twins: same place, same velocity, same mass. Colliding, they would separate.
  b.add(200.0, 60.0, 0.5, 0.0, 2.0, 10.0);
  b.add(200.0, 60.0, 0.5, 0.0, 2.0, 10.0);

  Box2dRain circles = make_peer(b, params, Box2dBodies::circles);
  Box2dRain points = make_peer(b, params, Box2dBodies::points);
  for (int k = 1; k <= 200; ++k) {
    circles.step();
    points.step();
    for (std::size_t i = 0; i < b.size(); ++i) {
      ASSERT_EQ(circles.x(i), points.x(i)) << i << " frame " << k;
      ASSERT_EQ(circles.y(i), points.y(i)) << i << " frame " << k;
      ASSERT_EQ(circles.vx(i), points.vx(i)) << i << " frame " << k;
      ASSERT_EQ(circles.vy(i), points.vy(i)) << i << " frame " << k;
    }
    const std::size_t a = b.size() - 2;
    ASSERT_EQ(circles.x(a), circles.x(a + 1)) << "frame " << k;
    ASSERT_EQ(circles.y(a), circles.y(a + 1)) << "frame " << k;
  }
}

TEST(Box2dPeer, RejectsMismatchedSpansAndBadMasses) {
  Bodies b;
  b.add(10.0, 10.0, 0.0, 0.0, 1.0, 2.0);
  std::vector<double> two = {1.0, 2.0};
  EXPECT_THROW(Box2dRain(b.x, b.y, b.vx, b.vy, two, b.radius, {}, Box2dBodies::points),
               std::invalid_argument);
  b.mass[0] = 0.0;
  EXPECT_THROW(make_peer(b, {}, Box2dBodies::circles), std::invalid_argument);
}

}  // namespace
