// SPDX-License-Identifier: MIT
// The plain loop of soa_rain.hpp. Compiled twice (bench/peers/CMakeLists.txt):
// SOA_RAIN_NAME names each copy's functions; -O3 -ffast-math and the copy's
// instruction set come from the build, nothing else is tuned.
#include <cmath>
#include <cstddef>

#include "peers/soa_rain.hpp"

#ifndef SOA_RAIN_NAME
#error "SOA_RAIN_NAME must name this copy (bench/peers/CMakeLists.txt)"
#endif

namespace calder::peers {

namespace {

// One step of every body (restrict-qualified parameters: the arrays don't
// overlap, which is what lets the compiler vectorise the loop).
template <class R>
void rain_step(std::size_t n, R* __restrict x, R* __restrict y, R* __restrict vx, R* __restrict vy,
               const R* __restrict m, const R* __restrict r, R g, R c, R e, R dt, R w, R h) {
  for (std::size_t i = 0; i < n; ++i) {
    // Gravity scaled by mass, over the mass: g. Drag: -c |v| v / m.
    const R speed = std::sqrt(vx[i] * vx[i] + vy[i] * vy[i]);
    const R k = c * speed / m[i];
    const R nvx = vx[i] - k * vx[i] * dt;
    const R nvy = vy[i] + (g - k * vy[i]) * dt;
    const R nx = x[i] + nvx * dt;
    const R ny = y[i] + nvy * dt;
    // Bounce on the radius: right before left, the floor; clamp, reverse.
    const R ri = r[i];
    const R right = w - ri;
    const R floor = h - ri;
    x[i] = nx > right ? right : (nx < ri ? ri : nx);
    y[i] = ny > floor ? floor : ny;
    vx[i] = (nx > right || nx < ri) ? -e * nvx : nvx;
    vy[i] = ny > floor ? -e * nvy : nvy;
  }
}

template <class R>
void rain_steps(SoaRainState<R>& s, std::size_t first, std::size_t count, int steps) {
  for (int step = 0; step < steps; ++step) {
    rain_step(count, s.x.data() + first, s.y.data() + first, s.vx.data() + first,
              s.vy.data() + first, s.mass.data() + first, s.radius.data() + first, s.gravity,
              s.drag, s.restitution, s.dt, s.width, s.height);
  }
}

}  // namespace

void SOA_RAIN_NAME(SoaRainState<float>& state, std::size_t first, std::size_t count, int steps) {
  rain_steps(state, first, count, steps);
}
void SOA_RAIN_NAME(SoaRainState<double>& state, std::size_t first, std::size_t count, int steps) {
  rain_steps(state, first, count, steps);
}

}  // namespace calder::peers
