// SPDX-License-Identifier: MIT
// The built-in scenes: every example of chapter 2 with the book's constants,
// initial state and order of operations (shared/spec/chapter2.md).
#include <cmath>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "calder/error.hpp"
#include "calder/scene.hpp"
#include "kepler_orbit.hpp"

namespace calder {

namespace {

Scene base(std::string name, std::string description) {
  Scene s;
  s.name = std::move(name);
  s.description = std::move(description);
  s.world.width = 640.0;
  s.world.height = 240.0;
  return s;
}

BodyGroup one_body(Vec2 position, double mass, RadiusRule radius, Vec2 velocity = {}) {
  BodyGroup g;
  g.count = 1;
  g.x = Draw::fixed(position.x);
  g.y = Draw::fixed(position.y);
  g.mass = Draw::fixed(mass);
  g.vx = Draw::fixed(velocity.x);
  g.vy = Draw::fixed(velocity.y);
  g.radius = radius;
  return g;
}

RadiusRule fixed_radius(double r) { return {RadiusRule::Kind::fixed, r}; }
RadiusRule radius_per_mass(double k) { return {RadiusRule::Kind::per_mass, k}; }
RadiusRule radius_per_sqrt_mass(double k) { return {RadiusRule::Kind::per_sqrt_mass, k}; }

SceneField field(Field f, FieldBinding binding = {}) { return {std::move(f), binding}; }
FieldBinding while_pressed() { return {.while_pressed = true}; }
FieldBinding draggable() { return {.draggable = true}; }

// Examples 2.1 and 2.2 share their world: gravity (0, 0.1), wind (0.1, 0)
// while the mouse is held, bounce off left, right and bottom on the centre.
void forces_world(Scene& s) {
  s.fields.push_back(field(Gravity{.g = {0.0, 0.1}}));
  s.fields.push_back(field(Wind{.force = {0.1, 0.0}}, while_pressed()));
  s.world.boundary = Boundary::bounce(1.0, false, {.top = false});
}

Scene example_2_1() {
  Scene s =
      base("example-2.1",
           "Forces: gravity pulls a mover down; wind pushes it right while the mouse is pressed");
  s.bodies.push_back(one_body({320.0, 30.0}, 1.0, fixed_radius(24.0)));
  forces_world(s);
  return s;
}

Scene example_2_2() {
  Scene s = base(
      "example-2.2",
      "Forces acting on two objects: the same forces move a light mover more than a heavy one");
  s.bodies.push_back(one_body({200.0, 30.0}, 10.0, radius_per_mass(8.0)));
  s.bodies.push_back(one_body({440.0, 30.0}, 2.0, radius_per_mass(8.0)));
  forces_world(s);
  return s;
}

Scene example_2_3() {
  Scene s =
      base("example-2.3",
           "Gravity scaled by mass: heavy and light movers fall together; edges count the radius");
  s.bodies.push_back(one_body({200.0, 30.0}, 10.0, radius_per_mass(8.0)));
  s.bodies.push_back(one_body({440.0, 30.0}, 2.0, radius_per_mass(8.0)));
  s.fields.push_back(field(Gravity{.g = {0.0, 0.1}, .scale_by_mass = true}));
  s.fields.push_back(field(Wind{.force = {0.1, 0.0}}, while_pressed()));
  s.world.boundary = Boundary::bounce(1.0, true, {.top = false});
  return s;
}

Scene example_2_4() {
  Scene s =
      base("example-2.4", "Including friction: a mover bounces and slides to a stop on the floor");
  s.bodies.push_back(one_body({320.0, 30.0}, 5.0, fixed_radius(40.0)));
  s.fields.push_back(field(Gravity{.g = {0.0, 1.0}}));
  s.fields.push_back(field(Wind{.force = {0.5, 0.0}}, while_pressed()));
  s.fields.push_back(field(Friction{.mu = 0.1}));
  s.world.boundary = Boundary::bounce(0.9, true, {.top = false});
  s.world.boundary.timing = BoundaryTiming::before_update;  // the book bounces, then updates
  return s;
}

Scene example_2_5() {
  Scene s =
      base("example-2.5",
           "Fluid resistance: nine movers of random mass fall into a liquid; a click resets them");
  BodyGroup movers;
  movers.count = 9;
  movers.x = Draw::linear(40.0, 70.0);
  movers.y = Draw::fixed(0.0);
  movers.mass = Draw::uniform(0.5, 3.0);
  movers.radius = radius_per_mass(8.0);
  s.bodies.push_back(movers);
  s.fields.push_back(field(Liquid{.region = {0.0, 120.0, 640.0, 120.0}, .c = 0.1}));
  s.fields.push_back(field(Gravity{.g = {0.0, 0.1}, .scale_by_mass = true}));
  s.world.boundary =
      Boundary::bounce(0.9, true, {.left = false, .right = false, .top = false, .bottom = true});
  s.on_press = PressAction::reset;
  return s;
}

// The attractor of examples 2.6 and 2.7: (320, 120), mass 20, G = 1, d in [5, 25].
SceneField book_attractor() {
  return field(Attractor{.position = {320.0, 120.0},
                         .mass = 20.0,
                         .law = AttractionLaw::book(1.0, 5.0, 25.0, MassProduct::left_to_right)},
               draggable());
}

Scene example_2_6() {
  Scene s = base("example-2.6", "Attraction: a mover orbits a draggable attractor");
  s.bodies.push_back(one_body({300.0, 50.0}, 2.0, radius_per_mass(8.0), {1.0, 0.0}));
  s.fields.push_back(book_attractor());
  return s;
}

Scene example_2_7() {
  Scene s = base("example-2.7",
                 "Attraction with many movers: ten random movers around a draggable attractor");
  BodyGroup movers;
  movers.count = 10;
  movers.x = Draw::uniform(0.0, 640.0);  // random(width): draw * 640, same bits
  movers.y = Draw::uniform(0.0, 240.0);
  movers.mass = Draw::uniform(0.5, 3.0);
  movers.vx = Draw::fixed(1.0);
  movers.radius = radius_per_mass(8.0);
  s.bodies.push_back(movers);
  s.fields.push_back(book_attractor());
  return s;
}

Scene example_2_8() {
  Scene s = base("example-2.8", "Two-body attraction: two equal bodies orbit each other");
  s.bodies.push_back(one_body({320.0, 40.0}, 8.0, radius_per_sqrt_mass(2.0), {1.0, 0.0}));
  s.bodies.push_back(one_body({320.0, 200.0}, 8.0, radius_per_sqrt_mass(2.0), {-1.0, 0.0}));
  s.fields.push_back(field(
      MutualAttraction{.law = AttractionLaw::book(1.0, 5.0, 25.0, MassProduct::masses_first)}));
  return s;
}

Scene example_2_9() {
  Scene s = base(
      "example-2.9",
      "n bodies: ten random bodies attract one another, updated one after another as in the book");
  BodyGroup bodies;
  bodies.count = 10;
  bodies.x = Draw::uniform(0.0, 640.0);
  bodies.y = Draw::uniform(0.0, 240.0);
  bodies.mass = Draw::uniform(0.1, 2.0);
  bodies.radius = radius_per_mass(8.0);
  s.bodies.push_back(bodies);
  s.fields.push_back(field(
      MutualAttraction{.law = AttractionLaw::book(1.0, 5.0, 25.0, MassProduct::left_to_right)}));
  s.world.update_order = UpdateOrder::sequential;  // body i moves before i + 1 feels it
  return s;
}

Scene exercise_2_16() {
  Scene s =
      base("exercise-2.16",
           "A spiral galaxy: a hundred bodies orbit a heavy fixed sun and attract one another");
  BodyGroup stars;
  stars.layout = BodyGroup::Layout::orbit;
  stars.count = 100;
  stars.center = {0.0, 0.0};
  stars.speed = Draw::uniform(10.0, 15.0);
  stars.distance = Draw::uniform(100.0, 150.0);
  stars.mass = Draw::uniform(10.0, 15.0);
  stars.radius = radius_per_sqrt_mass(1.0);
  s.bodies.push_back(stars);
  AttractionLaw law;
  law.G = 1.0;
  law.clamp = DistanceClamp::squared_distance;
  law.min = 100.0;
  law.max = 1000.0;
  law.product = MassProduct::masses_first;
  s.fields.push_back(
      field(MutualAttraction{.law = law,
                             .order = PairOrder::by_source,
                             .central = CentralBody{.position = {0.0, 0.0}, .mass = 500.0}}));
  s.origin = {320.0, 120.0};  // the sketch translates to the canvas centre
  s.look.trails = true;       // background(255, 50)
  s.look.trail_alpha = 50.0;
  s.look.body_gray = 0.0;  // fill(0, 100)
  s.look.body_alpha = 100.0;
  return s;
}

// --- the exercises (constants are calder's where the book leaves them open) ---

Scene exercise_2_1() {
  // The book's solution (nature_of_code_exercise_2_1_solution), step for
  // step: the ceiling check first in draw(), if (y - d/2 - strokeWeight < 0)
  // { y = d/2 - strokeWeight + 2; vy *= -0.75 }, i.e. a wall 1 px (the
  // stroke) below the top that puts the balloon at y = 25; helium (0, -0.02);
  // wind map(noise(noiseX), 0, 1, -0.01, 0.01) with noiseX from 1000 and
  // noiseX += 0.01 after each frame; vel.limit(5); the sides wrap to the
  // other edge. noiseSeed(seed) is the scene's seed.
  Scene s = base("exercise-2.1",
                 "A helium balloon rises in Perlin-noise wind, bounces off the ceiling and wraps "
                 "around the sides");
  s.bodies.push_back(one_body({320.0, 120.0}, 1.0, fixed_radius(24.0)));
  s.fields.push_back(field(Helium{.lift = 0.02}));
  s.fields.push_back(
      field(NoiseWind{.strength = 0.01, .rate = 0.01, .offset = 1000.0, .accumulate = true}));
  s.edges_first = Boundary::bounce(0.75, true, {.left = false, .right = false, .bottom = false});
  s.edges_first.inset = 1.0;
  s.world.boundary = Boundary::wrap(false);
  s.world.boundary.edges = {.top = false, .bottom = false};
  s.world.boundary.periodic = false;
  s.world.max_speed = 5.0;
  return s;
}

BodyGroup random_movers(std::size_t count, double min_mass, double max_mass, double speed) {
  BodyGroup g;
  g.count = count;
  g.x = Draw::uniform(0.0, 640.0);
  g.y = Draw::uniform(0.0, 240.0);
  g.mass = Draw::uniform(min_mass, max_mass);
  g.vx = Draw::uniform(-speed, speed);
  g.vy = Draw::uniform(-speed, speed);
  g.radius = radius_per_mass(8.0);
  return g;
}

Scene exercise_2_3() {
  Scene s =
      base("exercise-2.3",
           "An invisible force pushes movers back from the edges, stronger the closer they come");
  s.bodies.push_back(random_movers(10, 0.5, 3.0, 3.0));
  s.fields.push_back(field(EdgeForce{.strength = 1.0, .margin = 60.0}));
  return s;
}

Scene exercise_2_4() {
  Scene s =
      base("exercise-2.4",
           "Movers of different sizes bounce when their edge, not their centre, meets a wall");
  BodyGroup movers;
  movers.count = 5;
  movers.x = Draw::linear(80.0, 120.0);
  movers.y = Draw::fixed(40.0);
  movers.mass = Draw::linear(1.0, 0.75);
  movers.vx = Draw::linear(-2.0, 1.0);
  movers.radius = radius_per_mass(8.0);
  s.bodies.push_back(movers);
  s.fields.push_back(field(Gravity{.g = {0.0, 0.1}, .scale_by_mass = true}));
  s.fields.push_back(field(Wind{.force = {0.1, 0.0}}, while_pressed()));
  s.world.boundary = Boundary::bounce(1.0, true);
  return s;
}

Scene exercise_2_5() {
  Scene s = base("exercise-2.5", "A fan at the mouse blows the circles away from it");
  BodyGroup movers;
  movers.count = 8;
  movers.x = Draw::linear(60.0, 75.0);
  movers.y = Draw::fixed(200.0);
  movers.mass = Draw::uniform(1.0, 3.0);
  movers.radius = radius_per_mass(8.0);
  s.bodies.push_back(movers);
  s.fields.push_back(field(Gravity{.g = {0.0, 0.2}, .scale_by_mass = true}));
  s.fields.push_back(field(Fan{.position = {0.0, 120.0}, .strength = 2.0, .reach = 250.0},
                           {.follow_mouse = true}));
  s.fields.push_back(field(Friction{.mu = 0.1}));
  s.world.boundary = Boundary::bounce(0.6, true);
  s.input.mouse = {0.0, 200.0};
  return s;
}

Scene exercise_2_6() {
  Scene s = base("exercise-2.6",
                 "Four movers of different mass slide on floors of different roughness (own "
                 "friction coefficients)");
  const double mu[] = {0.01, 0.05, 0.1, 0.3};
  for (int k = 0; k < 4; ++k) {
    const double mass = 1.0 + k;  // on the floor from the start: y = height - radius
    BodyGroup g = one_body({80.0 + 160.0 * k, 240.0 - 8.0 * mass}, mass, radius_per_mass(8.0));
    g.friction = mu[k];
    s.bodies.push_back(g);
  }
  s.fields.push_back(field(Gravity{.g = {0.0, 0.2}, .scale_by_mass = true}));
  s.fields.push_back(field(Wind{.force = {0.2, 0.0}}, while_pressed()));
  s.fields.push_back(field(Friction{.mu = 0.1}));
  s.world.boundary = Boundary::bounce(0.9, true, {.top = false});
  s.world.boundary.timing = BoundaryTiming::before_update;
  s.input.mouse_pressed.push_back({1, 30});  // a push to the right to start them sliding
  return s;
}

Scene exercise_2_7() {
  Scene s = base("exercise-2.7", "Toss a mover: grab it with the mouse, drag, and let go");
  s.bodies.push_back(one_body({320.0, 60.0}, 2.0, fixed_radius(24.0)));
  s.fields.push_back(field(Gravity{.g = {0.0, 0.2}, .scale_by_mass = true}));
  s.fields.push_back(field(Drag{.c = 0.002}));
  s.world.boundary = Boundary::bounce(0.8, true);
  s.on_press = PressAction::toss;
  return s;
}

Scene exercise_2_8() {
  Scene s = base("exercise-2.8",
                 "Strong drag slows but never reverses movers dropped from different heights");
  BodyGroup movers;
  movers.count = 5;
  movers.x = Draw::linear(64.0, 128.0);
  movers.y = Draw::linear(10.0, 25.0);
  movers.mass = Draw::fixed(2.0);
  movers.radius = fixed_radius(16.0);
  s.bodies.push_back(movers);
  s.fields.push_back(
      field(Liquid{.region = {0.0, 150.0, 640.0, 90.0}, .c = 2.0, .never_reverse = true}));
  s.fields.push_back(field(Gravity{.g = {0.0, 0.1}, .scale_by_mass = true}));
  s.world.boundary = Boundary::bounce(0.5, true, {.left = false, .right = false, .top = false});
  return s;
}

Scene exercise_2_9() {
  Scene s = base("exercise-2.9", "Boxes of equal mass fall into water; wider boxes feel more drag");
  for (int k = 0; k < 4; ++k) {
    const double half_side = 8.0 + 4.0 * k;
    BodyGroup box = one_body({100.0 + 140.0 * k, 20.0}, 2.0, fixed_radius(half_side));
    box.drag_area = 2.0 * half_side / 20.0;  // the side facing the motion, in units of 20 px
    s.bodies.push_back(box);
  }
  s.fields.push_back(
      field(Liquid{.region = {0.0, 100.0, 640.0, 140.0}, .c = 0.5, .never_reverse = true}));
  s.fields.push_back(field(Gravity{.g = {0.0, 0.1}, .scale_by_mass = true}));
  s.world.boundary = Boundary::bounce(0.5, true, {.left = false, .right = false, .top = false});
  s.look.squares = true;
  return s;
}

Scene exercise_2_10() {
  Scene s = base("exercise-2.10",
                 "Lift: a glider moving right is held up by a force perpendicular to its motion");
  s.bodies.push_back(one_body({0.0, 120.0}, 1.0, fixed_radius(10.0), {4.0, 0.0}));
  s.fields.push_back(field(Gravity{.g = {0.0, 0.05}}));
  s.fields.push_back(field(Lift{.coefficient = 0.003}));
  s.fields.push_back(field(Drag{.c = 0.0005}));
  s.world.boundary = Boundary::wrap(true);
  return s;
}

Scene exercise_2_11() {
  Scene s =
      base("exercise-2.11", "Mass as area: the circle's area, not its diameter, grows with mass");
  BodyGroup movers;
  movers.count = 4;
  movers.x = Draw::linear(100.0, 140.0);
  movers.y = Draw::fixed(60.0);
  movers.mass = Draw::linear(1.0, 3.0);
  movers.radius = radius_per_sqrt_mass(12.0);
  s.bodies.push_back(movers);
  s.fields.push_back(field(Gravity{.g = {0.0, 0.1}, .scale_by_mass = true}));
  s.fields.push_back(field(Wind{.force = {0.2, 0.0}}, while_pressed()));
  s.world.boundary = Boundary::bounce(0.9, true, {.top = false});
  return s;
}

Scene exercise_2_12() {
  Scene s = base("exercise-2.12",
                 "A hundred movers wander among three invisible attractors, drawn as trails");
  BodyGroup movers = random_movers(100, 0.5, 2.0, 1.0);
  movers.radius = radius_per_mass(4.0);
  s.bodies.push_back(movers);
  const Vec2 at[] = {{160.0, 120.0}, {330.0, 60.0}, {500.0, 170.0}};
  for (const Vec2 p : at) {
    SceneField f = field(Attractor{.position = p, .mass = 20.0, .law = AttractionLaw::book()});
    f.visible = false;
    s.fields.push_back(f);
  }
  s.look.trails = true;
  s.look.trail_alpha = 20.0;
  return s;
}

Scene exercise_2_13() {
  // |F| = G M m / d^2 - R M m / d^3: zero at d = R / G = 60 px, so movers
  // settle into a ring around the attractor instead of falling in.
  Scene s = base("exercise-2.13",
                 "A custom force law: the attractor pulls from afar and pushes away up close");
  s.bodies.push_back(random_movers(30, 0.5, 2.0, 0.5));
  AttractionLaw law = AttractionLaw::book(1.0, 5.0, 1000.0);
  law.repulsion = 60.0;
  law.repulsion_exponent = 3.0;
  s.fields.push_back(
      field(Attractor{.position = {320.0, 120.0}, .mass = 20.0, .law = law}, draggable()));
  s.fields.push_back(field(Drag{.c = 0.02}));
  return s;
}

Scene exercise_2_14() {
  // The figure-eight choreography of three equal masses (Chenciner and
  // Montgomery 2000; initial conditions from Simo): G = m = 1, period
  // 6.32591398. Scaled to the canvas: 100 px per length unit and 60 frames per
  // time unit, so G = 100^3 / 60^2 and velocities times 100 / 60.
  Scene s = base("exercise-2.14",
                 "Three bodies chase each other along a figure eight (unclamped gravity)");
  const double length = 100.0;
  const double time = 60.0;
  const Vec2 centre{320.0, 120.0};
  const Vec2 x1{0.97000436, -0.24308753};
  const Vec2 v3{-0.93240737, -0.86473146};
  const Vec2 v1 = v3 * -0.5;
  const double speed = length / time;
  s.bodies.push_back(one_body(centre + x1 * length, 1.0, fixed_radius(8.0), v1 * speed));
  s.bodies.push_back(one_body(centre - x1 * length, 1.0, fixed_radius(8.0), v1 * speed));
  s.bodies.push_back(one_body(centre, 1.0, fixed_radius(8.0), v3 * speed));
  s.fields.push_back(field(
      MutualAttraction{.law = AttractionLaw::newtonian(length * length * length / (time * time))}));
  s.world.integrator = Integrator::rk4;
  s.frames = 380;  // one period is 6.32591398 * 60 = 379.55 frames
  s.look.trails = true;
  s.look.trail_alpha = 10.0;
  return s;
}

Scene exercise_2_15() {
  Scene s = base("exercise-2.15", "Bodies repel one another while all are drawn to the mouse");
  s.bodies.push_back(random_movers(20, 1.0, 3.0, 0.0));
  // Repulsion (G = -3) keeps bodies apart against the mouse's pull (mass 40); it must
  // fade with distance (clamp up to 1000 px), or the crowd pushes its fringe away forever.
  s.fields.push_back(field(MutualAttraction{.law = AttractionLaw::book(-3.0, 5.0, 1000.0)}));
  s.fields.push_back(field(
      Attractor{
          .position = {320.0, 120.0}, .mass = 40.0, .law = AttractionLaw::book(1.0, 5.0, 25.0)},
      {.follow_mouse = true}));
  s.fields.push_back(field(Drag{.c = 0.05}));
  s.input.mouse = {320.0, 120.0};
  return s;
}

// Not from the book: the movers benchmark (docs/PERFORMANCE.md). Drops of
// random mass under gravity and air drag, bouncing on their radius off the
// walls and the floor; no body-body collisions. Set bodies[0].count for more
// drops (the benchmark scales the canvas with it: same density).
Scene rain() {
  Scene s = base("rain",
                 "Rain: a thousand drops under gravity and air drag, bouncing off the walls and "
                 "the floor (the movers benchmark)");
  BodyGroup drops;
  drops.count = 1000;
  drops.x = Draw::uniform(0.0, 640.0);
  drops.y = Draw::uniform(0.0, 240.0);
  drops.mass = Draw::uniform(0.5, 3.0);
  drops.radius = radius_per_mass(2.0);
  s.bodies.push_back(drops);
  s.fields.push_back(field(Gravity{.g = {0.0, 0.1}, .scale_by_mass = true}));
  s.fields.push_back(field(Drag{.c = 0.01}));
  s.world.boundary = Boundary::bounce(0.9, true, {.top = false});
  s.world.seed = 1;
  return s;
}

// --- classic problems of celestial mechanics, integrated with ias15 ---
// Lengths are in pixels: each problem's unit of length is kUnit pixels and
// G is kUnit^3, so that its unit of time (and so its times) stay the
// literature's; velocities are the literature's times kUnit.

// Newton's law as a scene file's `clamp = "none"` reads it (min and max
// keep their defaults, unused without a clamp).
AttractionLaw newton(double G, double softening = 0.0) {
  AttractionLaw law;
  law.G = G;
  law.clamp = DistanceClamp::none;
  law.softening = softening;
  return law;
}

Scene classic(std::string name, std::string description, double unit) {
  Scene s = base(std::move(name), std::move(description));
  s.world.width = 640.0;
  s.world.height = 480.0;
  s.world.integrator = Integrator::ias15;
  s.origin = {320.0, 240.0};
  s.look.trails = true;
  s.look.trail_alpha = 20.0;
  s.look.body_gray = 0.0;
  s.look.body_alpha = 200.0;
  s.fields.push_back(field(MutualAttraction{.law = newton(unit * unit * unit)}));
  return s;
}

// Burrau's problem (1913): masses 3, 4 and 5 at rest at the corners of a
// 3-4-5 right triangle, each opposite the side of its length. Szebehely and
// Peters (1967) integrated it to t = 70: after many close approaches the
// lightest body escapes and the other two leave as a binary.
Scene pythagorean() {
  constexpr double kUnit = 40.0;
  Scene s = classic("pythagorean",
                    "Burrau's Pythagorean three-body problem: masses 3, 4, 5 at rest until t = 70; "
                    "the lightest escapes",
                    kUnit);
  s.bodies.push_back(one_body({1.0 * kUnit, 3.0 * kUnit}, 3.0, radius_per_sqrt_mass(3.0)));
  s.bodies.push_back(one_body({-2.0 * kUnit, -1.0 * kUnit}, 4.0, radius_per_sqrt_mass(3.0)));
  s.bodies.push_back(one_body({1.0 * kUnit, -1.0 * kUnit}, 5.0, radius_per_sqrt_mass(3.0)));
  s.world.dt = 0.1;
  s.frames = 700;
  return s;
}

// The figure-eight choreography (Moore 1993; Chenciner and Montgomery 2000):
// three equal masses chase each other along one figure eight. Initial
// conditions and period to 8 digits from Chenciner and Montgomery (Annals of
// Mathematics 152, 2000), after Simo: x1 = -x2 = (0.97000436, -0.24308753),
// x3 = 0, v3 = (-0.93240737, -0.86473146), v1 = v2 = -v3 / 2; period
// 6.32591398. A frame is a 120th of the period: 1200 frames, ten periods.
Scene figure_eight() {
  constexpr double kUnit = 100.0;
  Scene s = classic("figure-eight",
                    "The figure-eight choreography of three equal masses (Chenciner and "
                    "Montgomery): ten periods",
                    kUnit);
  const Vec2 x1{97.000436, -24.308753};  // the digits above, times kUnit
  const Vec2 v3{-93.240737, -86.473146};
  const Vec2 v1{-v3.x / 2.0, -v3.y / 2.0};
  s.bodies.push_back(one_body(x1, 1.0, fixed_radius(6.0), v1));
  s.bodies.push_back(one_body({-x1.x, -x1.y}, 1.0, fixed_radius(6.0), v1));
  s.bodies.push_back(one_body({0.0, 0.0}, 1.0, fixed_radius(6.0), v3));
  s.world.dt = 6.32591398 / 120.0;
  s.frames = 1200;
  return s;
}

// The Kepler problem: a body around a fixed unit mass (an attractor), on an
// orbit of semi-major axis 1 and eccentricity 0.9 (period 2 pi), from its
// pericentre (1 - e, 0) at the vis-viva speed sqrt((1 + e) / (1 - e)). A
// frame is a 60th of the period: 600 frames, ten orbits. scenes/kepler.toml
// gives the orbit as a key, kepler = { eccentricity = 0.9, ... }, for
// another eccentricity.
Scene kepler() {
  constexpr double kUnit = 100.0;
  constexpr double kGM = kUnit * kUnit * kUnit;  // G, times the unit mass
  Scene s = classic("kepler", "A Kepler orbit of eccentricity 0.9 around a fixed mass: ten orbits",
                    kUnit);
  s.fields.clear();
  s.fields.push_back(field(Attractor{.position = {0.0, 0.0}, .mass = 1.0, .law = newton(kGM)}));
  const detail::Pericentre start = detail::pericentre(kGM, kUnit, 0.9);
  s.bodies.push_back(one_body({start.distance, 0.0}, 1.0, fixed_radius(5.0), {0.0, start.speed}));
  s.origin = {480.0, 240.0};
  s.world.dt = 2.0 * 3.141592653589793 / 60.0;
  s.frames = 600;
  return s;
}

// A star cluster: 16 bodies of random mass at rest in a square collapse
// under their mutual attraction, softened (Plummer 1911) so that close
// passages stay smooth and ias15's steps stay long.
Scene plummer_cluster() {
  constexpr double kUnit = 100.0;
  Scene s = classic("plummer-cluster",
                    "A cold cluster of 16 bodies collapsing under Plummer-softened gravity", kUnit);
  BodyGroup stars;
  stars.count = 16;
  stars.x = Draw::uniform(-kUnit, kUnit);
  stars.y = Draw::uniform(-kUnit, kUnit);
  stars.mass = Draw::uniform(0.5, 1.5);
  stars.radius = radius_per_sqrt_mass(3.0);
  s.bodies.push_back(stars);
  s.fields.clear();
  s.fields.push_back(
      field(MutualAttraction{.law = newton(0.05 * kUnit * kUnit * kUnit, 0.2 * kUnit)}));
  s.world.dt = 0.05;
  s.frames = 200;
  return s;
}

struct Entry {
  const char* name;
  Scene (*make)();
};

const Entry kScenes[] = {
    {"example-2.1", example_2_1},
    {"example-2.2", example_2_2},
    {"example-2.3", example_2_3},
    {"example-2.4", example_2_4},
    {"example-2.5", example_2_5},
    {"example-2.6", example_2_6},
    {"example-2.7", example_2_7},
    {"example-2.8", example_2_8},
    {"example-2.9", example_2_9},
    {"exercise-2.1", exercise_2_1},
    {"exercise-2.3", exercise_2_3},
    {"exercise-2.4", exercise_2_4},
    {"exercise-2.5", exercise_2_5},
    {"exercise-2.6", exercise_2_6},
    {"exercise-2.7", exercise_2_7},
    {"exercise-2.8", exercise_2_8},
    {"exercise-2.9", exercise_2_9},
    {"exercise-2.10", exercise_2_10},
    {"exercise-2.11", exercise_2_11},
    {"exercise-2.12", exercise_2_12},
    {"exercise-2.13", exercise_2_13},
    {"exercise-2.14", exercise_2_14},
    {"exercise-2.15", exercise_2_15},
    {"exercise-2.16", exercise_2_16},
    {"rain", rain},
    {"pythagorean", pythagorean},
    {"figure-eight", figure_eight},
    {"kepler", kepler},
    {"plummer-cluster", plummer_cluster},
};

}  // namespace

const std::vector<SceneInfo>& builtin_scenes() {
  static const std::vector<SceneInfo> infos = [] {
    std::vector<SceneInfo> v;
    for (const Entry& e : kScenes) {
      const Scene s = e.make();
      v.push_back({s.name, s.description});
    }
    return v;
  }();
  return infos;
}

Scene builtin_scene(const std::string& name) {
  for (const Entry& e : kScenes) {
    if (name == e.name) return e.make();
  }
  throw InputError(unknown_scene_message(name));
}

bool is_builtin_scene(std::string_view name) {
  for (const Entry& e : kScenes) {
    if (name == e.name) return true;
  }
  return false;
}

std::string unknown_scene_message(std::string_view name,
                                  const std::vector<std::string_view>& also) {
  std::string names;
  std::vector<std::string_view> candidates;
  for (const Entry& e : kScenes) {
    names += names.empty() ? "" : ", ";
    names += e.name;
    candidates.emplace_back(e.name);
  }
  candidates.insert(candidates.end(), also.begin(), also.end());
  std::string message = "unknown scene '" + detail::printable(name) + "'";
  // A typo of a candidate, or a file named like it ("three" for three.toml).
  if (const auto near = detail::closest(name, candidates)) {
    message += " (did you mean '" + std::string(*near) + "'?)";
  } else if (const auto file = detail::closest(std::string(name) + ".toml", candidates)) {
    message += " (did you mean '" + std::string(*file) + "'?)";
  }
  return message + ": not a built-in scene (" + names + ")";
}

}  // namespace calder
