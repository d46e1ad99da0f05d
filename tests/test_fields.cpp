// SPDX-License-Identifier: MIT
// Tests of the fields of calder/fields.hpp, each through World::step(): one
// step of a world holding just that field changes a body's velocity by the
// law's force (calder/forces.hpp, called directly) / mass * dt, the way
// apply_force and the book's update do it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <limits>
#include <optional>
#include <ostream>
#include <string>
#include <variant>
#include <vector>

#include "calder/error.hpp"
#include "calder/fields.hpp"
#include "calder/forces.hpp"
#include "calder/random.hpp"
#include "calder/vec2.hpp"
#include "calder/world.hpp"
#include "support/test_support.hpp"

namespace {

using calder::AttractionLaw;
using calder::BodyDef;
using calder::Edge;
using calder::Error;
using calder::Field;
using calder::Mover;
using calder::UpdateOrder;
using calder::Vec2;
using calder::World;
using calder::WorldDef;
using calder::test::expect_error;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kDt = 0.5;

// The book's update for one force from rest acceleration, dt: a = 0 + F / m,
// v += a dt, x += v dt.
struct State {
  Vec2 position;
  Vec2 velocity;
};
State expected_after(const BodyDef& body, Vec2 force, double dt) {
  State s{body.position, body.velocity};
  s.velocity.x += (0.0 + force.x / body.mass) * dt;
  s.velocity.y += (0.0 + force.y / body.mass) * dt;
  s.position.x += s.velocity.x * dt;
  s.position.y += s.velocity.y * dt;
  return s;
}

// Steps a world holding one body and `field` once; checks the body against
// the force `force` (computed by the caller from the law). Then checks that
// the same field, disabled, does nothing.
template <class F>
void check_field(F field, const BodyDef& body, Vec2 force, WorldDef def = {.dt = kDt}) {
  ASSERT_NE(force, (Vec2{0.0, 0.0})) << "a zero force would prove nothing";
  {
    World world(def);
    Mover m = world.add_mover(body);
    world.add(field);
    world.step();
    const State want = expected_after(body, force, def.dt);
    EXPECT_EQ(m.velocity(), want.velocity) << calder::field_name(Field{field});
    EXPECT_EQ(m.position(), want.position) << calder::field_name(Field{field});
    EXPECT_EQ(m.acceleration(), (Vec2{0.0, 0.0}));
  }
  {
    field.enabled = false;
    World world(def);
    Mover m = world.add_mover(body);
    world.add(field);
    world.step();
    const State want = expected_after(body, {0.0, 0.0}, def.dt);
    EXPECT_EQ(m.velocity(), body.velocity) << "disabled " << calder::field_name(Field{field});
    EXPECT_EQ(m.position(), want.position) << "disabled " << calder::field_name(Field{field});
  }
}

// A body away from every edge, moving, with a mass that is not a power of two.
const BodyDef kBody{
    .position = {300.0, 100.0}, .velocity = {1.5, -0.75}, .mass = 2.5, .radius = 10.0};

// --------------------------------------------------------- each field alone ---

TEST(FieldStep, Gravity) {
  check_field(calder::Gravity{.g = {0.0, 0.1}}, kBody, calder::gravity({0.0, 0.1}, 2.5, false));
  check_field(calder::Gravity{.g = {0.0, 0.1}, .scale_by_mass = true}, kBody,
              calder::gravity({0.0, 0.1}, 2.5, true));
  check_field(calder::Gravity{.g = {0.03, -0.2}}, kBody, Vec2{0.03, -0.2});
}

TEST(FieldStep, GravityScaledByMassGivesEveryMassTheSameFall) {
  World world;
  world.add(calder::Gravity{.g = {0.0, 0.5}, .scale_by_mass = true});
  Mover light = world.add_mover({.mass = 0.5});
  Mover heavy = world.add_mover({.mass = 8.0});
  world.step(4);
  EXPECT_EQ(light.velocity(), (Vec2{0.0, 2.0}));
  EXPECT_EQ(heavy.velocity(), (Vec2{0.0, 2.0}));
}

TEST(FieldStep, Wind) { check_field(calder::Wind{.force = {0.1, 0.0}}, kBody, Vec2{0.1, 0.0}); }

TEST(FieldStep, Helium) { check_field(calder::Helium{.lift = 0.3}, kBody, calder::helium(0.3)); }

TEST(FieldStep, Fan) {
  const calder::Fan fan{.position = {250.0, 80.0}, .strength = 2.0, .reach = 120.0};
  check_field(fan, kBody, calder::fan(fan.position, kBody.position, 2.0, 120.0));
  // Out of reach: no force.
  World world;
  Mover m = world.add_mover({.position = {600.0, 200.0}});
  world.add(fan);
  world.step();
  EXPECT_EQ(m.velocity(), (Vec2{0.0, 0.0}));
}

TEST(FieldStep, EdgeForceUsesTheWorldsSize) {
  // A 400 x 300 world; the body is 20 from the right edge and 30 from the bottom.
  const WorldDef def{.width = 400.0, .height = 300.0, .dt = kDt};
  const BodyDef body{.position = {380.0, 270.0}, .velocity = {1.0, 1.0}, .mass = 2.5};
  const calder::EdgeForce field{.strength = 1.5, .margin = 50.0};
  const Vec2 force = calder::edge_force(body.position, 400.0, 300.0, 1.5, 50.0);
  EXPECT_NEAR(force.x, -1.5 * 30.0 / 50.0, 1e-15);  // pushed left and up
  EXPECT_NEAR(force.y, -1.5 * 20.0 / 50.0, 1e-15);
  check_field(field, body, force, def);
}

TEST(FieldStep, NoiseWindUsesTheWorldsNoiseAtTheWorldsTime) {
  // Seed 7; after 3 steps of 0.5 the 4th step is at time 1.5.
  const calder::NoiseWind field{.strength = 0.4, .rate = 0.37, .offset = 2.0};
  World world({.dt = kDt, .seed = 7});
  Mover m = world.add_mover(kBody);
  world.add(field);
  world.step(3);
  ASSERT_EQ(world.time(), 1.5);
  const BodyDef now{.position = m.position(), .velocity = m.velocity(), .mass = 2.5};
  world.step();
  // An independent noise with the world's seed gives the same force.
  const calder::Noise noise(7);
  const Vec2 force = calder::noise_wind(noise, 1.5, 0.4, 0.37, 2.0);
  ASSERT_NE(force.x, 0.0);
  const State want = expected_after(now, force, kDt);
  EXPECT_EQ(m.velocity(), want.velocity);
  EXPECT_EQ(m.position(), want.position);
  // The field reads world.noise(): reseeding it changes the wind.
  world.noise().noise_seed(99);
  const BodyDef then{.position = m.position(), .velocity = m.velocity(), .mass = 2.5};
  world.step();
  const Vec2 reseeded = calder::noise_wind(calder::Noise(99), 2.0, 0.4, 0.37, 2.0);
  EXPECT_EQ(m.velocity(), expected_after(then, reseeded, kDt).velocity);
  // And disabled it does nothing.
  check_field(field, kBody, calder::noise_wind(calder::Noise(0), 0.0, 0.4, 0.37, 2.0));
}

TEST(FieldStep, NoiseWindChangesOverTime) {
  World world({.seed = 3});
  Mover m = world.add_mover({});
  world.add(calder::NoiseWind{.strength = 1.0, .rate = 0.1});
  std::vector<double> dv;
  double previous = 0.0;
  for (int k = 0; k < 50; ++k) {
    world.step();
    dv.push_back(m.velocity().x - previous);
    previous = m.velocity().x;
  }
  double lo = dv[0];
  double hi = dv[0];
  for (const double d : dv) {
    lo = std::min(lo, d);
    hi = std::max(hi, d);
    EXPECT_LE(std::abs(d), 1.0 + 1e-15);
  }
  EXPECT_GT(hi - lo, 0.05);  // not one constant wind
}

TEST(FieldStep, FrictionOnContactOnly) {
  // Bottom contact: y > 240 - r - 1 = 229 with r = 10.
  const calder::Friction field{.mu = 0.1};
  BodyDef touching = kBody;
  touching.position = {300.0, 229.5};
  check_field(field, touching, calder::friction(kBody.velocity, 0.1, 1.0));
  // Just above contact: nothing.
  World world({.dt = kDt});
  BodyDef above = kBody;
  above.position = {300.0, 229.0};
  Mover m = world.add_mover(above);
  world.add(field);
  world.step();
  EXPECT_EQ(m.velocity(), kBody.velocity);
}

TEST(FieldStep, FrictionNormalSurfaceAndTolerance) {
  // Left wall, tolerance 5, normal 2: x < r + 5 = 15.
  const calder::Friction field{.mu = 0.1, .normal = 2.0, .surface = Edge::left, .tolerance = 5.0};
  BodyDef body = kBody;
  body.position = {14.0, 120.0};
  check_field(field, body, calder::friction(kBody.velocity, 0.1, 2.0));
  body.position = {16.0, 120.0};
  World world({.dt = kDt});
  Mover m = world.add_mover(body);
  world.add(field);
  world.step();
  EXPECT_EQ(m.velocity(), kBody.velocity);
}

TEST(FieldStep, FrictionPerBodyCoefficientOverridesMu) {
  World world({.dt = kDt});
  world.add(calder::Friction{.mu = 0.1});
  const Vec2 v{2.0, 0.0};
  const BodyDef plain{.position = {100.0, 239.5}, .velocity = v, .mass = 2.5};
  BodyDef rough = plain;
  rough.friction = 0.3;
  BodyDef ice = plain;
  ice.friction = 0.0;
  Mover a = world.add_mover(plain);
  Mover b = world.add_mover(rough);
  Mover c = world.add_mover(ice);
  world.step();
  EXPECT_EQ(a.velocity(), expected_after(plain, calder::friction(v, 0.1), kDt).velocity);
  EXPECT_EQ(b.velocity(), expected_after(rough, calder::friction(v, 0.3), kDt).velocity);
  EXPECT_EQ(c.velocity(), v);  // its own coefficient 0 wins over the field's 0.1
  // Friction slows, it does not push: all speeds went down or stayed.
  EXPECT_LT(b.velocity().x, a.velocity().x);
  EXPECT_LT(a.velocity().x, v.x);
  // set_friction(nullopt) goes back to the field's mu.
  world.set_friction(b.id(), std::nullopt);
  const BodyDef b_now{.position = b.position(), .velocity = b.velocity(), .mass = 2.5};
  world.step();
  EXPECT_EQ(b.velocity(),
            expected_after(b_now, calder::friction(b_now.velocity, 0.1), kDt).velocity);
}

TEST(FieldStep, LiquidDragInside) {
  const calder::Liquid field{.region = {0.0, 120.0, 640.0, 120.0}, .c = 0.1};
  BodyDef inside = kBody;
  inside.position = {300.0, 150.0};
  check_field(field, inside, calder::drag(kBody.velocity, 0.1, 1.0));
  // calculate_drag is the same law.
  EXPECT_EQ(field.calculate_drag(kBody.velocity), calder::drag(kBody.velocity, 0.1, 1.0));
}

TEST(FieldStep, LiquidActsOnlyStrictlyInside) {
  const calder::Liquid field{.region = {10.0, 120.0, 600.0, 100.0}, .c = 0.1};
  // On the region's border (x = 10, x = 610, y = 120, y = 220) and outside: nothing.
  const Vec2 outside[] = {{300.0, 120.0}, {300.0, 220.0}, {10.0, 150.0},
                          {610.0, 150.0}, {300.0, 100.0}, {300.0, 230.0}};
  for (const Vec2 p : outside) {
    World world({.dt = kDt});
    Mover m = world.add_mover({.position = p, .velocity = {1.0, 2.0}});
    world.add(field);
    world.step();
    EXPECT_EQ(m.velocity(), (Vec2{1.0, 2.0})) << p.x << ", " << p.y;
  }
  World world({.dt = kDt});
  Mover m = world.add_mover({.position = {300.0, 120.5}, .velocity = {1.0, 2.0}});
  world.add(field);
  world.step();
  EXPECT_LT(m.velocity().y, 2.0);  // just inside: slowed
}

TEST(FieldStep, LiquidNeverReverse) {
  // A strong liquid: drag 5 * |v|^2 on a light body would reverse it in one step.
  const calder::Liquid field{.region = {0.0, 0.0, 640.0, 240.0}, .c = 5.0, .never_reverse = true};
  const BodyDef body{.position = {300.0, 100.0}, .velocity = {3.0, 4.0}, .mass = 0.5};
  const Vec2 raw = calder::drag(body.velocity, 5.0, 1.0);
  const Vec2 limited = calder::limit_drag(raw, body.velocity, 0.5, kDt);
  ASSERT_LT(limited.mag(), raw.mag());
  check_field(field, body, limited);
  World world({.dt = kDt});
  Mover m = world.add_mover(body);
  world.add(field);
  world.step();
  EXPECT_GE(m.velocity().dot(body.velocity), -1e-12);
}

TEST(FieldStep, Drag) {
  check_field(calder::Drag{.c = 0.02}, kBody, calder::drag(kBody.velocity, 0.02, 1.0));
  const BodyDef fast{.position = {300.0, 100.0}, .velocity = {30.0, 40.0}, .mass = 0.5};
  check_field(calder::Drag{.c = 1.0, .never_reverse = true}, fast,
              calder::limit_drag(calder::drag(fast.velocity, 1.0, 1.0), fast.velocity, 0.5, kDt));
}

TEST(FieldStep, DragAreaScalesLiquidAndDrag) {
  BodyDef wide = kBody;
  wide.position = {300.0, 150.0};
  wide.drag_area = 2.0;
  const Vec2 f2 = calder::drag(kBody.velocity, 0.1, 2.0);
  const Vec2 f1 = calder::drag(kBody.velocity, 0.1, 1.0);
  EXPECT_NEAR(f2.x, 2.0 * f1.x, 1e-15);
  EXPECT_NEAR(f2.y, 2.0 * f1.y, 1e-15);
  check_field(calder::Liquid{.region = {0.0, 120.0, 640.0, 120.0}, .c = 0.1}, wide, f2);
  check_field(calder::Drag{.c = 0.1}, wide, f2);
  // set_drag_area changes it later.
  World world({.dt = kDt});
  Mover m = world.add_mover(kBody);
  world.add(calder::Drag{.c = 0.1});
  world.set_drag_area(m.id(), 0.0);
  world.step();
  EXPECT_EQ(m.velocity(), kBody.velocity);
}

TEST(FieldStep, Lift) {
  check_field(calder::Lift{.coefficient = 0.05}, kBody, calder::lift(kBody.velocity, 0.05));
}

TEST(FieldStep, Attractor) {
  const calder::Attractor field{.position = {320.0, 120.0}, .mass = 20.0, .law = {}};
  const Vec2 force = calder::attraction({320.0, 120.0}, 20.0, kBody.position, 2.5, field.law);
  EXPECT_EQ(field.attract(kBody.position, 2.5), force);
  check_field(field, kBody, force);
}

TEST(FieldStep, AttractorPullsAndCanBeDragged) {
  World world;
  Mover m = world.add_mover({.position = {100.0, 120.0}, .mass = 2.0});
  auto& attractor = world.add(calder::Attractor{.position = {320.0, 120.0}, .mass = 20.0});
  world.step(5);
  EXPECT_GT(m.position().x, 100.0);  // toward the attractor (+x)
  EXPECT_EQ(m.position().y, 120.0);
  // Drag the attractor below the body: the next pull is downward.
  const BodyDef now{.position = m.position(), .velocity = m.velocity(), .mass = 2.0};
  attractor.position = {now.position.x, 200.0};
  world.step();
  const Vec2 force =
      calder::attraction({now.position.x, 200.0}, 20.0, now.position, 2.0, AttractionLaw{});
  EXPECT_GT(force.y, 0.0);
  EXPECT_EQ(m.velocity(), expected_after(now, force, 1.0).velocity);
  // A negative G repels.
  World repel;
  Mover r = repel.add_mover({.position = {300.0, 120.0}});
  repel.add(calder::Attractor{.position = {320.0, 120.0}, .law = AttractionLaw::book(-1.0)});
  repel.step();
  EXPECT_LT(r.velocity().x, 0.0);
}

TEST(FieldStep, CustomForceSeesTheContext) {
  const WorldDef def{.width = 500.0, .height = 400.0, .dt = kDt, .seed = 4};
  World world(def);
  Mover m = world.add_mover(kBody);
  world.step(2);  // time 1
  double seen_time = -1.0;
  double seen_dt = -1.0;
  double seen_width = -1.0;
  double seen_height = -1.0;
  bool seen_noise = false;
  std::size_t seen_count = 0;
  world.add(calder::CustomForce{.force = [&](const calder::FieldContext& c, std::size_t i) {
    seen_time = c.time;
    seen_dt = c.dt;
    seen_width = c.width;
    seen_height = c.height;
    seen_noise = c.noise != nullptr;
    seen_count = c.bodies.size();
    // A spring toward x = 250, reading the body's position.
    return Vec2{(250.0 - c.bodies.x[i]) * 0.01, 0.0};
  }});
  const BodyDef now{.position = m.position(), .velocity = m.velocity(), .mass = 2.5};
  world.step();
  EXPECT_EQ(seen_time, 1.0);
  EXPECT_EQ(seen_dt, kDt);
  EXPECT_EQ(seen_width, 500.0);
  EXPECT_EQ(seen_height, 400.0);
  EXPECT_TRUE(seen_noise);
  EXPECT_EQ(seen_count, 1U);
  EXPECT_EQ(m.velocity(),
            expected_after(now, {(250.0 - now.position.x) * 0.01, 0.0}, kDt).velocity);
  check_field(calder::CustomForce{.force =
                                      [](const calder::FieldContext&, std::size_t) {
                                        return Vec2{0.25, -0.5};
                                      }},
              kBody, Vec2{0.25, -0.5});
}

// -------------------------------------------------- several fields together ---

TEST(FieldStep, FieldsAccumulateLikeApplyForceInTheOrderAdded) {
  // Gravity then wind on mass 3: a = (0 + g/m) + w/m, exactly as two apply_force calls.
  const Vec2 g{0.2, 0.1};
  const Vec2 w{0.4, -0.3};
  World fields;
  Mover a = fields.add_mover({.mass = 3.0});
  fields.add(calder::Gravity{.g = g});
  fields.add(calder::Wind{.force = w});
  World by_hand;
  Mover b = by_hand.add_mover({.mass = 3.0});
  double vx = 0.0;  // by hand: v += ((0 + g/m) + w/m) dt each step
  for (int k = 0; k < 20; ++k) {
    vx += ((0.0 + 0.2 / 3.0) + 0.4 / 3.0) * 1.0;
    fields.step();
    b.apply_force(g);
    b.apply_force(w);
    b.update();
    ASSERT_EQ(a.velocity(), b.velocity()) << "step " << k;
    ASSERT_EQ(a.position(), b.position()) << "step " << k;
  }
  EXPECT_EQ(a.velocity().x, vx);
}

TEST(FieldStep, FieldOrderChangesOnlyTheLastBits) {
  World ab;
  World ba;
  const calder::Gravity gravity{.g = {0.0, 0.1}};
  const calder::Wind wind{.force = {0.03, 0.0}};
  const calder::Drag drag{.c = 0.01};
  const calder::Lift lift{.coefficient = 0.003};
  ab.add(gravity);
  ab.add(wind);
  ab.add(drag);
  ab.add(lift);
  ba.add(lift);
  ba.add(drag);
  ba.add(wind);
  ba.add(gravity);
  for (World* w : {&ab, &ba}) {
    w->add_body({.position = {10.0, 10.0}, .velocity = {2.0, -1.0}, .mass = 1.7});
    w->add_body({.position = {300.0, 50.0}, .velocity = {-0.3, 0.0}, .mass = 0.3});
    w->step(200);
  }
  for (std::size_t i = 0; i < 2; ++i) {
    const Vec2 p = ab.position(ab.body(i));
    const Vec2 q = ba.position(ba.body(i));
    EXPECT_NEAR(p.x, q.x, 1e-9 * std::max(1.0, std::abs(p.x)));
    EXPECT_NEAR(p.y, q.y, 1e-9 * std::max(1.0, std::abs(p.y)));
    const Vec2 u = ab.velocity(ab.body(i));
    const Vec2 v = ba.velocity(ba.body(i));
    EXPECT_NEAR(u.x, v.x, 1e-12);
    EXPECT_NEAR(u.y, v.y, 1e-12);
  }
}

// ------------------------------------------------------- mutual attraction ---

TEST(MutualAttraction, PairForceIsAppliedAsPlusAndMinus) {
  // Two bodies: +F on body 1 (toward 0), -F on body 0.
  const AttractionLaw law = AttractionLaw::book(1.0, 5.0, 25.0);
  const BodyDef a{.position = {320.0, 40.0}, .velocity = {1.0, 0.0}, .mass = 8.0};
  const BodyDef b{.position = {330.0, 60.0}, .velocity = {-1.0, 0.0}, .mass = 3.0};
  World world({.dt = kDt});
  Mover ma = world.add_mover(a);
  Mover mb = world.add_mover(b);
  world.add(calder::MutualAttraction{.law = law});
  world.step();
  const Vec2 on_b = calder::attraction(a.position, 8.0, b.position, 3.0, law);
  EXPECT_EQ(mb.velocity(), expected_after(b, on_b, kDt).velocity);
  EXPECT_EQ(ma.velocity(), expected_after(a, -on_b, kDt).velocity);
  EXPECT_EQ(mb.position(), expected_after(b, on_b, kDt).position);
}

TEST(MutualAttraction, SimultaneousConservesMomentum) {
  // Masses that are powers of two make m * (F / m) exact; with two bodies the
  // momentum change is then exactly F - F = 0.
  {
    World world;
    Mover a = world.add_mover({.position = {100.0, 100.0}, .mass = 4.0});
    Mover b = world.add_mover({.position = {110.0, 95.0}, .mass = 0.5});
    world.add(calder::MutualAttraction{});
    world.step();
    EXPECT_EQ(4.0 * a.velocity().x + 0.5 * b.velocity().x, 0.0);
    EXPECT_EQ(4.0 * a.velocity().y + 0.5 * b.velocity().y, 0.0);
  }
  // Many bodies of any mass: zero up to rounding over many steps.
  World world;
  calder::Random rng(2);
  for (int i = 0; i < 8; ++i) {
    const double x = rng.random(640.0);
    const double y = rng.random(240.0);
    world.add_body({.position = {x, y}, .mass = rng.random(0.1, 2.0)});
  }
  world.add(calder::MutualAttraction{});
  double scale = 0.0;
  for (int k = 0; k < 100; ++k) {
    world.step();
    double px = 0.0;
    double py = 0.0;
    const calder::BodyView v = world.bodies();
    for (std::size_t i = 0; i < v.size(); ++i) {
      px += v.mass[i] * v.vx[i];
      py += v.mass[i] * v.vy[i];
      scale = std::max(scale, v.mass[i] * std::abs(v.vx[i]) + v.mass[i] * std::abs(v.vy[i]));
    }
    ASSERT_GT(scale, 0.0);
    EXPECT_NEAR(px, 0.0, 1e-13 * scale) << "step " << k;
    EXPECT_NEAR(py, 0.0, 1e-13 * scale) << "step " << k;
  }
}

// Ten bodies from randomSeed(1), drawn as example 2.9 draws them:
// x = random(640), y = random(240), mass = random(0.1, 2) per body.
void add_bodies_of_example_2_9(World& world) {
  calder::Random rng(1);
  for (int i = 0; i < 10; ++i) {
    const double x = rng.random(640.0);
    const double y = rng.random(240.0);
    const double mass = rng.random(0.1, 2.0);
    world.add_body({.position = {x, y}, .mass = mass});
  }
}

TEST(MutualAttraction, SequentialOrderIsTheBooksExample29Loop) {
  const AttractionLaw law = AttractionLaw::book(1.0, 5.0, 25.0);  // (G * M) * m, as 2.9
  World fields({.update_order = UpdateOrder::sequential});
  add_bodies_of_example_2_9(fields);
  fields.add(calder::MutualAttraction{.law = law});
  World book;
  add_bodies_of_example_2_9(book);
  std::vector<Mover> movers;
  for (std::size_t i = 0; i < book.body_count(); ++i) movers.push_back(book.mover(book.body(i)));

  for (int step = 1; step <= 100; ++step) {
    fields.step();
    // The book: for i { for j != i { force = movers[j].attract(movers[i]);
    // movers[i].applyForce(force); } movers[i].update(); }
    for (std::size_t i = 0; i < movers.size(); ++i) {
      for (std::size_t j = 0; j < movers.size(); ++j) {
        if (i == j) continue;
        const Vec2 force = calder::attraction(movers[j].position(), movers[j].mass(),
                                              movers[i].position(), movers[i].mass(), law);
        movers[i].apply_force(force);
      }
      movers[i].update();
    }
    for (std::size_t i = 0; i < movers.size(); ++i) {
      ASSERT_EQ(fields.position(fields.body(i)), movers[i].position())
          << "body " << i << ", step " << step;
      ASSERT_EQ(fields.velocity(fields.body(i)), movers[i].velocity())
          << "body " << i << ", step " << step;
    }
  }
}

TEST(MutualAttraction, SimultaneousIsAllForcesFromOneStateThenAllUpdates) {
  // With G = 1 the pairwise +F / -F form gives the same bits as each body
  // summing the forces of the others in index order: (1 * M) * m commutes,
  // and the source - target difference flips sign exactly.
  const AttractionLaw law = AttractionLaw::book(1.0, 5.0, 25.0);
  World fields;
  add_bodies_of_example_2_9(fields);
  fields.add(calder::MutualAttraction{.law = law});
  World book;
  add_bodies_of_example_2_9(book);
  std::vector<Mover> movers;
  for (std::size_t i = 0; i < book.body_count(); ++i) movers.push_back(book.mover(book.body(i)));
  World sequential({.update_order = UpdateOrder::sequential});
  add_bodies_of_example_2_9(sequential);
  sequential.add(calder::MutualAttraction{.law = law});

  for (int step = 1; step <= 100; ++step) {
    fields.step();
    sequential.step();
    for (std::size_t i = 0; i < movers.size(); ++i) {
      for (std::size_t j = 0; j < movers.size(); ++j) {
        if (i == j) continue;
        movers[i].apply_force(calder::attraction(movers[j].position(), movers[j].mass(),
                                                 movers[i].position(), movers[i].mass(), law));
      }
    }
    for (Mover& m : movers) m.update();
    for (std::size_t i = 0; i < movers.size(); ++i) {
      ASSERT_EQ(fields.position(fields.body(i)), movers[i].position())
          << "body " << i << ", step " << step;
      ASSERT_EQ(fields.velocity(fields.body(i)), movers[i].velocity())
          << "body " << i << ", step " << step;
    }
  }
  // The two orders are different simulations.
  EXPECT_NE(fields.position(fields.body(9)), sequential.position(sequential.body(9)));
}

TEST(MutualAttraction, DisabledDoesNothing) {
  World world;
  world.add_body({.position = {100.0, 100.0}});
  world.add_body({.position = {110.0, 100.0}});
  world.add(calder::MutualAttraction{.enabled = false});
  world.step();
  EXPECT_EQ(world.velocity(world.body(0)), (Vec2{0.0, 0.0}));
  EXPECT_EQ(world.velocity(world.body(1)), (Vec2{0.0, 0.0}));
}

// --------------------------------------------------- validation and names ---

struct BadField {
  Field field;
  const char* name;
  const char* parameter;
};

TEST(FieldValidation, RejectsABadParameterOfEachField) {
  const BadField cases[] = {
      {calder::Gravity{.g = {0.0, kNaN}}, "gravity", "g"},
      {calder::Wind{.force = {kInf, 0.0}}, "wind", "force"},
      {calder::NoiseWind{.rate = kNaN}, "noise_wind", "rate"},
      {calder::Helium{.lift = kNaN}, "helium", "lift"},
      {calder::Fan{.reach = 0.0}, "fan", "reach"},
      {calder::EdgeForce{.margin = -1.0}, "edge_force", "margin"},
      {calder::Friction{.mu = -0.1}, "friction", "mu"},
      {calder::Liquid{.region = {0.0, 0.0, -1.0, 10.0}}, "liquid", "region.w"},
      {calder::Drag{.c = -0.01}, "drag", "c"},
      {calder::Lift{.coefficient = kInf}, "lift", "coefficient"},
      {calder::Attractor{.mass = 0.0}, "attractor", "mass"},
      {calder::MutualAttraction{.law = AttractionLaw::book(1.0, 30.0, 25.0)}, "mutual_attraction",
       "min"},
      {calder::CustomForce{}, "custom_force", "force"},
  };
  ASSERT_EQ(std::size(cases), std::variant_size_v<Field>);  // one per field type
  for (const BadField& c : cases) {
    SCOPED_TRACE(c.name);
    expect_error([&] { calder::validate(c.field); }, {c.name, c.parameter});
    // world.add rejects it too, and keeps nothing.
    World world;
    expect_error([&] { std::visit([&](const auto& f) { world.add(f); }, c.field); },
                 {c.name, c.parameter});
    EXPECT_TRUE(world.fields().empty());
  }
}

TEST(FieldValidation, AcceptsTheDefaults) {
  for (const Field& f :
       {Field{calder::Gravity{}}, Field{calder::Wind{}}, Field{calder::NoiseWind{}},
        Field{calder::Helium{}}, Field{calder::Fan{}}, Field{calder::EdgeForce{}},
        Field{calder::Friction{}}, Field{calder::Liquid{}}, Field{calder::Drag{}},
        Field{calder::Lift{}}, Field{calder::Attractor{}}, Field{calder::MutualAttraction{}}}) {
    EXPECT_NO_THROW(calder::validate(f)) << calder::field_name(f);
  }
}

TEST(FieldValidation, MutatedFieldIsCaughtByStep) {
  World world;
  Mover m = world.add_mover({.velocity = {1.0, 0.0}});
  auto& attractor = world.add(calder::Attractor{});
  attractor.law.G = kNaN;
  expect_error([&] { world.step(); }, {"attractor", "G"});
  EXPECT_EQ(m.position(), (Vec2{0.0, 0.0}));
  EXPECT_EQ(world.step_count(), 0);
}

TEST(FieldNames, EveryField) {
  EXPECT_STREQ(calder::field_name(calder::Gravity{}), "gravity");
  EXPECT_STREQ(calder::field_name(calder::Wind{}), "wind");
  EXPECT_STREQ(calder::field_name(calder::NoiseWind{}), "noise_wind");
  EXPECT_STREQ(calder::field_name(calder::Helium{}), "helium");
  EXPECT_STREQ(calder::field_name(calder::Fan{}), "fan");
  EXPECT_STREQ(calder::field_name(calder::EdgeForce{}), "edge_force");
  EXPECT_STREQ(calder::field_name(calder::Friction{}), "friction");
  EXPECT_STREQ(calder::field_name(calder::Liquid{}), "liquid");
  EXPECT_STREQ(calder::field_name(calder::Drag{}), "drag");
  EXPECT_STREQ(calder::field_name(calder::Lift{}), "lift");
  EXPECT_STREQ(calder::field_name(calder::Attractor{}), "attractor");
  EXPECT_STREQ(calder::field_name(calder::MutualAttraction{}), "mutual_attraction");
  EXPECT_STREQ(calder::field_name(calder::CustomForce{}), "custom_force");
}

TEST(Rect, ContainsIsStrict) {
  const calder::Rect r{0.0, 120.0, 640.0, 120.0};
  EXPECT_TRUE(r.contains({1.0, 121.0}));
  EXPECT_FALSE(r.contains({0.0, 121.0}));
  EXPECT_FALSE(r.contains({640.0, 121.0}));
  EXPECT_FALSE(r.contains({1.0, 120.0}));
  EXPECT_FALSE(r.contains({1.0, 240.0}));
}

}  // namespace
