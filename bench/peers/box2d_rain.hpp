// SPDX-License-Identifier: MIT
// Box2D 2.4 running calder's "rain" scene, a benchmark peer for calder's mover
// kernels. Each frame, per body: gravity scaled by mass, quadratic drag
// everywhere, semi-implicit Euler (Box2D's island integrator), then a bounce on
// the radius off the left, right and bottom walls; no body-body collisions.
//
// The public interface is in calder units (pixels, frames, y down); the Box2D
// world behind it runs in metres and seconds (see box2d_rain.cpp), so no Box2D
// header leaks into users of this one.
#pragma once

#include <cstddef>
#include <memory>
#include <span>

namespace calder::peers {

struct RainParams {
  double width = 640.0, height = 240.0;
  double gravity = 0.1;      // px/frame^2, downward (+y), scaled by mass
  double drag = 0.01;        // quadratic drag coefficient c: F = -c |v| v
  double restitution = 0.9;  // bounce off left, right, bottom walls, on the radius
};

// circles: a b2CircleShape fixture each, in Box2D's broad phase, with body-body
// collisions filtered out (one negative collision group); points: bodies with
// no fixture, so no broad phase at all.
enum class Box2dBodies { circles, points };

class Box2dRain {
 public:
  // Mirrors bodies given in calder units (equal-size spans; mass > 0, radius >= 0).
  // Throws std::invalid_argument otherwise.
  Box2dRain(std::span<const double> x, std::span<const double> y, std::span<const double> vx,
            std::span<const double> vy, std::span<const double> mass,
            std::span<const double> radius, const RainParams& params, Box2dBodies kind);
  ~Box2dRain();
  Box2dRain(Box2dRain&&) noexcept;
  Box2dRain& operator=(Box2dRain&&) noexcept;
  Box2dRain(const Box2dRain&) = delete;
  Box2dRain& operator=(const Box2dRain&) = delete;

  // One frame: forces per body (ApplyForceToCenter), b2World::Step, then the bounce per body.
  void step();

  std::size_t size() const;
  // Back in calder units (px, px/frame).
  double x(std::size_t i) const;
  double y(std::size_t i) const;
  double vx(std::size_t i) const;
  double vy(std::size_t i) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace calder::peers
