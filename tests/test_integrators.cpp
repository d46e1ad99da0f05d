// SPDX-License-Identifier: MIT
// Tests of the three integrators against exact solutions: their order of
// convergence on a Kepler orbit (exact position from Kepler's equation) and
// under quadratic drag (closed form), their long-run energy behaviour, and
// the exact cases (no force, one step of constant force).
//
// Expected orders and exact results are the textbook properties of the
// methods, derived in the comments; no expected number comes from calder.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <ostream>
#include <string_view>
#include <vector>

#include "calder/diagnostics.hpp"
#include "calder/error.hpp"
#include "calder/fields.hpp"
#include "calder/forces.hpp"
#include "calder/vec2.hpp"
#include "calder/world.hpp"
#include "support/test_support.hpp"

namespace {

using calder::AttractionLaw;
using calder::BodyId;
using calder::Integrator;
using calder::Vec2;
using calder::World;
using calder::WorldDef;

constexpr double kPi = 3.141592653589793;

// Least-squares slope of log(error) against log(dt): the observed order p of
// error ~ C dt^p.
double fitted_order(const std::vector<double>& dts, const std::vector<double>& errors) {
  const std::size_t n = dts.size();
  double sx = 0.0;
  double sy = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    sx += std::log(dts[i]);
    sy += std::log(errors[i]);
  }
  const double mx = sx / static_cast<double>(n);
  const double my = sy / static_cast<double>(n);
  double sxy = 0.0;
  double sxx = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double dx = std::log(dts[i]) - mx;
    sxy += dx * (std::log(errors[i]) - my);
    sxx += dx * dx;
  }
  return sxy / sxx;
}

// Checks the fitted order and, to show the dt range is in the asymptotic
// regime, each local order log2(e(dt) / e(dt / 2)) (dt halves each time).
void expect_order(const std::vector<double>& dts, const std::vector<double>& errors, double lo,
                  double hi, std::string_view what) {
  const double p = fitted_order(dts, errors);
  EXPECT_GE(p, lo) << what;
  EXPECT_LE(p, hi) << what;
  for (std::size_t i = 1; i < errors.size(); ++i) {
    const double local = std::log2(errors[i - 1] / errors[i]);
    EXPECT_GE(local, lo) << what << ", local order between dt " << dts[i - 1] << " and " << dts[i];
    EXPECT_LE(local, hi) << what << ", local order between dt " << dts[i - 1] << " and " << dts[i];
  }
}

// ======================================================================== Kepler ===
//
// A body around a fixed point mass with mu = G M, on an ellipse of semi-major
// axis a and eccentricity e with the focus at the origin and periapsis on +x.
// Mean motion n = sqrt(mu / a^3); at time t the mean anomaly is M = n t, the
// eccentric anomaly E solves Kepler's equation E - e sin E = M (Newton:
// E <- E - (E - e sin E - M) / (1 - e cos E)), and
//   x = a (cos E - e),  y = b sin E,  b = a sqrt(1 - e^2),
//   dE/dt = n / (1 - e cos E),  vx = -a sin E dE/dt,  vy = b cos E dE/dt.

struct KeplerOrbit {
  double mu = 1.0;
  double a = 1.0;
  double e = 0.5;

  [[nodiscard]] double mean_motion() const { return std::sqrt(mu / (a * a * a)); }
  [[nodiscard]] double period() const { return 2.0 * kPi / mean_motion(); }

  [[nodiscard]] double eccentric_anomaly(double t) const {
    const double mean = mean_motion() * t;
    double ecc = mean;
    for (int k = 0; k < 100; ++k) {
      const double step = (ecc - e * std::sin(ecc) - mean) / (1.0 - e * std::cos(ecc));
      ecc -= step;
      if (std::abs(step) < 1e-15) break;
    }
    return ecc;
  }
  [[nodiscard]] Vec2 position(double t) const {
    const double ecc = eccentric_anomaly(t);
    return {a * (std::cos(ecc) - e), a * std::sqrt(1.0 - e * e) * std::sin(ecc)};
  }
  [[nodiscard]] Vec2 velocity(double t) const {
    const double ecc = eccentric_anomaly(t);
    const double rate = mean_motion() / (1.0 - e * std::cos(ecc));
    return {-a * std::sin(ecc) * rate, a * std::sqrt(1.0 - e * e) * std::cos(ecc) * rate};
  }
};

// A world with the fixed attractor (G = 1, M = mu) at the origin and the body
// at periapsis (t = 0).
World kepler_world(const KeplerOrbit& orbit, double dt, Integrator integrator) {
  World world(WorldDef{.dt = dt, .integrator = integrator});
  world.add(calder::Attractor{
      .position = {0.0, 0.0}, .mass = orbit.mu, .law = AttractionLaw::newtonian(1.0)});
  world.add_body({.position = orbit.position(0.0), .velocity = orbit.velocity(0.0), .mass = 1.0});
  return world;
}

TEST(IntegratorsKepler, ExactSolutionSatisfiesKeplersLaws) {
  // Guards the reference itself: energy -mu / (2 a) and angular momentum
  // sqrt(mu a (1 - e^2)) per unit mass are constant along the exact orbit.
  const KeplerOrbit orbit;
  for (const double t : {0.0, 0.7, 2.0, 3.1, 5.5, 8.0}) {
    const Vec2 p = orbit.position(t);
    const Vec2 v = orbit.velocity(t);
    EXPECT_NEAR(0.5 * v.mag_sq() - orbit.mu / p.mag(), -orbit.mu / (2.0 * orbit.a), 1e-14);
    EXPECT_NEAR(p.cross(v), std::sqrt(orbit.mu * orbit.a * (1.0 - orbit.e * orbit.e)), 1e-14);
  }
  EXPECT_NEAR(orbit.position(orbit.period()).x, orbit.a * (1.0 - orbit.e), 1e-14);
}

TEST(IntegratorsKepler, ConvergenceOrders) {
  // Global error at fixed T of a method of order p: C dt^p. Semi-implicit
  // Euler p = 1, velocity Verlet p = 2, RK4 p = 4. T = 8 (1.27 periods, past
  // the second periapsis passage); dt = T / n with n a power of two, so the
  // world's clock lands exactly on T. The ranges of n are where the local
  // orders have settled (checked by expect_order) and RK4 stays well above
  // rounding (its smallest error is ~2e-10).
  const KeplerOrbit orbit;
  const double T = 8.0;
  const Vec2 exact = orbit.position(T);
  const struct {
    Integrator integrator;
    int n0;
    double lo;
    double hi;
  } cases[] = {
      {Integrator::semi_implicit_euler, 4096, 0.8, 1.2},
      {Integrator::velocity_verlet, 512, 1.8, 2.2},
      {Integrator::rk4, 512, 3.6, 4.4},
      {Integrator::yoshida4, 512, 3.6, 4.4},
      {Integrator::yoshida6, 128, 5.4, 6.6},
  };
  for (const auto& c : cases) {
    std::vector<double> dts;
    std::vector<double> errors;
    for (int n = c.n0; n <= 8 * c.n0; n *= 2) {
      World world = kepler_world(orbit, T / n, c.integrator);
      world.step(n);
      ASSERT_EQ(world.time(), T);
      dts.push_back(T / n);
      errors.push_back((world.position(world.body(0)) - exact).mag());
    }
    expect_order(dts, errors, c.lo, c.hi, calder::integrator_name(c.integrator));
  }
}

// ================================================================ energy, long run ===
//
// For a position-dependent force both semi-implicit Euler and velocity Verlet
// are symplectic: each exactly conserves a "shadow" energy within O(dt^p) of
// the true one, so the true energy error oscillates but stays bounded for
// exponentially long times, with amplitude O(dt) for Euler and O(dt^2) for
// Verlet. RK4 is not symplectic: its energy error is O(dt^4) per orbit but
// accumulates, growing linearly with time (a secular drift).
//
// Orbit: e = 0.3, 100 steps per period, 1000 periods.

struct EnergyRun {
  double max_first = 0.0;    // max |E - E0| / |E0| over the first 100 orbits
  double max_last = 0.0;     // same over the last 100 orbits
  std::vector<double> ends;  // (E - E0) / |E0| at the end of orbits 100, 200, ..., 1000
};

EnergyRun energy_run(Integrator integrator, bool every_step) {
  const KeplerOrbit orbit{.mu = 1.0, .a = 1.0, .e = 0.3};
  const int per_orbit = 100;
  const int orbits = 1000;
  World world = kepler_world(orbit, orbit.period() / per_orbit, integrator);
  const double e0 = calder::total_energy(world);
  // Guards against a mistaken potential: E0 = -mu m / (2 a).
  EXPECT_NEAR(e0, -0.5, 1e-14);
  EnergyRun run;
  for (int k = 1; k <= orbits; ++k) {
    double max_orbit = 0.0;
    if (every_step) {
      for (int s = 0; s < per_orbit; ++s) {
        world.step();
        max_orbit = std::max(max_orbit, std::abs(calder::total_energy(world) - e0) / -e0);
      }
    } else {
      world.step(per_orbit);
    }
    if (k <= 100) run.max_first = std::max(run.max_first, max_orbit);
    if (k > orbits - 100) run.max_last = std::max(run.max_last, max_orbit);
    if (k % 100 == 0) run.ends.push_back((calder::total_energy(world) - e0) / -e0);
  }
  return run;
}

TEST(IntegratorsEnergy, SymplecticMethodsStayBoundedRk4Drifts) {
  const EnergyRun verlet = energy_run(Integrator::velocity_verlet, true);
  const EnergyRun euler = energy_run(Integrator::semi_implicit_euler, true);
  const EnergyRun rk4 = energy_run(Integrator::rk4, false);

  // Velocity Verlet: small and bounded, no growth from the first 100 orbits
  // to the last 100.
  EXPECT_LT(verlet.max_first, 5e-3);
  EXPECT_LT(verlet.max_last, 2.0 * verlet.max_first);
  EXPECT_GT(verlet.max_last, 0.5 * verlet.max_first);

  // Semi-implicit Euler is symplectic too: bounded as well, no secular drift,
  // but first order, so far larger than Verlet's at the same dt.
  EXPECT_LT(euler.max_last, 2.0 * euler.max_first);
  EXPECT_GT(euler.max_last, 0.5 * euler.max_first);
  EXPECT_LT(euler.max_first, 0.2);
  EXPECT_LT(5.0 * verlet.max_first, euler.max_first);

  // RK4: the error after 100 k orbits is k times the error after 100 orbits
  // (linear drift), always of one sign.
  ASSERT_EQ(rk4.ends.size(), 10U);
  EXPECT_GT(std::abs(rk4.ends[0]), 1e-6) << "RK4 drift too small to measure the trend";
  for (std::size_t k = 1; k < rk4.ends.size(); ++k) {
    const double ratio = rk4.ends[k] / rk4.ends[0];
    EXPECT_NEAR(ratio, static_cast<double>(k + 1), 0.1 * static_cast<double>(k + 1))
        << "after " << 100 * (k + 1) << " orbits";
  }
}

// ============================================================ velocity-dependent ===
//
// 1D quadratic drag, no other force: m dv/dt = -c v^2 (v > 0), so
//   v(t) = v0 / (1 + c v0 t / m),  x(t) = x0 + (m / c) ln(1 + c v0 t / m).
// Velocity-dependent forces exercise the stages' velocities: RK4 must stay
// fourth order (in v and x), Verlet (whose end-of-step force sees the
// predicted velocity v + a dt: Heun's method in v) second order in v, Euler
// first order.

TEST(IntegratorsDrag, ConvergenceOrdersAgainstClosedForm) {
  const double c = 0.1;
  const double m = 1.0;
  const double v0 = 10.0;
  const double T = 4.0;
  const double k = c * v0 / m;  // 1 / time scale
  const double v_exact = v0 / (1.0 + k * T);
  const double x_exact = m / c * std::log(1.0 + k * T);
  const struct {
    Integrator integrator;
    int n0;
    double lo;
    double hi;
  } cases[] = {
      {Integrator::semi_implicit_euler, 128, 0.8, 1.2},
      {Integrator::velocity_verlet, 64, 1.8, 2.2},
      {Integrator::rk4, 64, 3.6, 4.4},
  };
  for (const auto& cs : cases) {
    std::vector<double> dts;
    std::vector<double> v_errors;
    std::vector<double> x_errors;
    for (int n = cs.n0; n <= 8 * cs.n0; n *= 2) {
      World world(WorldDef{.dt = T / n, .integrator = cs.integrator});
      world.add(calder::Drag{.c = c});
      const BodyId body = world.add_body({.velocity = {v0, 0.0}, .mass = m});
      world.step(n);
      EXPECT_EQ(world.velocity(body).y, 0.0);
      dts.push_back(T / n);
      v_errors.push_back(std::abs(world.velocity(body).x - v_exact));
      x_errors.push_back(std::abs(world.position(body).x - x_exact));
    }
    expect_order(dts, v_errors, cs.lo, cs.hi, calder::integrator_name(cs.integrator));
    if (cs.integrator == Integrator::rk4) expect_order(dts, x_errors, cs.lo, cs.hi, "rk4 position");
  }
}

// ================================================================== exact cases ===

TEST(IntegratorsExact, NoForceMeansStraightLineAtConstantVelocity) {
  // Newton's first law: with no force the velocity never changes (bit for
  // bit: every integrator adds zero to it) and the position advances by v dt
  // each step. With dyadic v, dt and x0 the positions x0 + k v dt are exact.
  for (const Integrator integrator :
       {Integrator::semi_implicit_euler, Integrator::velocity_verlet, Integrator::rk4}) {
    const Vec2 x0{10.0, 20.0};
    const Vec2 v{1.5, -0.75};
    World world(WorldDef{.dt = 0.5, .integrator = integrator});
    world.add(calder::Gravity{.enabled = false});  // a disabled field contributes nothing
    const BodyId body = world.add_body({.position = x0, .velocity = v, .mass = 2.0});
    // A second body with a non-dyadic velocity: still a straight line.
    const Vec2 w{0.1, 0.3};
    const BodyId other = world.add_body({.position = {1.0, 1.0}, .velocity = w});
    for (int k = 1; k <= 1000; ++k) {
      world.step();
      ASSERT_EQ(world.velocity(body), v) << calder::integrator_name(integrator);
      ASSERT_EQ(world.velocity(other), w) << calder::integrator_name(integrator);
    }
    EXPECT_EQ(world.position(body), x0 + v * 500.0) << calder::integrator_name(integrator);
    // At (1, 1) + w t up to the rounding of 1000 additions, each at most half
    // an ulp of the coordinate (< 256, ulp 2^-45): 1000 * 2^-46.
    const Vec2 expected = Vec2{1.0, 1.0} + w * 500.0;
    const double bound = 1000.0 * std::ldexp(1.0, -46);
    EXPECT_NEAR(world.position(other).x, expected.x, bound) << calder::integrator_name(integrator);
    EXPECT_NEAR(world.position(other).y, expected.y, bound) << calder::integrator_name(integrator);
  }
}

TEST(IntegratorsExact, OneStepOfAppliedConstantForce) {
  // A force applied before step() acts through the whole step for every
  // integrator, and is cleared after it. From x0, v0 with a = F / m:
  //   semi-implicit Euler: v1 = v0 + a dt, x1 = x0 + v1 dt = x0 + v0 dt + a dt^2;
  //   velocity Verlet:     v_half = v0 + a dt / 2, x1 = x0 + v_half dt
  //                          = x0 + v0 dt + a dt^2 / 2, v1 = v_half + a dt / 2;
  //   RK4: stage velocities v0, v0 + a dt/2 (twice), v0 + a dt, weighted 1 2 2 1
  //        over 6: x1 = x0 + v0 dt + a dt^2 / 2, v1 = v0 + a dt
  // (Verlet and RK4 are exact for a constant force). Dyadic values: exact in
  // binary, except RK4's dt / 6 (to a few ulps).
  const Vec2 x0{10.0, 20.0};
  const Vec2 v0{1.0, 0.25};
  const double m = 4.0;
  const Vec2 force{2.0, -3.0};
  const Vec2 a = force / m;  // (0.5, -0.75)
  const double dt = 0.5;
  for (const Integrator integrator :
       {Integrator::semi_implicit_euler, Integrator::velocity_verlet, Integrator::rk4}) {
    World world(WorldDef{.dt = dt, .integrator = integrator});
    const BodyId body = world.add_body({.position = x0, .velocity = v0, .mass = m});
    world.apply_force(body, force);
    EXPECT_EQ(world.acceleration(body), a);
    world.step();
    const Vec2 v1 = v0 + a * dt;
    const Vec2 x1 = integrator == Integrator::semi_implicit_euler
                        ? x0 + v0 * dt + a * (dt * dt)
                        : x0 + v0 * dt + a * (dt * dt / 2.0);
    if (integrator == Integrator::rk4) {
      EXPECT_DOUBLE_EQ(world.position(body).x, x1.x);
      EXPECT_DOUBLE_EQ(world.position(body).y, x1.y);
      EXPECT_DOUBLE_EQ(world.velocity(body).x, v1.x);
      EXPECT_DOUBLE_EQ(world.velocity(body).y, v1.y);
    } else {
      EXPECT_EQ(world.position(body), x1) << calder::integrator_name(integrator);
      EXPECT_EQ(world.velocity(body), v1) << calder::integrator_name(integrator);
    }
    EXPECT_EQ(world.acceleration(body), Vec2{}) << calder::integrator_name(integrator);
    // The force does not persist: the next step coasts at v1.
    const Vec2 before = world.position(body);
    const Vec2 velocity = world.velocity(body);
    world.step();
    EXPECT_EQ(world.velocity(body), velocity) << calder::integrator_name(integrator);
    EXPECT_NEAR((world.position(body) - (before + velocity * dt)).mag(), 0.0, 1e-13);
  }
}

TEST(IntegratorsExact, VerletAndRk4AreExactForConstantGravity) {
  // Under a constant field both reproduce x(t) = x0 + v0 t + a t^2 / 2 at
  // every step (their local error terms involve da/dt = 0). Verlet, dyadic
  // values: exactly; RK4: to rounding. Euler instead carries a t dt / 2.
  const Vec2 x0{5.0, -3.0};
  const Vec2 v0{0.5, 2.0};
  const Vec2 g{0.25, 1.0};
  const double dt = 0.125;
  World verlet(WorldDef{.dt = dt, .integrator = Integrator::velocity_verlet});
  World rk4(WorldDef{.dt = dt, .integrator = Integrator::rk4});
  for (World* world : {&verlet, &rk4}) {
    world->add(calder::Gravity{.g = g, .scale_by_mass = true});
    world->add_body({.position = x0, .velocity = v0, .mass = 3.0});
  }
  for (int k = 1; k <= 800; ++k) {
    verlet.step();
    rk4.step();
    const double t = k * dt;
    const Vec2 exact = x0 + v0 * t + g * (t * t / 2.0);
    ASSERT_EQ(verlet.position(verlet.body(0)), exact) << "step " << k;
    ASSERT_EQ(verlet.velocity(verlet.body(0)), v0 + g * t) << "step " << k;
    ASSERT_NEAR((rk4.position(rk4.body(0)) - exact).mag(), 0.0, 1e-10 * exact.mag())
        << "step " << k;
  }
}

TEST(IntegratorsExact, SequentialOrderNeedsEuler) {
  // UpdateOrder::sequential is defined for the book's one-stage update only.
  World world(
      WorldDef{.integrator = Integrator::rk4, .update_order = calder::UpdateOrder::sequential});
  world.add_body({});
  EXPECT_THROW(world.step(), calder::Error);
}

}  // namespace
