// SPDX-License-Identifier: MIT
// Scenes and Simulation: generation in the book's draw order, the mouse's
// events, bindings, validation, and the built-in scenes.
#include <gtest/gtest.h>

#include <calder/calder.hpp>
#include <cmath>
#include <set>
#include <string>
#include <variant>

#include "support/test_support.hpp"

namespace {

using calder::BodyGroup;
using calder::Draw;
using calder::InputState;
using calder::Scene;
using calder::Simulation;
using calder::Vec2;

Scene empty_scene() {
  Scene s;
  s.name = "test";
  return s;
}

TEST(SceneGeneration, GridDrawsXThenYThenMassPerBodyLikeNewMover) {
  // p5: new Mover(random(width), random(height), random(0.5, 3)) draws x, y,
  // mass for mover 0, then for mover 1, ... from one generator.
  Scene s = empty_scene();
  BodyGroup g;
  g.count = 3;
  g.x = Draw::uniform(0.0, 640.0);
  g.y = Draw::uniform(0.0, 240.0);
  g.mass = Draw::uniform(0.5, 3.0);
  g.vx = Draw::fixed(1.0);
  s.bodies.push_back(g);
  Simulation sim(s, 7u);
  calder::Random rng(7);
  for (std::size_t i = 0; i < 3; ++i) {
    const double x = rng.random() * 640.0;  // random(0, 640) = draw * 640 + 0
    const double y = rng.random() * 240.0;
    const double m = rng.random() * (3.0 - 0.5) + 0.5;
    const calder::BodyId id = sim.world().body(i);
    EXPECT_EQ(sim.world().position(id), (Vec2{x, y}));
    EXPECT_EQ(sim.world().mass(id), m);
    EXPECT_EQ(sim.world().velocity(id), (Vec2{1.0, 0.0}));
  }
}

TEST(SceneGeneration, LinearPlacesStartPlusIndexTimesStep) {
  Scene s = empty_scene();
  BodyGroup g;
  g.count = 9;
  g.x = Draw::linear(40.0, 70.0);  // example 2.5: 40 + i * 70
  g.radius = {calder::RadiusRule::Kind::per_mass, 8.0};
  g.mass = Draw::fixed(2.0);
  s.bodies.push_back(g);
  Simulation sim(s);
  for (std::size_t i = 0; i < 9; ++i) {
    EXPECT_EQ(sim.world().position(sim.world().body(i)).x, 40.0 + static_cast<double>(i) * 70.0);
    EXPECT_EQ(sim.world().radius(sim.world().body(i)), 16.0);
  }
}

TEST(SceneGeneration, OrbitLayoutIsPerpendicularAtTheDrawnDistanceAndSpeed) {
  Scene s = empty_scene();
  BodyGroup g;
  g.layout = BodyGroup::Layout::orbit;
  g.count = 20;
  g.center = {5.0, -3.0};
  g.distance = Draw::uniform(100.0, 150.0);
  g.speed = Draw::uniform(10.0, 15.0);
  g.mass = Draw::uniform(10.0, 15.0);
  g.radius = {calder::RadiusRule::Kind::per_sqrt_mass, 1.0};
  s.bodies.push_back(g);
  Simulation sim(s, 1u);
  for (std::size_t i = 0; i < 20; ++i) {
    const calder::BodyId id = sim.world().body(i);
    const Vec2 r = sim.world().position(id) - g.center;
    const Vec2 v = sim.world().velocity(id);
    EXPECT_GE(r.mag(), 100.0 - 1e-9);
    EXPECT_LT(r.mag(), 150.0 + 1e-9);
    EXPECT_GE(v.mag(), 10.0 - 1e-9);
    EXPECT_LT(v.mag(), 15.0 + 1e-9);
    EXPECT_NEAR(r.dot(v) / (r.mag() * v.mag()), 0.0, 1e-12);  // perpendicular
    // +90 degrees: v = rotate(r-hat) * speed, so r x v > 0 (clockwise on a y-down canvas).
    EXPECT_GT(r.cross(v), 0.0);
    EXPECT_DOUBLE_EQ(sim.world().radius(id), std::sqrt(sim.world().mass(id)));
  }
}

TEST(SceneGeneration, SeedArgumentReplacesTheScenesSeed) {
  Scene s = calder::builtin_scene("example-2.7");
  s.world.seed = 99;
  Simulation a(s, 1u);
  Simulation b(calder::builtin_scene("example-2.7"), 1u);
  Simulation c(s);
  EXPECT_EQ(calder::state_hash(a.world()), calder::state_hash(b.world()));
  EXPECT_NE(calder::state_hash(a.world()), calder::state_hash(c.world()));
}

TEST(SimulationInput, WindBlowsOnlyWhilePressed) {
  Scene s = calder::builtin_scene("example-2.1");
  Simulation sim(s);
  sim.step(InputState{.mouse_pressed = false});
  EXPECT_EQ(sim.world().velocity(sim.world().body(0)).x, 0.0);
  sim.step(InputState{.mouse_pressed = true});
  EXPECT_EQ(sim.world().velocity(sim.world().body(0)).x, 0.1);  // wind (0.1, 0) / mass 1
  sim.step(InputState{.mouse_pressed = false});
  EXPECT_EQ(sim.world().velocity(sim.world().body(0)).x, 0.1);  // no more wind: Newton's first law
}

TEST(SimulationInput, ScriptedRangesAreInclusiveDrawNumbers) {
  calder::InputScript script;
  script.mouse_pressed.push_back({100, 160});
  EXPECT_FALSE(script.pressed_at(99));
  EXPECT_TRUE(script.pressed_at(100));
  EXPECT_TRUE(script.pressed_at(160));
  EXPECT_FALSE(script.pressed_at(161));
  script.mouse = {1, 2};
  script.moves.push_back({10, {3, 4}});
  EXPECT_EQ(script.mouse_at(9), (Vec2{1, 2}));
  EXPECT_EQ(script.mouse_at(10), (Vec2{3, 4}));
}

TEST(SimulationInput, PressResetsWithNewMassesFromTheContinuingGenerator) {
  // Example 2.5: mousePressed() -> reset(): nine new movers, masses drawn by
  // the same generator after the nine of setup().
  Simulation sim(calder::builtin_scene("example-2.5"), 1u);
  calder::Random rng(1);
  for (int i = 0; i < 9; ++i) rng.random(0.5, 3.0);  // setup's draws
  sim.step(InputState{});
  sim.step(InputState{});
  EXPECT_NE(sim.world().position(sim.world().body(0)).y, 0.0);  // the movers fell
  sim.step(InputState{.mouse_pressed = true});  // press: reset, then the frame's step
  for (std::size_t i = 0; i < 9; ++i) {
    const double m = rng.random(0.5, 3.0);
    EXPECT_EQ(sim.world().mass(sim.world().body(i)), m);
    // One frame after the reset: y = 0 + 0.1 (gravity m * 0.1 / m; not in the liquid).
    EXPECT_DOUBLE_EQ(sim.world().position(sim.world().body(i)).y, 0.1 * m / m);
  }
  // Holding the mouse is not a new press: no second reset.
  const double y_before = sim.world().position(sim.world().body(0)).y;
  sim.step(InputState{.mouse_pressed = true});
  EXPECT_GT(sim.world().position(sim.world().body(0)).y, y_before);
}

TEST(SimulationInput, AttractorIsGrabbedWithinItsMassAndDraggedOnlyWhenTheMouseMoves) {
  Simulation sim(calder::builtin_scene("example-2.6"));
  const auto attractor = [&] { return std::get<calder::Attractor>(sim.world().field(0)); };
  // A press 25 px away (more than mass 20) grabs nothing.
  sim.step(InputState{.mouse_pressed = true, .mouse = {345, 120}});
  sim.step(InputState{.mouse_pressed = true, .mouse = {400, 100}});
  EXPECT_EQ(attractor().position, (Vec2{320, 120}));
  sim.step(InputState{.mouse_pressed = false, .mouse = {400, 100}});
  // A press 10.3 px away grabs it with that offset...
  sim.step(InputState{.mouse_pressed = true, .mouse = {330.3, 120}});
  EXPECT_EQ(attractor().position, (Vec2{320, 120}));  // a press alone doesn't move it
  sim.step(InputState{.mouse_pressed = true, .mouse = {330.3, 120}});
  EXPECT_EQ(attractor().position, (Vec2{320, 120}));  // nor does holding still
  sim.step(InputState{.mouse_pressed = true, .mouse = {130.3, 20}});
  EXPECT_NEAR(attractor().position.x, 120.0, 1e-12);  // mouse + (320 - 330.3)
  EXPECT_NEAR(attractor().position.y, 20.0, 1e-12);
  // ...and releases it.
  sim.step(InputState{.mouse_pressed = false, .mouse = {0, 0}});
  sim.step(InputState{.mouse_pressed = true, .mouse = {600, 200}});
  sim.step(InputState{.mouse_pressed = true, .mouse = {610, 210}});
  EXPECT_NEAR(attractor().position.x, 120.0, 1e-12);
}

TEST(SimulationInput, FollowMouseMovesAFan) {
  Scene s = empty_scene();
  s.bodies.push_back(BodyGroup{});
  s.fields.push_back({calder::Fan{.position = {0, 0}, .strength = 1, .reach = 100},
                      calder::FieldBinding{.follow_mouse = true}});
  Simulation sim(s);
  sim.step(InputState{.mouse = {-10, 0}});  // body at the origin, fan 10 px to its left
  // Pushed right by strength * (1 - 10 / 100) = 0.9, mass 1, dt 1.
  EXPECT_DOUBLE_EQ(sim.world().velocity(sim.world().body(0)).x, 0.9);
  EXPECT_EQ(std::get<calder::Fan>(sim.world().field(0)).position, (Vec2{-10, 0}));
}

TEST(SimulationState, SetBodiesReplacesAllOrNothing) {
  Simulation sim(calder::builtin_scene("example-2.2"));
  EXPECT_THROW(sim.set_bodies({{.mass = 1.0}, {.mass = -1.0}}), calder::Error);
  EXPECT_EQ(sim.world().body_count(), 2U);  // unchanged
  EXPECT_EQ(sim.world().mass(sim.world().body(0)), 10.0);
  sim.set_bodies({{.position = {1, 2}, .mass = 3.0}});
  EXPECT_EQ(sim.world().body_count(), 1U);
  EXPECT_EQ(sim.world().position(sim.world().body(0)), (Vec2{1, 2}));
}

TEST(SceneValidation, RejectsWhatCannotBeRun) {
  const auto rejects = [](const Scene& s, const std::string& phrase) {
    calder::test::expect_error([&] { s.validate(); }, phrase);
  };
  Scene s = empty_scene();
  s.frames = -1;
  rejects(s, "frames");
  s.frames = calder::max_frames + 1;
  rejects(s, "frames");
  s = empty_scene();
  s.bodies.push_back(BodyGroup{.mass = Draw::fixed(0.0)});
  rejects(s, "mass");
  s = empty_scene();
  s.bodies.push_back(BodyGroup{.mass = Draw::uniform(-1.0, 2.0)});
  rejects(s, "mass");
  s = empty_scene();
  s.bodies.push_back(BodyGroup{.x = Draw::fixed(std::nan(""))});
  rejects(s, "finite");
  s = empty_scene();
  s.bodies.push_back(BodyGroup{.count = calder::max_bodies + 1});
  rejects(s, "bodies");
  s = empty_scene();
  s.fields.push_back({calder::Wind{}, calder::FieldBinding{.draggable = true}});
  rejects(s, "dragged");
  s = empty_scene();
  s.fields.push_back({calder::Gravity{.g = {0, INFINITY}}});
  rejects(s, "gravity");
  s = empty_scene();
  s.input.mouse_pressed.push_back({5, 4});
  rejects(s, "mouse_pressed");
  s = empty_scene();
  s.world.update_order = calder::UpdateOrder::sequential;
  s.world.integrator = calder::Integrator::rk4;
  rejects(s, "sequential");
}

TEST(BuiltinScenes, EveryExampleOfTheChapterWithADescription) {
  std::set<std::string> names;
  for (const calder::SceneInfo& info : calder::builtin_scenes()) {
    names.insert(info.name);
    EXPECT_FALSE(info.description.empty()) << info.name;
    EXPECT_EQ(info.description.find('\n'), std::string::npos) << info.name;
    const Scene s = calder::builtin_scene(info.name);
    EXPECT_EQ(s.name, info.name);
    EXPECT_NO_THROW(s.validate()) << info.name;
  }
  for (const char* name :
       {"example-2.1", "example-2.2", "example-2.3", "example-2.4", "example-2.5", "example-2.6",
        "example-2.7", "example-2.8", "example-2.9", "exercise-2.16"}) {
    EXPECT_EQ(names.count(name), 1U) << name;
  }
  calder::test::expect_error([] { (void)calder::builtin_scene("example-2.10"); }, "example-2.9");
}

TEST(BuiltinScenes, BookInitialStates) {
  // Spec: 2.7 has 10 movers with v = (1, 0); 2.9 has 10 bodies at rest in
  // [0, 640) x [0, 240) with masses in [0.1, 2); the galaxy has 100 bodies.
  Simulation seven(calder::builtin_scene("example-2.7"), 1u);
  ASSERT_EQ(seven.world().body_count(), 10U);
  for (std::size_t i = 0; i < 10; ++i) {
    EXPECT_EQ(seven.world().velocity(seven.world().body(i)), (Vec2{1, 0}));
  }
  Simulation nine(calder::builtin_scene("example-2.9"), 1u);
  ASSERT_EQ(nine.world().body_count(), 10U);
  for (std::size_t i = 0; i < 10; ++i) {
    const calder::BodyId id = nine.world().body(i);
    EXPECT_EQ(nine.world().velocity(id), (Vec2{0, 0}));
    EXPECT_GE(nine.world().mass(id), 0.1);
    EXPECT_LT(nine.world().mass(id), 2.0);
  }
  Simulation galaxy(calder::builtin_scene("exercise-2.16"), 1u);
  EXPECT_EQ(galaxy.world().body_count(), 100U);
}

// --- mutual attraction's orders ---

calder::World three_bodies() {
  calder::World w;
  w.add_body({.position = {0, 0}, .velocity = {0.1, 0}, .mass = 2});
  w.add_body({.position = {30, 5}, .velocity = {0, -0.2}, .mass = 3});
  w.add_body({.position = {-12, 20}, .velocity = {0.05, 0.05}, .mass = 1.5});
  return w;
}

TEST(MutualAttractionOrder, BySourceWithCentralMatchesTheGalaxyLoopBitForBit) {
  // Exercise 2.16's draw(): for each mover: sun.attract(mover); for each
  // other: mover.attract(other) (force on other); then every mover updates.
  calder::AttractionLaw law;
  law.clamp = calder::DistanceClamp::squared_distance;
  law.min = 100;
  law.max = 1000;
  law.product = calder::MassProduct::masses_first;
  const calder::CentralBody sun{.position = {3, 4}, .mass = 500};
  calder::World fields = three_bodies();
  fields.add(
      calder::MutualAttraction{.law = law, .order = calder::PairOrder::by_source, .central = sun});
  calder::World book = three_bodies();
  for (int step = 0; step < 50; ++step) {
    fields.step();
    const std::size_t n = book.body_count();
    for (std::size_t i = 0; i < n; ++i) {
      const calder::BodyId mover = book.body(i);
      book.apply_force(mover, calder::attraction(sun.position, sun.mass, book.position(mover),
                                                 book.mass(mover), law));
      for (std::size_t j = 0; j < n; ++j) {
        if (j == i) continue;
        const calder::BodyId other = book.body(j);
        book.apply_force(other, calder::attraction(book.position(mover), book.mass(mover),
                                                   book.position(other), book.mass(other), law));
      }
    }
    for (std::size_t i = 0; i < n; ++i) book.update(book.body(i));
  }
  EXPECT_EQ(calder::state_hash(fields), calder::state_hash(book));
}

TEST(MutualAttractionOrder, PairwiseAndBySourceAgreeToRoundingAndPairwiseConservesMomentum) {
  calder::World pairwise = three_bodies();
  calder::World by_source = three_bodies();
  const auto law = calder::AttractionLaw::book(1, 5, 25, calder::MassProduct::masses_first);
  pairwise.add(calder::MutualAttraction{.law = law});
  by_source.add(calder::MutualAttraction{.law = law, .order = calder::PairOrder::by_source});
  const Vec2 p0 = calder::linear_momentum(pairwise);
  pairwise.step(20);
  by_source.step(20);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(pairwise.position(pairwise.body(i)).x, by_source.position(by_source.body(i)).x,
                1e-9);
  }
  EXPECT_NEAR((calder::linear_momentum(pairwise) - p0).mag(), 0.0, 1e-15);
}

TEST(MutualAttractionOrder, CentralBodyPotentialCountsInTheEnergy) {
  calder::World w;
  w.add_body({.position = {10, 0}, .mass = 2});
  w.add(calder::MutualAttraction{.law = calder::AttractionLaw::newtonian(1.0),
                                 .central = calder::CentralBody{.position = {0, 0}, .mass = 5}});
  // One body: no pairs; the central body's potential is -G M m / r = -5 * 2 / 10.
  EXPECT_DOUBLE_EQ(calder::potential_energy(w), -1.0);
}

}  // namespace
