// The built-in scenes: every example of chapter 2 with the book's constants,
// initial state and order of operations (shared/spec/chapter2.md).
#include <functional>
#include <string>
#include <utility>

#include "calder/error.hpp"
#include "calder/scene.hpp"

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
  return s;
}

struct Entry {
  const char* name;
  Scene (*make)();
};

const Entry kScenes[] = {
    {"example-2.1", example_2_1},     {"example-2.2", example_2_2}, {"example-2.3", example_2_3},
    {"example-2.4", example_2_4},     {"example-2.5", example_2_5}, {"example-2.6", example_2_6},
    {"example-2.7", example_2_7},     {"example-2.8", example_2_8}, {"example-2.9", example_2_9},
    {"exercise-2.16", exercise_2_16},
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
  std::string names;
  for (const Entry& e : kScenes) {
    names += names.empty() ? "" : ", ";
    names += e.name;
  }
  throw Error("no built-in scene '" + name + "' (built-in scenes: " + names + ")");
}

}  // namespace calder
