// SPDX-License-Identifier: MIT
// The world's integrators: the book's semi-implicit Euler (simultaneous and
// sequential), velocity Verlet and classic RK4.
#include <algorithm>
#include <span>

#include "calder/world.hpp"
#include "integrate.hpp"

namespace calder {

void World::step_euler_simultaneous() {
  const std::size_t n = bodies_.x.size();
  const double dt = def_.dt;
  // bodies_.ax, bodies_.ay already hold the forces applied since the last step.
  accumulate_fields(context(bodies(), time_), 0, n, bodies_.ax, bodies_.ay);
  const bool before = def_.boundary.timing == BoundaryTiming::before_update;
  for (std::size_t i = 0; i < n; ++i) {
    if (before) boundary_one(i, def_.boundary);
    detail::book_update(bodies_.x[i], bodies_.y[i], bodies_.vx[i], bodies_.vy[i], bodies_.ax[i],
                        bodies_.ay[i], dt, def_.max_speed);
    if (!before) boundary_one(i, def_.boundary);
  }
}

void World::step_euler_sequential() {
  const std::size_t n = bodies_.x.size();
  const double dt = def_.dt;
  const bool before = def_.boundary.timing == BoundaryTiming::before_update;
  for (std::size_t i = 0; i < n; ++i) {
    // Forces on body i see the bodies before i already moved (example 2.9).
    accumulate_fields(context(bodies(), time_), i, i + 1, bodies_.ax, bodies_.ay);
    if (before) boundary_one(i, def_.boundary);
    detail::book_update(bodies_.x[i], bodies_.y[i], bodies_.vx[i], bodies_.vy[i], bodies_.ax[i],
                        bodies_.ay[i], dt, def_.max_speed);
    if (!before) boundary_one(i, def_.boundary);
  }
}

namespace {

// Stage state of a multi-stage step, carved out of one scratch vector.
struct Stage {
  std::span<double> x, y, vx, vy, ax, ay;
};

Stage carve(std::vector<double>& scratch, std::size_t n, std::size_t slot) {
  double* base = scratch.data() + slot * 6 * n;
  return {{base, n},         {base + n, n},     {base + 2 * n, n},
          {base + 3 * n, n}, {base + 4 * n, n}, {base + 5 * n, n}};
}

// Kick-drift-kick, from the accelerations at the current state (in s).
// Velocity-dependent forces at the end of the step see the predicted
// velocity v + a dt.
template <class Evaluate>
void velocity_verlet(BodyColumnsOf<std::vector<double>>& b, const Stage& s, double time, double dt,
                     const Evaluate& evaluate) {
  const std::size_t n = b.x.size();
  const double half = 0.5 * dt;
  for (std::size_t i = 0; i < n; ++i) {
    b.vx[i] += s.ax[i] * half;
    b.vy[i] += s.ay[i] * half;
    b.x[i] += b.vx[i] * dt;
    b.y[i] += b.vy[i] * dt;
    s.x[i] = b.x[i];
    s.y[i] = b.y[i];
    s.vx[i] = b.vx[i] + s.ax[i] * half;
    s.vy[i] = b.vy[i] + s.ay[i] * half;
  }
  evaluate(time + dt);
  for (std::size_t i = 0; i < n; ++i) {
    b.vx[i] += s.ax[i] * half;
    b.vy[i] += s.ay[i] * half;
  }
}

// Classic RK4 on (x, v): k1 at t (the accelerations in s), k2 and k3 at
// t + dt/2, k4 at t + dt, weights 1, 2, 2, 1 over 6.
template <class Evaluate>
void rk4(BodyColumnsOf<std::vector<double>>& b, const Stage& s, const Stage& sum, double time,
         double dt, const Evaluate& evaluate) {
  const std::size_t n = b.x.size();
  const double half = 0.5 * dt;
  for (std::size_t i = 0; i < n; ++i) {  // k1: velocity v, acceleration s.a
    sum.x[i] = b.vx[i];
    sum.y[i] = b.vy[i];
    sum.vx[i] = s.ax[i];
    sum.vy[i] = s.ay[i];
  }
  const double stage_dt[3] = {half, half, dt};
  const double weight[3] = {2.0, 2.0, 1.0};
  for (int k = 0; k < 3; ++k) {
    // The next stage's state from the previous stage's derivatives (s.v, s.a).
    for (std::size_t i = 0; i < n; ++i) {
      const double vx = s.vx[i];
      const double vy = s.vy[i];
      s.x[i] = b.x[i] + vx * stage_dt[k];
      s.y[i] = b.y[i] + vy * stage_dt[k];
      s.vx[i] = b.vx[i] + s.ax[i] * stage_dt[k];
      s.vy[i] = b.vy[i] + s.ay[i] * stage_dt[k];
    }
    evaluate(time + stage_dt[k]);
    for (std::size_t i = 0; i < n; ++i) {
      sum.x[i] += weight[k] * s.vx[i];
      sum.y[i] += weight[k] * s.vy[i];
      sum.vx[i] += weight[k] * s.ax[i];
      sum.vy[i] += weight[k] * s.ay[i];
    }
  }
  const double sixth = dt / 6.0;
  for (std::size_t i = 0; i < n; ++i) {
    b.x[i] += sum.x[i] * sixth;
    b.y[i] += sum.y[i] * sixth;
    b.vx[i] += sum.vx[i] * sixth;
    b.vy[i] += sum.vy[i] * sixth;
  }
}

// Yoshida (1990, Phys. Lett. A 150, 262): velocity Verlet steps of these
// fractions of dt compose to 4th order (w1, w0, w1 with w1 = 1 / (2 - 2^(1/3)),
// w0 = 1 - 2 w1) and to 6th order (his solution A: w3, w2, w1, w0, w1, w2, w3,
// w0 = 1 - 2 (w1 + w2 + w3)).
constexpr double kYoshida4[3] = {1.3512071919596576, -1.7024143839193153, 1.3512071919596576};
constexpr double kYoshida6[7] = {0.784513610477560, 0.235573213359357, -1.17767998417887,
                                 1.315186320683906, -1.17767998417887, 0.235573213359357,
                                 0.784513610477560};

}  // namespace

void World::step_multistage() {
  const std::size_t n = bodies_.x.size();
  const double dt = def_.dt;
  const Boundary& boundary = def_.boundary;
  if (boundary.timing == BoundaryTiming::before_update) {
    for (std::size_t i = 0; i < n; ++i) boundary_one(i, boundary);
  }
  scratch_.assign(6 * n * 3, 0.0);
  Stage s = carve(scratch_, n, 0);    // stage positions, velocities, accelerations
  Stage sum = carve(scratch_, n, 1);  // RK4: weighted sums of velocities (x, y) and accelerations
  Stage applied = carve(scratch_, n, 2);  // forces applied by the user, held for every stage
  std::copy(bodies_.ax.begin(), bodies_.ax.end(), applied.ax.begin());
  std::copy(bodies_.ay.begin(), bodies_.ay.end(), applied.ay.begin());

  // Acceleration at the stage state s (positions and velocities) and time t into s.ax, s.ay.
  const auto evaluate = [&](double t) {
    std::copy(applied.ax.begin(), applied.ax.end(), s.ax.begin());
    std::copy(applied.ay.begin(), applied.ay.end(), s.ay.begin());
    BodyView view = bodies();  // the stage's positions and velocities, the bodies' properties
    view.x = s.x;
    view.y = s.y;
    view.vx = s.vx;
    view.vy = s.vy;
    accumulate_fields(context(view, t), 0, n, s.ax, s.ay);
  };
  const auto load_current = [&] {
    std::copy(bodies_.x.begin(), bodies_.x.end(), s.x.begin());
    std::copy(bodies_.y.begin(), bodies_.y.end(), s.y.begin());
    std::copy(bodies_.vx.begin(), bodies_.vx.end(), s.vx.begin());
    std::copy(bodies_.vy.begin(), bodies_.vy.end(), s.vy.begin());
  };

  load_current();
  evaluate(time_);
  if (def_.integrator == Integrator::velocity_verlet) {
    velocity_verlet(bodies_, s, time_, dt, evaluate);
  } else if (def_.integrator == Integrator::yoshida4 || def_.integrator == Integrator::yoshida6) {
    const std::span<const double> weights = def_.integrator == Integrator::yoshida4
                                                ? std::span<const double>(kYoshida4)
                                                : std::span<const double>(kYoshida6);
    double t = time_;
    // Each substep starts from the accelerations the last one ended with.
    for (const double w : weights) {
      velocity_verlet(bodies_, s, t, w * dt, evaluate);
      t += w * dt;
    }
  } else {
    rk4(bodies_, s, sum, time_, dt, evaluate);
  }
  std::fill(bodies_.ax.begin(), bodies_.ax.end(), 0.0);
  std::fill(bodies_.ay.begin(), bodies_.ay.end(), 0.0);
  if (boundary.timing == BoundaryTiming::after_update) {
    for (std::size_t i = 0; i < n; ++i) boundary_one(i, boundary);
  }
}

}  // namespace calder
