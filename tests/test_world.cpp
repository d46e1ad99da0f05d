// SPDX-License-Identifier: MIT
// Tests of the World / Mover API (calder/world.hpp), FixedStep and the
// trajectory writer, against values worked by hand and the book's semantics
// (shared/spec/chapter2.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <initializer_list>
#include <limits>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "calder/error.hpp"
#include "calder/fields.hpp"
#include "calder/fixed_step.hpp"
#include "calder/trajectory.hpp"
#include "calder/vec2.hpp"
#include "calder/world.hpp"
#include "support/test_support.hpp"

namespace {

using calder::BodyDef;
using calder::BodyId;
using calder::Boundary;
using calder::BoundaryTiming;
using calder::Edge;
using calder::Error;
using calder::FixedStep;
using calder::Integrator;
using calder::Mover;
using calder::UpdateOrder;
using calder::Vec2;
using calder::World;
using calder::WorldDef;
using calder::test::expect_error;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Asserts that f throws calder::Error whose message contains every needle
// (the function's name and the offending field).
bool finite_state(const World& w) {
  const calder::BodyView b = w.bodies();
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (!b.position(i).is_finite() || !b.velocity(i).is_finite()) return false;
  }
  return true;
}

// ------------------------------------------------------------ apply_force ---

TEST(WorldApplyForce, DividesByMassAndAccumulatesOneCallAtATime) {
  World world;
  Mover m = world.add_mover({.position = {0.0, 0.0}, .mass = 3.0});
  const Vec2 f1{0.2, 0.1};
  const Vec2 f2{0.4, -0.3};
  m.apply_force(f1);
  EXPECT_EQ(m.acceleration(), (Vec2{0.2 / 3.0, 0.1 / 3.0}));
  m.apply_force(f2);
  // acc = (0 + F1/m) + F2/m, one division per force (not (F1 + F2) / m, not F * (1/m)).
  EXPECT_EQ(m.acceleration().x, (0.0 + 0.2 / 3.0) + 0.4 / 3.0);
  EXPECT_EQ(m.acceleration().y, (0.0 + 0.1 / 3.0) + -0.3 / 3.0);
  // The groupings differ in the last bits here, so the test tells them apart:
  // 0.2 and 0.20000000000000004; -0.06666666666666665 and -0.06666666666666667.
  ASSERT_NE((0.0 + 0.2 / 3.0) + 0.4 / 3.0, (0.2 + 0.4) / 3.0);
  ASSERT_NE((0.0 + 0.1 / 3.0) + -0.3 / 3.0, (0.1 + -0.3) / 3.0);
}

TEST(WorldApplyForce, LeavesTheCallersForceAlone) {
  // The seed's aliasing bug: applyForce(force) { force.div(mass); ... } divided
  // the caller's wind, so the second mover got wind / m1 / m2.
  World world;
  Mover a = world.add_mover({.mass = 2.0});
  Mover b = world.add_mover({.mass = 5.0});
  Vec2 wind{0.1, 0.0};
  a.apply_force(wind);
  b.apply_force(wind);
  EXPECT_EQ(wind, (Vec2{0.1, 0.0}));
  EXPECT_EQ(a.acceleration().x, 0.1 / 2.0);
  EXPECT_EQ(b.acceleration().x, 0.1 / 5.0);
  world.apply_force(a.id(), wind);
  EXPECT_EQ(wind, (Vec2{0.1, 0.0}));
  EXPECT_EQ(a.acceleration().x, 0.1 / 2.0 + 0.1 / 2.0);
}

// ----------------------------------------------------------------- update ---

TEST(WorldUpdate, SemiImplicitEulerThenClearsAcceleration) {
  // x = (1, 2), v = (3, 4), F = (0.5, -1), m = 2, dt = 1: a = (0.25, -0.5),
  // v = (3.25, 3.5), x = (4.25, 5.5) (the new velocity moves the body).
  World world;
  Mover m = world.add_mover({.position = {1.0, 2.0}, .velocity = {3.0, 4.0}, .mass = 2.0});
  m.apply_force({0.5, -1.0});
  m.update();
  EXPECT_EQ(m.velocity(), (Vec2{3.25, 3.5}));
  EXPECT_EQ(m.position(), (Vec2{4.25, 5.5}));
  EXPECT_EQ(m.acceleration(), (Vec2{0.0, 0.0}));
  // No force now: v constant, x += v.
  m.update();
  EXPECT_EQ(m.velocity(), (Vec2{3.25, 3.5}));
  EXPECT_EQ(m.position(), (Vec2{7.5, 9.0}));
}

TEST(WorldUpdate, UsesTheWorldsDt) {
  // dt = 0.5: v = 3 + 0.25 * 0.5 = 3.125, x = 1 + 3.125 * 0.5 = 2.5625
  // (explicit Euler would give 1 + 3 * 0.5 = 2.5).
  World world({.dt = 0.5});
  Mover m = world.add_mover({.position = {1.0, 2.0}, .velocity = {3.0, 4.0}, .mass = 2.0});
  m.apply_force({0.5, -1.0});
  m.update();
  EXPECT_EQ(m.velocity(), (Vec2{3.125, 3.75}));
  EXPECT_EQ(m.position(), (Vec2{2.5625, 3.875}));
}

TEST(WorldUpdate, NewtonsFirstLawOverManySteps) {
  World world;
  Mover m = world.add_mover({.position = {0.0, 0.0}, .velocity = {0.1, 0.3}});
  const BodyId other = world.add_body({.position = {5.0, 5.0}, .velocity = {-0.7, 0.01}});
  double x = 0.0;
  double y = 0.0;
  for (int k = 0; k < 1000; ++k) {
    m.update();
    x += 0.1;
    y += 0.3;
  }
  EXPECT_EQ(m.velocity(), (Vec2{0.1, 0.3}));
  EXPECT_EQ(m.position(), (Vec2{x, y}));
  // And world.step() with no fields: the same.
  double ox = 5.0;
  double oy = 5.0;
  const Vec2 p = m.position();
  world.step(1000);
  for (int k = 0; k < 1000; ++k) {
    ox += -0.7;
    oy += 0.01;
    x += 0.1;
    y += 0.3;
  }
  EXPECT_EQ(world.velocity(other), (Vec2{-0.7, 0.01}));
  EXPECT_EQ(world.position(other), (Vec2{ox, oy}));
  EXPECT_NE(m.position(), p);
  EXPECT_EQ(m.position(), (Vec2{x, y}));
}

TEST(WorldStep, IncludesForcesAppliedBeforeTheStepAndClearsThem) {
  World world;
  Mover m = world.add_mover({.mass = 4.0});
  m.apply_force({1.0, 2.0});  // a = (0.25, 0.5)
  world.step();
  EXPECT_EQ(m.velocity(), (Vec2{0.25, 0.5}));
  EXPECT_EQ(m.position(), (Vec2{0.25, 0.5}));
  EXPECT_EQ(m.acceleration(), (Vec2{0.0, 0.0}));
  world.step();
  EXPECT_EQ(m.velocity(), (Vec2{0.25, 0.5}));
  EXPECT_EQ(m.position(), (Vec2{0.5, 1.0}));
}

// ------------------------------------------------------------- validation ---

TEST(WorldValidation, BodyDefinitions) {
  World world;
  expect_error([&] { world.add_body({.mass = 0.0}); }, {"World::add_body", "mass"});
  expect_error([&] { world.add_body({.mass = -1.0}); }, {"World::add_body", "mass"});
  expect_error([&] { world.add_body({.mass = kNaN}); }, {"World::add_body", "mass"});
  expect_error([&] { world.add_body({.mass = kInf}); }, {"World::add_body", "mass"});
  expect_error([&] { world.add_body({.position = {kNaN, 0.0}}); }, {"World::add_body", "position"});
  expect_error(
      [&] {
        world.add_body({.position = {0.0, -kInf}});
      },
      {"World::add_body", "position"});
  expect_error([&] { world.add_body({.velocity = {0.0, kNaN}}); }, {"World::add_body", "velocity"});
  expect_error([&] { world.add_body({.radius = -1.0}); }, {"World::add_body", "radius"});
  expect_error([&] { world.add_body({.radius = kNaN}); }, {"World::add_body", "radius"});
  expect_error([&] { world.add_body({.friction = -0.1}); }, {"World::add_body", "friction"});
  expect_error([&] { world.add_body({.drag_area = kNaN}); }, {"World::add_body", "drag_area"});
  expect_error([&] { (void)world.add_mover({.mass = 0.0}); }, {"mass"});
  EXPECT_EQ(world.body_count(), 0U);  // nothing half-added
}

TEST(WorldValidation, SettersAndForcesKeepTheStateFinite) {
  World world;
  Mover m = world.add_mover({.position = {1.0, 2.0}, .velocity = {3.0, 4.0}, .mass = 2.0});
  const BodyId id = m.id();
  expect_error([&] { m.apply_force({kNaN, 0.0}); }, {"World::apply_force", "force"});
  expect_error([&] { m.apply_force({0.0, kInf}); }, {"World::apply_force", "force"});
  expect_error([&] { m.set_position({kNaN, 0.0}); }, {"World::set_position", "position"});
  expect_error([&] { m.set_velocity({0.0, kInf}); }, {"World::set_velocity", "velocity"});
  expect_error([&] { world.set_mass(id, 0.0); }, {"World::set_mass", "mass"});
  expect_error([&] { world.set_mass(id, kNaN); }, {"World::set_mass", "mass"});
  expect_error([&] { world.set_radius(id, -2.0); }, {"World::set_radius", "radius"});
  expect_error([&] { world.set_radius(id, kNaN); }, {"World::set_radius", "radius"});
  expect_error([&] { world.set_friction(id, -1.0); }, {"World::set_friction", "friction"});
  expect_error([&] { world.set_drag_area(id, -1.0); }, {"World::set_drag_area", "drag_area"});
  EXPECT_EQ(m.position(), (Vec2{1.0, 2.0}));
  EXPECT_EQ(m.velocity(), (Vec2{3.0, 4.0}));
  EXPECT_EQ(m.acceleration(), (Vec2{0.0, 0.0}));
  EXPECT_EQ(m.mass(), 2.0);
  EXPECT_EQ(m.radius(), 0.0);
}

TEST(WorldValidation, WorldDefinitionAndDt) {
  expect_error([] { World w({.width = 0.0}); }, {"World", "width"});
  expect_error([] { World w({.width = -640.0}); }, {"World", "width"});
  expect_error([] { World w({.height = 0.0}); }, {"World", "height"});
  expect_error([] { World w({.height = kNaN}); }, {"World", "height"});
  expect_error([] { World w({.dt = 0.0}); }, {"World", "dt"});
  expect_error([] { World w({.dt = -1.0}); }, {"World", "dt"});
  expect_error([] { World w({.dt = kNaN}); }, {"World", "dt"});
  expect_error([] { World w({.boundary = Boundary::bounce(-0.5)}); }, {"World", "restitution"});
  World world;
  expect_error([&] { world.set_dt(0.0); }, {"World::set_dt", "dt"});
  expect_error([&] { world.set_dt(-0.1); }, {"World::set_dt", "dt"});
  expect_error([&] { world.set_dt(kNaN); }, {"World::set_dt", "dt"});
  expect_error([&] { world.set_dt(kInf); }, {"World::set_dt", "dt"});
  EXPECT_EQ(world.dt(), 1.0);
  world.set_dt(0.25);
  EXPECT_EQ(world.dt(), 0.25);
  expect_error([&] { world.set_boundary(Boundary::bounce(-1.0)); },
               {"World::set_boundary", "restitution"});
  expect_error([&] { world.set_boundary(Boundary::bounce(kNaN)); },
               {"World::set_boundary", "restitution"});
  EXPECT_EQ(world.boundary().kind, calder::BoundaryKind::none);
}

TEST(WorldValidation, BadBodyIds) {
  World world;
  world.add_body({});
  const BodyId bad{7};
  expect_error([&] { (void)world.position(bad); }, {"World::position", "7"});
  expect_error([&] { (void)world.velocity(bad); }, {"World::velocity"});
  expect_error([&] { (void)world.acceleration(bad); }, {"World::acceleration"});
  expect_error([&] { (void)world.mass(bad); }, {"World::mass"});
  expect_error([&] { (void)world.radius(bad); }, {"World::radius"});
  expect_error([&] { world.apply_force(bad, {1.0, 0.0}); }, {"World::apply_force"});
  expect_error([&] { world.update(bad); }, {"World::update"});
  expect_error([&] { world.set_position(bad, {}); }, {"World::set_position"});
  expect_error([&] { world.apply_boundary(bad); }, {"World::apply_boundary"});
  expect_error([&] { (void)world.touching(bad, Edge::bottom); }, {"World::touching"});
  expect_error([&] { (void)world.mover(bad); }, {"World::mover"});
  expect_error([&] { (void)world.mover(BodyId{}); }, {"World::mover"});  // default: invalid
  expect_error([&] { (void)world.body(1); }, {"World::body", "1"});
}

TEST(WorldValidation, NegativeStepCount) {
  World world;
  world.add_body({.velocity = {1.0, 0.0}});
  expect_error([&] { world.step(-1); }, {"World::step", "count"});
  EXPECT_EQ(world.step_count(), 0);
  world.step(0);
  EXPECT_EQ(world.step_count(), 0);
  EXPECT_EQ(world.position(world.body(0)), (Vec2{0.0, 0.0}));
}

TEST(WorldValidation, FieldWithNaNParameterIsRejectedByAdd) {
  World world;
  expect_error([&] { world.add(calder::Gravity{.g = {0.0, kNaN}}); }, {"gravity", "g"});
  expect_error([&] { world.add(calder::Drag{.c = -1.0}); }, {"drag", "c"});
  EXPECT_TRUE(world.fields().empty());
}

TEST(WorldValidation, FieldMutatedToNaNStopsStepBeforeAnyChange) {
  World world;
  Mover m = world.add_mover({.position = {10.0, 20.0}, .velocity = {1.0, -2.0}, .mass = 2.0});
  world.add(calder::Gravity{});
  auto& wind = world.add(calder::Wind{.force = {0.1, 0.0}});
  world.step();
  const Vec2 p = m.position();
  const Vec2 v = m.velocity();
  m.apply_force({0.5, 0.0});
  wind.force.x = kNaN;
  expect_error([&] { world.step(); }, {"wind", "force"});
  EXPECT_EQ(m.position(), p);
  EXPECT_EQ(m.velocity(), v);
  EXPECT_EQ(m.acceleration(), (Vec2{0.25, 0.0}));  // the applied force is still pending
  EXPECT_EQ(world.time(), 1.0);
  EXPECT_EQ(world.step_count(), 1);
  // Fixed, the world goes on.
  wind.force.x = 0.0;
  world.step();
  EXPECT_EQ(world.step_count(), 2);
}

TEST(WorldValidation, CustomForceReturningNaNThrowsFromStep) {
  // Body 1's custom force is NaN. The step throws, and no body has moved: not
  // body 1, and not body 0 either (which a sequential step reaches first).
  for (const UpdateOrder order : {UpdateOrder::simultaneous, UpdateOrder::sequential}) {
    SCOPED_TRACE(order == UpdateOrder::simultaneous ? "simultaneous" : "sequential");
    World world({.update_order = order});
    Mover first = world.add_mover({.position = {1.0, 1.0}, .velocity = {0.5, 0.0}});
    Mover m = world.add_mover({.position = {10.0, 20.0}, .velocity = {1.0, -2.0}});
    world.add(calder::CustomForce{.force = [](const calder::FieldContext&, std::size_t i) {
      return i == 1 ? Vec2{kNaN, 0.0} : Vec2{0.0, 1.0};
    }});
    expect_error([&] { world.step(); }, {"custom_force"});
    EXPECT_TRUE(finite_state(world));
    EXPECT_EQ(m.position(), (Vec2{10.0, 20.0}));
    EXPECT_EQ(m.velocity(), (Vec2{1.0, -2.0}));
    EXPECT_EQ(first.position(), (Vec2{1.0, 1.0}));
    EXPECT_EQ(first.velocity(), (Vec2{0.5, 0.0}));
    EXPECT_EQ(world.step_count(), 0);
    EXPECT_EQ(world.time(), 0.0);
  }
}

TEST(WorldValidation, AFailedStepLeavesNoHalfAccumulatedForce) {
  // Gravity (0, 0.1) on mass 1, then a custom force that fails. Once the
  // custom force is switched off, the next step must be an ordinary one:
  // v = (0, 0.1), not gravity counted twice.
  World world;
  Mover m = world.add_mover({});
  world.add(calder::Gravity{});
  auto& custom =
      world.add(calder::CustomForce{.force = [](const calder::FieldContext&, std::size_t) {
        return Vec2{kNaN, 0.0};
      }});
  EXPECT_THROW(world.step(), Error);
  EXPECT_EQ(m.acceleration(), (Vec2{0.0, 0.0}));
  custom.enabled = false;
  world.step();
  EXPECT_EQ(m.velocity(), (Vec2{0.0, 0.1}));
}

TEST(WorldValidation, AnOverflowingStepThrowsWithoutLeavingInfinityInTheState) {
  // A finite force so large that F / m overflows: the step must throw, and
  // (never NaN or infinity in the state) the body must stay finite.
  World world;
  Mover m = world.add_mover({.position = {1.0, 2.0}, .mass = 1e-10});
  world.add(calder::Wind{.force = {1e300, 0.0}});
  expect_error([&] { world.step(); }, {"World::step"});
  EXPECT_TRUE(finite_state(world)) << "x " << m.position().x << ", vx " << m.velocity().x;
}

TEST(WorldValidation, AnOverflowingForceNeverLeavesInfinityInTheState) {
  // apply_force(1e300) on mass 1e-10: acceleration 1e310 overflows. Whatever
  // throws, and where, the body's state must stay finite.
  World world;
  Mover m = world.add_mover({.position = {1.0, 2.0}, .mass = 1e-10});
  bool threw = false;
  try {
    m.apply_force({1e300, 0.0});
    m.update();
  } catch (const Error&) {
    threw = true;
  }
  EXPECT_TRUE(threw);
  EXPECT_TRUE(finite_state(world)) << "x " << m.position().x << ", vx " << m.velocity().x;
  EXPECT_TRUE(m.acceleration().is_finite()) << m.acceleration().x;
}

TEST(WorldValidation, EmptyCustomForceIsRejected) {
  World world;
  expect_error([&] { world.add(calder::CustomForce{}); }, {"custom_force"});
}

// ------------------------------------------------------------- boundaries ---

struct BounceCase {
  const char* name;
  Vec2 position;
  Vec2 velocity;
  Vec2 expected_position;
  Vec2 expected_velocity;
};

TEST(WorldBoundary, BounceOnTheCentreWithRestitution) {
  // 640 x 240, restitution 0.9: one step moves the body past an edge; it is
  // put back on the edge and that velocity component becomes -0.9 times itself.
  const BounceCase cases[] = {
      {"right", {639.5, 100.0}, {1.0, 0.0}, {640.0, 100.0}, {-0.9, 0.0}},
      {"left", {0.5, 100.0}, {-1.0, 0.0}, {0.0, 100.0}, {0.9, 0.0}},
      {"bottom", {100.0, 239.5}, {0.0, 1.0}, {100.0, 240.0}, {0.0, -0.9}},
      {"top", {100.0, 0.5}, {0.0, -1.0}, {100.0, 0.0}, {0.0, 0.9}},
      {"corner", {639.5, 239.5}, {1.0, 1.0}, {640.0, 240.0}, {-0.9, -0.9}},
      {"inside", {320.0, 120.0}, {1.0, 1.0}, {321.0, 121.0}, {1.0, 1.0}},
  };
  for (const BounceCase& c : cases) {
    World world({.boundary = Boundary::bounce(0.9)});
    Mover m = world.add_mover({.position = c.position, .velocity = c.velocity, .radius = 10.0});
    world.step();
    EXPECT_EQ(m.position(), c.expected_position) << c.name;
    EXPECT_EQ(m.velocity(), c.expected_velocity) << c.name;
  }
}

TEST(WorldBoundary, BounceOnTheRadius) {
  // r = 10: the walls are at x = 10, 630 and y = 10, 230.
  const BounceCase cases[] = {
      {"right", {629.5, 100.0}, {1.0, 0.0}, {630.0, 100.0}, {-0.9, 0.0}},
      {"left", {10.5, 100.0}, {-1.0, 0.0}, {10.0, 100.0}, {0.9, 0.0}},
      {"bottom", {100.0, 229.5}, {0.0, 1.0}, {100.0, 230.0}, {0.0, -0.9}},
      {"top", {100.0, 10.5}, {0.0, -1.0}, {100.0, 10.0}, {0.0, 0.9}},
  };
  for (const BounceCase& c : cases) {
    World world({.boundary = Boundary::bounce(0.9, true)});
    Mover m = world.add_mover({.position = c.position, .velocity = c.velocity, .radius = 10.0});
    world.step();
    EXPECT_EQ(m.position(), c.expected_position) << c.name;
    EXPECT_EQ(m.velocity(), c.expected_velocity) << c.name;
  }
  // Restitution 1 reverses exactly; restitution 0 stops the component.
  World elastic({.boundary = Boundary::bounce(1.0, true)});
  Mover e = elastic.add_mover({.position = {629.5, 100.0}, .velocity = {1.0, 0.5}, .radius = 10.0});
  elastic.step();
  EXPECT_EQ(e.velocity(), (Vec2{-1.0, 0.5}));
  World dead({.boundary = Boundary::bounce(0.0, true)});
  Mover d = dead.add_mover({.position = {629.5, 100.0}, .velocity = {1.0, 0.5}, .radius = 10.0});
  dead.step();
  EXPECT_EQ(d.velocity().x, 0.0);
  EXPECT_EQ(d.position().x, 630.0);
}

TEST(WorldBoundary, OnlyTheChosenEdges) {
  World world({.boundary = Boundary::bounce(1.0, false, {.left = false, .top = false})});
  Mover up = world.add_mover({.position = {100.0, 0.5}, .velocity = {0.0, -1.0}});
  Mover left = world.add_mover({.position = {0.5, 100.0}, .velocity = {-1.0, 0.0}});
  Mover right = world.add_mover({.position = {639.5, 100.0}, .velocity = {1.0, 0.0}});
  world.step(2);
  EXPECT_EQ(up.position(), (Vec2{100.0, -1.5}));  // through the top
  EXPECT_EQ(up.velocity(), (Vec2{0.0, -1.0}));
  EXPECT_EQ(left.position(), (Vec2{-1.5, 100.0}));  // through the left
  EXPECT_EQ(left.velocity(), (Vec2{-1.0, 0.0}));
  EXPECT_EQ(right.position(), (Vec2{639.0, 100.0}));  // right still bounces: 640, then 639
  EXPECT_EQ(right.velocity(), (Vec2{-1.0, 0.0}));
}

TEST(WorldBoundary, WrapOnTheCentre) {
  // Periodic on [0, 640] x [0, 240]: the overshoot reappears on the other side.
  World world({.boundary = Boundary::wrap()});
  Mover r = world.add_mover({.position = {639.5, 100.0}, .velocity = {1.0, 0.0}, .radius = 10.0});
  Mover l = world.add_mover({.position = {0.5, 100.0}, .velocity = {-1.0, 0.0}});
  Mover b = world.add_mover({.position = {100.0, 239.5}, .velocity = {0.0, 1.0}});
  Mover t = world.add_mover({.position = {100.0, 0.5}, .velocity = {0.0, -1.0}});
  world.step();
  EXPECT_EQ(r.position(), (Vec2{0.5, 100.0}));
  EXPECT_EQ(l.position(), (Vec2{639.5, 100.0}));
  EXPECT_EQ(b.position(), (Vec2{100.0, 0.5}));
  EXPECT_EQ(t.position(), (Vec2{100.0, 239.5}));
  // Velocities are untouched by wrapping.
  EXPECT_EQ(r.velocity(), (Vec2{1.0, 0.0}));
  EXPECT_EQ(t.velocity(), (Vec2{0.0, -1.0}));
}

TEST(WorldBoundary, WrapOnTheRadius) {
  // r = 10: a circle wraps once it has wholly left, x > 650, and comes back
  // just outside the other side: the period is 640 + 2 r = 660.
  World world({.boundary = Boundary::wrap(true)});
  Mover partly =
      world.add_mover({.position = {639.5, 100.0}, .velocity = {1.0, 0.0}, .radius = 10.0});
  Mover gone =
      world.add_mover({.position = {649.5, 100.0}, .velocity = {1.0, 0.0}, .radius = 10.0});
  Mover left =
      world.add_mover({.position = {-9.5, 100.0}, .velocity = {-1.0, 0.0}, .radius = 10.0});
  Mover down = world.add_mover({.position = {50.0, 249.5}, .velocity = {0.0, 1.0}, .radius = 10.0});
  world.step();
  EXPECT_EQ(partly.position(), (Vec2{640.5, 100.0}));  // still partly visible
  EXPECT_EQ(gone.position(), (Vec2{-9.5, 100.0}));     // 650.5 - 660
  EXPECT_EQ(left.position(), (Vec2{649.5, 100.0}));    // -10.5 + 660
  EXPECT_EQ(down.position(), (Vec2{50.0, -9.5}));      // 250.5 - 260
}

TEST(WorldBoundary, WrapToTheOtherEdgeWhenNotPeriodic) {
  // The book's rule (exercise 2.1): past the right edge, x = 0 (+0, not -0);
  // past the left, x = width; y only when top or bottom is listed.
  Boundary wrap = Boundary::wrap();
  wrap.periodic = false;
  wrap.edges = {.top = false, .bottom = false};
  World world({.boundary = wrap});
  Mover r = world.add_mover({.position = {639.5, 100.0}, .velocity = {1.0, 0.0}});
  Mover l = world.add_mover({.position = {0.5, 100.0}, .velocity = {-1.0, 0.0}});
  Mover b = world.add_mover({.position = {100.0, 239.5}, .velocity = {0.0, 1.0}});
  world.step();
  EXPECT_EQ(std::bit_cast<std::uint64_t>(r.position().x), std::bit_cast<std::uint64_t>(0.0));
  EXPECT_EQ(l.position(), (Vec2{640.0, 100.0}));
  EXPECT_EQ(b.position(), (Vec2{100.0, 240.5}));  // not wrapped: top and bottom are off
  EXPECT_EQ(r.velocity(), (Vec2{1.0, 0.0}));
  // On the radius: a circle of radius 10 goes to x = -10 once past 650.
  wrap.use_radius = true;
  World round({.boundary = wrap});
  Mover gone = round.add_mover({.position = {649.5, 50.0}, .velocity = {1.0, 0.0}, .radius = 10.0});
  round.step();
  EXPECT_EQ(gone.position(), (Vec2{-10.0, 50.0}));
}

TEST(WorldBoundary, BounceInsetMovesTheWallsIn) {
  // Walls 1 px inside the canvas, on the radius 24: the balloon of exercise
  // 2.1 is put at y = 25 once above it, its vertical speed times -0.75.
  Boundary ceiling = Boundary::bounce(0.75, true, {.left = false, .right = false, .bottom = false});
  ceiling.inset = 1.0;
  World world({.boundary = ceiling});
  Mover up = world.add_mover({.position = {100.0, 25.5}, .velocity = {0.0, -1.0}, .radius = 24});
  Mover stays = world.add_mover({.position = {200.0, 27.0}, .velocity = {0.0, -1.0}, .radius = 24});
  world.step();
  EXPECT_EQ(up.position(), (Vec2{100.0, 25.0}));
  EXPECT_EQ(up.velocity(), (Vec2{0.0, 0.75}));
  EXPECT_EQ(stays.position(), (Vec2{200.0, 26.0}));  // 26 > 25: no bounce
  ceiling.inset = -1.0;
  expect_error([&] { World bad({.boundary = ceiling}); }, {"boundary", "inset"});
}

TEST(WorldMaxSpeed, LimitsTheSpeedLikeP5sLimitBetweenKickAndDrift) {
  // p5: vel.add(acc); vel.limit(5): if |v|^2 > 25, v = v / |v| * 5; pos.add(vel).
  World world({.max_speed = 5.0});
  Mover fast = world.add_mover({.position = {100.0, 100.0}, .velocity = {3.0, 3.0}, .mass = 2});
  Mover slow = world.add_mover({.position = {100.0, 100.0}, .velocity = {1.0, 0.0}});
  fast.apply_force({2.0, 0.5});  // a = (1, 0.25)
  slow.apply_force({0.5, 0.0});
  world.step();
  const double vx = 3.0 + 1.0;
  const double vy = 3.0 + 0.25;
  const double m = std::sqrt(vx * vx + vy * vy);
  const Vec2 limited{vx / m * 5.0, vy / m * 5.0};
  EXPECT_EQ(fast.velocity(), limited);
  EXPECT_EQ(fast.position(), (Vec2{100.0 + limited.x, 100.0 + limited.y}));
  EXPECT_EQ(slow.velocity(), (Vec2{1.5, 0.0}));  // under the limit: untouched
  // Mover::update (book style) limits the same way.
  World book({.max_speed = 5.0});
  Mover single = book.add_mover({.velocity = {3.0, 3.0}, .mass = 2});
  single.apply_force({2.0, 0.5});
  single.update();
  EXPECT_EQ(single.velocity(), limited);
  // Only the book's integrator and arithmetic know it.
  World verlet({.integrator = calder::Integrator::velocity_verlet, .max_speed = 5.0});
  verlet.add_body({});
  expect_error([&] { verlet.step(); }, {"max_speed", "semi_implicit_euler"});
  World float64({.arithmetic = calder::Arithmetic::float64, .max_speed = 5.0});
  float64.add_body({});
  expect_error([&] { float64.step(); }, {"float64", "max_speed"});
  expect_error([&] { World bad({.max_speed = -1.0}); }, {"World", "max_speed"});
}

TEST(WorldBoundary, TimingBeforeOrAfterTheUpdate) {
  // Body outside the right edge at x = 640.5 moving right at 1.
  // before_update: bounce (x = 640, vx = -1), then update: x = 639.
  // after_update: update (x = 641.5), then bounce: x = 640, vx = -1.
  Boundary before = Boundary::bounce(1.0);
  before.timing = BoundaryTiming::before_update;
  World wb({.boundary = before});
  Mover mb = wb.add_mover({.position = {640.5, 100.0}, .velocity = {1.0, 0.0}});
  wb.step();
  EXPECT_EQ(mb.position(), (Vec2{639.0, 100.0}));
  EXPECT_EQ(mb.velocity(), (Vec2{-1.0, 0.0}));

  World wa({.boundary = Boundary::bounce(1.0)});
  EXPECT_EQ(wa.boundary().timing, BoundaryTiming::after_update);
  Mover ma = wa.add_mover({.position = {640.5, 100.0}, .velocity = {1.0, 0.0}});
  wa.step();
  EXPECT_EQ(ma.position(), (Vec2{640.0, 100.0}));
  EXPECT_EQ(ma.velocity(), (Vec2{-1.0, 0.0}));
}

TEST(WorldBoundary, ApplyBoundaryByHand) {
  World world;  // the world's own boundary is none
  Mover m = world.add_mover({.position = {700.0, -5.0}, .velocity = {2.0, -3.0}, .radius = 4.0});
  m.check_edges();  // none: nothing happens
  EXPECT_EQ(m.position(), (Vec2{700.0, -5.0}));
  m.check_edges(Boundary::bounce(0.5, true));  // x > 636 -> 636, y < 4 -> 4
  EXPECT_EQ(m.position(), (Vec2{636.0, 4.0}));
  EXPECT_EQ(m.velocity(), (Vec2{-1.0, 1.5}));
  expect_error([&] { m.check_edges(Boundary::bounce(-1.0)); },
               {"World::apply_boundary", "restitution"});
  world.set_boundary(Boundary::wrap());
  m.set_position({-1.0, 250.0});
  m.check_edges();
  EXPECT_EQ(m.position(), (Vec2{639.0, 10.0}));
}

// --------------------------------------------------------------- touching ---

TEST(WorldTouching, AllFourEdgesWithTolerance) {
  // r = 40 on 640 x 240, tolerance 1: bottom is y > 240 - 40 - 1 = 199 (strict).
  World world;
  Mover m = world.add_mover({.position = {320.0, 199.0}, .radius = 40.0});
  const BodyId id = m.id();
  EXPECT_FALSE(world.touching(id, Edge::bottom));
  EXPECT_FALSE(m.contact_edge());
  m.set_position({320.0, 199.5});
  EXPECT_TRUE(world.touching(id, Edge::bottom));
  EXPECT_TRUE(m.contact_edge());
  EXPECT_FALSE(world.touching(id, Edge::bottom, 0.0));  // 199.5 > 200 is false
  EXPECT_FALSE(world.touching(id, Edge::top));
  EXPECT_FALSE(world.touching(id, Edge::left));
  EXPECT_FALSE(world.touching(id, Edge::right));
  // top: y < r + tolerance = 41.
  m.set_position({320.0, 41.0});
  EXPECT_FALSE(world.touching(id, Edge::top));
  m.set_position({320.0, 40.5});
  EXPECT_TRUE(world.touching(id, Edge::top));
  EXPECT_TRUE(world.touching(id, Edge::top, 0.6));
  EXPECT_FALSE(world.touching(id, Edge::top, 0.5));
  // left: x < 41; right: x > 640 - 41 = 599.
  m.set_position({41.0, 120.0});
  EXPECT_FALSE(world.touching(id, Edge::left));
  m.set_position({40.5, 120.0});
  EXPECT_TRUE(world.touching(id, Edge::left));
  m.set_position({599.0, 120.0});
  EXPECT_FALSE(world.touching(id, Edge::right));
  m.set_position({599.5, 120.0});
  EXPECT_TRUE(world.touching(id, Edge::right));
  EXPECT_TRUE(m.contact_edge(500.0));  // a huge tolerance reaches the bottom from anywhere
  expect_error([&] { (void)world.touching(id, Edge::left, kNaN); },
               {"World::touching", "tolerance"});
}

TEST(WorldTouching, FreeFunctionMatchesTheBookForm) {
  // contactEdge: y > height - radius - 1.
  EXPECT_TRUE(calder::touches_edge(Edge::bottom, {0.0, 199.0001}, 40.0, 640.0, 240.0, 1.0));
  EXPECT_FALSE(calder::touches_edge(Edge::bottom, {0.0, 199.0}, 40.0, 640.0, 240.0, 1.0));
  EXPECT_TRUE(calder::touches_edge(Edge::right, {639.5, 0.0}, 0.0, 640.0, 240.0, 1.0));
  EXPECT_FALSE(calder::touches_edge(Edge::left, {1.0, 0.0}, 0.0, 640.0, 240.0, 1.0));
}

// ------------------------------------------------------------------- step ---

TEST(WorldStep, TimeAndStepCountAdvance) {
  World world({.dt = 0.5});
  world.add_body({});
  EXPECT_EQ(world.time(), 0.0);
  EXPECT_EQ(world.step_count(), 0);
  world.step();
  EXPECT_EQ(world.time(), 0.5);
  EXPECT_EQ(world.step_count(), 1);
  world.step(3);
  EXPECT_EQ(world.time(), 2.0);
  EXPECT_EQ(world.step_count(), 4);
  World empty;  // a world without bodies steps too
  empty.step(5);
  EXPECT_EQ(empty.time(), 5.0);
}

TEST(WorldStep, DtScalesTheVelocityAndPositionChange) {
  // Gravity (0, 0.5), dt = 0.25: v = 0.5 * 0.25 = 0.125, y = 0.125 * 0.25 = 0.03125.
  World world({.dt = 0.25});
  Mover m = world.add_mover({});
  world.add(calder::Gravity{.g = {0.0, 0.5}});
  world.step();
  EXPECT_EQ(m.velocity(), (Vec2{0.0, 0.125}));
  EXPECT_EQ(m.position(), (Vec2{0.0, 0.03125}));
  world.set_dt(1.0);
  world.step();
  EXPECT_EQ(m.velocity(), (Vec2{0.0, 0.625}));
  EXPECT_EQ(m.position(), (Vec2{0.0, 0.65625}));
  EXPECT_EQ(world.time(), 1.25);
}

TEST(WorldStep, SequentialOrderNeedsTheEulerIntegrator) {
  for (const Integrator integrator : {Integrator::velocity_verlet, Integrator::rk4}) {
    World world({.integrator = integrator, .update_order = UpdateOrder::sequential});
    world.add_body({.velocity = {1.0, 0.0}});
    expect_error([&] { world.step(); }, {"World::step", "sequential"});
    EXPECT_EQ(world.position(world.body(0)), (Vec2{0.0, 0.0}));
    EXPECT_EQ(world.step_count(), 0);
    // The same world runs once switched back to simultaneous.
    world.set_update_order(UpdateOrder::simultaneous);
    EXPECT_NO_THROW(world.step());
  }
  World euler({.update_order = UpdateOrder::sequential});
  euler.add_body({.velocity = {1.0, 0.0}});
  EXPECT_NO_THROW(euler.step());
  euler.set_integrator(Integrator::rk4);
  EXPECT_THROW(euler.step(), Error);
}

TEST(WorldStep, ConstantForceIntegratorsAgainstKinematics) {
  // Constant a = (0, 0.5), v0 = (1, 0), dt = 1, n = 10 steps.
  // Velocity Verlet and RK4 are exact for constant force: y = a n^2 / 2 = 25.
  // Semi-implicit Euler (the book): y = a n (n + 1) / 2 = 27.5.
  for (const Integrator integrator :
       {Integrator::semi_implicit_euler, Integrator::velocity_verlet, Integrator::rk4}) {
    World world({.integrator = integrator});
    Mover m = world.add_mover({.velocity = {1.0, 0.0}, .mass = 2.0});
    world.add(calder::Gravity{.g = {0.0, 0.5}, .scale_by_mass = true});  // a = 0.5
    world.step(10);
    const double expected_y = integrator == Integrator::semi_implicit_euler ? 27.5 : 25.0;
    const int which = static_cast<int>(integrator);
    EXPECT_NEAR(m.position().x, 10.0, 1e-12) << which;
    EXPECT_NEAR(m.position().y, expected_y, 1e-12) << which;
    EXPECT_NEAR(m.velocity().x, 1.0, 1e-14) << which;
    EXPECT_NEAR(m.velocity().y, 5.0, 1e-13) << which;
    EXPECT_EQ(m.acceleration(), (Vec2{0.0, 0.0}));
  }
}

TEST(WorldStep, SequentialWithoutInteractionEqualsSimultaneous) {
  World a;
  World b({.update_order = UpdateOrder::sequential});
  for (World* w : {&a, &b}) {
    w->add_body({.position = {10.0, 10.0}, .velocity = {1.5, 0.0}, .mass = 3.0});
    w->add_body({.position = {100.0, 50.0}, .velocity = {-0.5, 2.0}, .mass = 0.7});
    w->add(calder::Gravity{});
    w->add(calder::Drag{.c = 0.01});
    w->step(50);
  }
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(a.position(a.body(i)), b.position(b.body(i)));
    EXPECT_EQ(a.velocity(a.body(i)), b.velocity(b.body(i)));
  }
}

// ------------------------------------------------------- bodies and movers ---

TEST(WorldBodies, IdsAccessorsAndSetters) {
  World world;
  const BodyId a = world.add_body({.position = {1.0, 2.0}, .mass = 3.0, .radius = 4.0});
  const BodyId b = world.add_body({.friction = 0.25, .drag_area = 2.0});
  EXPECT_EQ(a.index, 0U);
  EXPECT_EQ(b.index, 1U);
  EXPECT_EQ(world.body_count(), 2U);
  EXPECT_EQ(world.body(1), b);
  EXPECT_EQ(world.mass(a), 3.0);
  EXPECT_EQ(world.radius(a), 4.0);
  EXPECT_FALSE(world.friction(a).has_value());
  EXPECT_EQ(world.friction(b), std::optional<double>(0.25));
  EXPECT_EQ(world.drag_area(a), 1.0);
  EXPECT_EQ(world.drag_area(b), 2.0);

  world.set_mass(a, 6.0);
  world.set_radius(a, 0.0);
  world.set_friction(a, 0.5);
  world.set_friction(b, std::nullopt);
  world.set_drag_area(b, 0.0);
  EXPECT_EQ(world.mass(a), 6.0);
  EXPECT_EQ(world.radius(a), 0.0);
  EXPECT_EQ(world.friction(a), std::optional<double>(0.5));
  EXPECT_FALSE(world.friction(b).has_value());
  EXPECT_EQ(world.drag_area(b), 0.0);

  // The new mass is what apply_force divides by.
  world.apply_force(a, {3.0, 0.0});
  EXPECT_EQ(world.acceleration(a), (Vec2{0.5, 0.0}));

  Mover m = world.mover(b);
  EXPECT_EQ(m.id(), b);
  EXPECT_EQ(&m.world(), &world);
  m.set_position({7.0, 8.0});
  m.set_velocity({-1.0, 0.5});
  EXPECT_EQ(world.position(b), (Vec2{7.0, 8.0}));
  EXPECT_EQ(world.velocity(b), (Vec2{-1.0, 0.5}));
  EXPECT_EQ(m.mass(), 1.0);

  // bodies(): the same state as contiguous arrays.
  const calder::BodyView view = world.bodies();
  ASSERT_EQ(view.size(), 2U);
  EXPECT_EQ(view.position(1), (Vec2{7.0, 8.0}));
  EXPECT_EQ(view.mass[0], 6.0);
  EXPECT_EQ(view.friction_or(0, 9.0), 0.5);
  EXPECT_EQ(view.friction_or(1, 9.0), 9.0);
}

TEST(WorldBodies, MoverAttractIsTheAttractionLaw) {
  World world;
  Mover a = world.add_mover({.position = {0.0, 0.0}, .mass = 10.0});
  Mover b = world.add_mover({.position = {0.0, 10.0}, .mass = 3.0});
  // a.attract(b): the force on b toward a, 10 * 3 / 100 = 0.3.
  const Vec2 f = a.attract(b);
  EXPECT_NEAR(f.y, -0.3, 1e-16);
  EXPECT_EQ(f.x, 0.0);
}

TEST(WorldBodies, OutOfRangeMessagesCountBodiesAndFieldsInTheRightNumber) {
  World world;
  expect_error([&] { (void)world.body(0); }, {"World::body", "(the world has 0 bodies)"});
  world.add_body({.position = {1.0, 1.0}});
  expect_error([&] { (void)world.body(1); }, {"World::body", "(the world has 1 body)"});
  expect_error([&] { (void)world.position(BodyId{3}); }, {"no body with id 3", "has 1 body)"});
  world.add_body({.position = {2.0, 2.0}});
  expect_error([&] { (void)world.body(2); }, {"(the world has 2 bodies)"});
  world.add(calder::Gravity{});
  expect_error([&] { (void)world.field(1); }, {"World::field", "(the world has 1 field)"});
  world.add(calder::Drag{});
  expect_error([&] { (void)world.field(5); }, {"(the world has 2 fields)"});
}

TEST(WorldBodies, ClearBodies) {
  World world;
  world.add_body({.position = {1.0, 1.0}});
  world.add_body({.position = {2.0, 2.0}});
  world.add(calder::Gravity{});
  world.clear_bodies();
  EXPECT_EQ(world.body_count(), 0U);
  EXPECT_THROW((void)world.position(BodyId{0}), Error);
  EXPECT_EQ(world.fields().size(), 1U);  // fields stay
  const BodyId again = world.add_body({.position = {5.0, 5.0}});
  EXPECT_EQ(again.index, 0U);
  EXPECT_EQ(world.position(again), (Vec2{5.0, 5.0}));
  EXPECT_EQ(world.acceleration(again), (Vec2{0.0, 0.0}));
  world.clear_fields();
  EXPECT_TRUE(world.fields().empty());
}

TEST(WorldBodies, CopyIsIndependentOfTheOriginal) {
  World original;
  const BodyId id = original.add_body({.position = {1.0, 2.0}, .velocity = {1.0, 0.0}});
  auto& gravity = original.add(calder::Gravity{.g = {0.0, 0.5}});
  original.apply_force(id, {2.0, 0.0});

  World copy = original;
  copy.step();
  EXPECT_EQ(copy.position(id), (Vec2{4.0, 2.5}));  // v = (3, 0.5)
  EXPECT_EQ(original.position(id), (Vec2{1.0, 2.0}));
  EXPECT_EQ(original.acceleration(id), (Vec2{2.0, 0.0}));
  EXPECT_EQ(original.step_count(), 0);

  // Changing the original's field or bodies leaves the copy alone.
  gravity.g = {0.0, 100.0};
  original.set_velocity(id, {0.0, 0.0});
  copy.step();
  EXPECT_EQ(copy.velocity(id), (Vec2{3.0, 1.0}));
  EXPECT_EQ(copy.position(id), (Vec2{7.0, 3.5}));
  original.step();
  EXPECT_EQ(original.velocity(id), (Vec2{2.0, 100.0}));
}

TEST(WorldBodies, CopiedGeneratorsAreIndependent) {
  World a({.seed = 9});
  World b = a;
  const double first = a.random().random();
  // b was not advanced by a's draw: it draws the same first value.
  EXPECT_EQ(b.random().random(), first);
  EXPECT_NE(a.random().random(), first);
  EXPECT_EQ(a.noise().noise(0.5), b.noise().noise(0.5));
}

// -------------------------------------------------------------- FixedStep ---

TEST(FixedStep, OneFrameAtSixtyStepsPerSecondIsOneStep) {
  World world;
  FixedStep fixed(60.0);
  EXPECT_EQ(fixed.advance(world, 1.0 / 60.0), 1);
  EXPECT_EQ(world.step_count(), 1);
  EXPECT_NEAR(fixed.alpha(), 0.0, 1e-12);
  EXPECT_EQ(fixed.steps_per_second(), 60.0);
}

TEST(FixedStep, AccumulatesFractionsOfAStep) {
  World world;
  FixedStep fixed(60.0);
  EXPECT_EQ(fixed.advance(world, 0.5 / 60.0), 0);
  EXPECT_NEAR(fixed.alpha(), 0.5, 1e-12);
  EXPECT_EQ(fixed.advance(world, 0.5 / 60.0), 1);
  EXPECT_NEAR(fixed.alpha(), 0.0, 1e-12);
  EXPECT_EQ(fixed.advance(world, 0.5 / 60.0), 0);
  EXPECT_NEAR(fixed.alpha(), 0.5, 1e-12);
  EXPECT_EQ(world.step_count(), 1);
  fixed.reset();
  EXPECT_EQ(fixed.alpha(), 0.0);
  EXPECT_EQ(fixed.advance(world, 0.0), 0);
}

TEST(FixedStep, MaxStepsCapsAndDropsTheBacklog) {
  World world;
  FixedStep fixed(60.0, 3);
  EXPECT_EQ(fixed.advance(world, 1.0), 3);  // 60 steps due, 3 run
  EXPECT_EQ(world.step_count(), 3);
  EXPECT_EQ(fixed.alpha(), 0.0);            // the rest is dropped
  EXPECT_EQ(fixed.advance(world, 0.0), 0);  // and not run later
  EXPECT_EQ(world.step_count(), 3);
  // Less than max_steps + 1 steps due: the fraction left over is kept.
  // 4 steps/s, 0.875 s = 3.5 steps: 3 run, alpha 0.5.
  FixedStep exact(4.0, 3);
  EXPECT_EQ(exact.advance(world, 0.875), 3);
  EXPECT_EQ(exact.alpha(), 0.5);
}

TEST(FixedStep, SetStepsPerSecond) {
  World world;
  FixedStep fixed(4.0);
  EXPECT_EQ(fixed.advance(world, 0.25), 1);
  fixed.set_steps_per_second(8.0);
  EXPECT_EQ(fixed.steps_per_second(), 8.0);
  EXPECT_EQ(fixed.advance(world, 0.25), 2);
  EXPECT_EQ(fixed.advance(world, 0.0625), 0);
  EXPECT_EQ(fixed.alpha(), 0.5);
}

TEST(FixedStep, InvalidArguments) {
  expect_error([] { FixedStep f(0.0); }, {"FixedStep", "steps_per_second"});
  expect_error([] { FixedStep f(-60.0); }, {"FixedStep", "steps_per_second"});
  expect_error([] { FixedStep f(kNaN); }, {"FixedStep", "steps_per_second"});
  expect_error([] { FixedStep f(60.0, 0); }, {"FixedStep", "max_steps"});
  World world;
  FixedStep fixed;
  expect_error([&] { fixed.advance(world, -0.1); }, {"FixedStep::advance", "elapsed_seconds"});
  expect_error([&] { fixed.advance(world, kNaN); }, {"FixedStep::advance", "elapsed_seconds"});
  expect_error([&] { fixed.set_steps_per_second(0.0); },
               {"FixedStep::set_steps_per_second", "steps_per_second"});
  EXPECT_EQ(fixed.steps_per_second(), 60.0);
  EXPECT_EQ(world.step_count(), 0);
}

TEST(FixedStep, UsesTheWorldsDtPerStep) {
  World world({.dt = 0.5});
  Mover m = world.add_mover({.velocity = {2.0, 0.0}});
  FixedStep fixed(4.0);
  EXPECT_EQ(fixed.advance(world, 0.5), 2);  // 2 steps of dt 0.5: x = 2
  EXPECT_EQ(m.position(), (Vec2{2.0, 0.0}));
  EXPECT_EQ(world.time(), 1.0);
}

// -------------------------------------------------------- trajectory output ---

std::uint64_t bits(double v) { return std::bit_cast<std::uint64_t>(v); }

TEST(FormatNumber, RoundTripsExactly) {
  const double values[] = {0.1,
                           1.0 / 3.0,
                           1e-300,
                           30.599999999999998,
                           -0.0,
                           0.0,
                           1e21,
                           1e-7,
                           123456789012345680.0,
                           std::numeric_limits<double>::denorm_min(),
                           std::numeric_limits<double>::max(),
                           -std::numeric_limits<double>::min(),
                           0.30000000000000004,
                           640.0,
                           -2.5};
  for (const double v : values) {
    const std::string s = calder::format_number(v);
    char* end = nullptr;
    const double back = std::strtod(s.c_str(), &end);
    EXPECT_EQ(*end, '\0') << s;
    EXPECT_EQ(bits(back), bits(v)) << s;
  }
}

TEST(FormatNumber, ShortestForm) {
  EXPECT_EQ(calder::format_number(0.1), "0.1");  // not 0.10000000000000001
  EXPECT_EQ(calder::format_number(1.0 / 3.0), "0.3333333333333333");
  EXPECT_EQ(calder::format_number(1e-300), "1e-300");
  EXPECT_EQ(calder::format_number(30.599999999999998), "30.599999999999998");
  EXPECT_EQ(calder::format_number(0.30000000000000004), "0.30000000000000004");
  EXPECT_EQ(calder::format_number(640.0), "640");
  EXPECT_EQ(calder::format_number(-2.5), "-2.5");
  EXPECT_EQ(calder::format_number(0.0), "0");
  EXPECT_EQ(calder::format_number(1e21), "1e+21");
  EXPECT_EQ(calder::format_number(kNaN), "nan");
  EXPECT_EQ(calder::format_number(kInf), "inf");
  EXPECT_EQ(calder::format_number(-kInf), "-inf");
  const std::string negative_zero = calder::format_number(-0.0);
  EXPECT_EQ(negative_zero.front(), '-');
  EXPECT_LE(negative_zero.size(), 4U);
}

TEST(TrajectoryWriter, HeaderThenOneRowPerBody) {
  World world;
  world.add_body({.position = {0.1, 30.599999999999998}, .velocity = {-0.0, 1e-300}});
  world.add_body({.position = {1.0 / 3.0, 1e21}, .velocity = {640.0, -2.5}});
  std::ostringstream out;
  calder::TrajectoryWriter writer(out);
  EXPECT_EQ(out.str(), "frame,body,x,y,vx,vy\n");
  writer.write(7, world);
  const std::string expected = "frame,body,x,y,vx,vy\n7,0,0.1,30.599999999999998," +
                               calder::format_number(-0.0) +
                               ",1e-300\n"
                               "7,1,0.3333333333333333,1e+21,640,-2.5\n";
  EXPECT_EQ(out.str(), expected);
  writer.write(8, world);
  // 1 header + 2 frames x 2 bodies.
  const std::string text = out.str();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 5);
  EXPECT_NE(text.find("\n8,1,0.3333333333333333,"), std::string::npos);
}

TEST(TrajectoryWriter, RowsReadBackToTheExactState) {
  World world;
  world.add(calder::Gravity{});
  world.add(calder::Drag{.c = 0.013});
  world.add_body({.position = {1.0, 2.0}, .velocity = {0.3, -0.7}, .mass = 1.7});
  world.step(37);
  std::ostringstream out;
  calder::TrajectoryWriter writer(out);
  writer.write(37, world);
  std::istringstream in(out.str());
  std::string line;
  std::getline(in, line);
  std::getline(in, line);
  std::vector<double> fields;
  std::size_t start = 0;
  while (start <= line.size()) {
    const std::size_t comma = std::min(line.find(',', start), line.size());
    fields.push_back(std::strtod(line.substr(start, comma - start).c_str(), nullptr));
    start = comma + 1;
  }
  ASSERT_EQ(fields.size(), 6U);
  const BodyId id = world.body(0);
  EXPECT_EQ(fields[0], 37.0);
  EXPECT_EQ(fields[1], 0.0);
  EXPECT_EQ(bits(fields[2]), bits(world.position(id).x));
  EXPECT_EQ(bits(fields[3]), bits(world.position(id).y));
  EXPECT_EQ(bits(fields[4]), bits(world.velocity(id).x));
  EXPECT_EQ(bits(fields[5]), bits(world.velocity(id).y));
}

// ------------------------------------------------------ add_bodies ---

TEST(WorldAddBodies, EqualsAddBodyOneByOneWithOneValueForAll) {
  const std::vector<double> x{1.0, 2.0, 3.0}, y{4.0, 5.0, 6.0}, mass{1.0, 2.0, 3.0};
  const std::vector<double> friction{0.3, std::numeric_limits<double>::quiet_NaN(), 0.1};
  const std::vector<double> vy{-1.0};  // one value for all
  World bulk;
  bulk.add_body({.position = {9.0, 9.0}});
  const BodyId first =
      bulk.add_bodies({.x = x, .y = y, .vy = vy, .mass = mass, .friction = friction});
  EXPECT_EQ(first.index, 1U);
  World single;
  single.add_body({.position = {9.0, 9.0}});
  for (std::size_t i = 0; i < x.size(); ++i) {
    single.add_body(
        {.position = {x[i], y[i]},
         .velocity = {0.0, -1.0},
         .mass = mass[i],
         .friction = std::isnan(friction[i]) ? std::nullopt : std::optional(friction[i])});
  }
  ASSERT_EQ(bulk.body_count(), 4U);
  for (std::size_t i = 0; i < 4; ++i) {
    const BodyId id = bulk.body(i);
    EXPECT_EQ(bulk.position(id), single.position(id));
    EXPECT_EQ(bulk.velocity(id), single.velocity(id));
    EXPECT_EQ(bulk.mass(id), single.mass(id));
    EXPECT_EQ(bulk.radius(id), single.radius(id));
    EXPECT_EQ(bulk.friction(id), single.friction(id));
    EXPECT_EQ(bulk.drag_area(id), single.drag_area(id));
  }
}

TEST(WorldAddBodies, AllOrNoneAndTheBadBodyNamed) {
  World world;
  world.add_body({});
  const std::vector<double> x{0.0, 1.0, 2.0}, mass{1.0, 1.0, -2.0}, short_column{1.0, 2.0};
  expect_error([&] { world.add_bodies({.x = x, .mass = mass}); },
               {"World::add_bodies: body 2", "mass"});
  expect_error([&] { world.add_bodies({.x = x, .y = short_column}); },
               {"World::add_bodies", "y has 2 values, expected 3"});
  EXPECT_EQ(world.body_count(), 1U);
  EXPECT_EQ(world.add_bodies({}).index, 1U);  // nothing to add
  EXPECT_EQ(world.body_count(), 1U);
}

}  // namespace
