// Internal: the book's update for one body, shared by World::update and the
// whole-world semi-implicit Euler step so that both give the same bits.
#pragma once

namespace calder::detail {

// velocity += acceleration * dt; position += velocity * dt; acceleration = 0.
// With dt = 1 the products are exact, so this is p5's vel.add(acc); pos.add(vel).
inline void kick_drift(double& x, double& y, double& vx, double& vy, double& ax, double& ay,
                       double dt) {
  vx += ax * dt;
  vy += ay * dt;
  x += vx * dt;
  y += vy * dt;
  ax = 0.0;
  ay = 0.0;
}

}  // namespace calder::detail
