// SPDX-License-Identifier: MIT
// Tests of scene files (calder/scene_file.hpp, docs/SCENES.md): the files of
// scenes/ against the built-in scenes (bit-identical trajectories), to_toml's
// round trip, every kind of error with its line and column, the defaults, the
// order of random draws, and every example of docs/SCENES.md.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <iostream>
#include <limits>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "calder/diagnostics.hpp"
#include "calder/error.hpp"
#include "calder/fields.hpp"
#include "calder/random.hpp"
#include "calder/scene.hpp"
#include "calder/scene_file.hpp"
#include "calder/world.hpp"

namespace {

using calder::Scene;
using calder::SceneFileError;
using calder::Simulation;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::StartsWith;

std::string scene_path(const std::string& name) {
  return std::string(CALDER_SOURCE_DIR) + "/scenes/" + name + ".toml";
}

// The message of the SceneFileError that parsing text throws.
std::string error_of(std::string_view text) {
  try {
    (void)calder::parse_scene(text, "t.toml");
  } catch (const SceneFileError& e) {
    return e.what();
  }
  return "(no error)";
}

std::uint64_t bits(double v) { return std::bit_cast<std::uint64_t>(v); }

// Runs both simulations `frames` frames with their scripted input and expects
// every body's position and velocity to be the same bits after every frame.
void expect_same_trajectory(Simulation& a, Simulation& b, int frames) {
  ASSERT_EQ(a.world().body_count(), b.world().body_count());
  for (int frame = 0; frame <= frames; ++frame) {
    if (frame > 0) {
      a.step();
      b.step();
    }
    const calder::BodyView va = a.world().bodies();
    const calder::BodyView vb = b.world().bodies();
    ASSERT_EQ(va.size(), vb.size()) << "frame " << frame;
    for (std::size_t i = 0; i < va.size(); ++i) {
      ASSERT_EQ(bits(va.x[i]), bits(vb.x[i])) << "frame " << frame << " body " << i << " x";
      ASSERT_EQ(bits(va.y[i]), bits(vb.y[i])) << "frame " << frame << " body " << i << " y";
      ASSERT_EQ(bits(va.vx[i]), bits(vb.vx[i])) << "frame " << frame << " body " << i << " vx";
      ASSERT_EQ(bits(va.vy[i]), bits(vb.vy[i])) << "frame " << frame << " body " << i << " vy";
      ASSERT_EQ(bits(va.mass[i]), bits(vb.mass[i])) << "frame " << frame << " body " << i;
      ASSERT_EQ(bits(va.radius[i]), bits(vb.radius[i])) << "frame " << frame << " body " << i;
    }
  }
}

// The mouse held from frame 100 to 160 at the attractor of 2.6 and 2.7, moved
// at frame 130: wind blows, 2.5 resets, the attractor is dragged.
calder::InputScript press_script() {
  calder::InputScript in;
  in.mouse_pressed = {{100, 160}};
  in.mouse = {320.0, 120.0};
  in.moves = {{130, {300.0, 100.0}}};
  return in;
}

// --- the scene files of scenes/ against the built-in scenes ---------------------------

std::vector<std::string> builtin_names() {
  std::vector<std::string> names;
  for (const calder::SceneInfo& info : calder::builtin_scenes()) names.push_back(info.name);
  return names;
}

class SceneFileBuiltin : public ::testing::TestWithParam<std::string> {};

TEST_P(SceneFileBuiltin, FileDescribesTheBuiltinScene) {
  const Scene file = calder::load_scene_file(scene_path(GetParam()));
  const Scene builtin = calder::builtin_scene(GetParam());
  // Same text once written: every parameter, the name and the description.
  EXPECT_EQ(calder::to_toml(file), calder::to_toml(builtin));
}

TEST_P(SceneFileBuiltin, SameTrajectoryBitForBit) {
  Simulation from_file(calder::load_scene_file(scene_path(GetParam())), 1);
  Simulation builtin(calder::builtin_scene(GetParam()), 1);
  expect_same_trajectory(from_file, builtin, 600);
}

TEST_P(SceneFileBuiltin, SameTrajectoryWithTheMousePressed) {
  Scene file = calder::load_scene_file(scene_path(GetParam()));
  Scene builtin = calder::builtin_scene(GetParam());
  file.input = press_script();
  builtin.input = press_script();
  Simulation a(std::move(file), 1);
  Simulation b(std::move(builtin), 1);
  expect_same_trajectory(a, b, 600);
}

TEST_P(SceneFileBuiltin, ToTomlRoundTrip) {
  const Scene scene = calder::builtin_scene(GetParam());
  const std::string text = calder::to_toml(scene);
  const Scene back = calder::parse_scene(text, GetParam() + ".toml");
  EXPECT_EQ(calder::to_toml(back), text);
  Simulation a(scene, 1);
  Simulation b(back, 1);
  for (int i = 0; i < 50; ++i) {
    a.step();
    b.step();
  }
  EXPECT_EQ(calder::state_hash(a.world()), calder::state_hash(b.world()));
}

std::string test_name(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = info.param;
  for (char& c : name) {
    if (c == '-' || c == '.') c = '_';
  }
  return name;
}

INSTANTIATE_TEST_SUITE_P(SceneFile, SceneFileBuiltin, ::testing::ValuesIn(builtin_names()),
                         test_name);

TEST(SceneFileBuiltinTest, EveryBuiltinSceneHasAFile) {
  for (const std::string& name : builtin_names()) {
    std::ifstream file(scene_path(name));
    EXPECT_TRUE(file.good()) << scene_path(name);
  }
}

// --- errors: "FILE:LINE:COLUMN: problem" --------------------------------------------------

TEST(SceneFileErrors, MissingFile) {
  try {
    (void)calder::load_scene_file("/nonexistent/rain.toml");
    FAIL() << "no error";
  } catch (const SceneFileError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/rain.toml: cannot read: No such file or directory");
  }
}

TEST(SceneFileErrors, UnreadableFile) {
  const std::string dir = std::string(CALDER_SOURCE_DIR) + "/scenes";
  try {
    (void)calder::load_scene_file(dir);
    FAIL() << "no error";
  } catch (const SceneFileError& e) {
    EXPECT_EQ(std::string(e.what()), dir + ": cannot read: Is a directory");
  }
}

TEST(SceneFileErrors, IsACalderError) {
  EXPECT_THROW((void)calder::parse_scene("frames = -1", "t.toml"), calder::Error);
}

TEST(SceneFileErrors, TomlSyntax) {
  EXPECT_THAT(error_of("name = \"x\"\nframes = 600\nseed = \n"), StartsWith("t.toml:3:8: "));
  // A trailing comma in an inline table, which TOML forbids.
  EXPECT_THAT(error_of("[[bodies]]\nposition = [1, 2]\nmass = { min = 1, max = 2, }\n"),
              StartsWith("t.toml:3:28: "));
  EXPECT_THAT(error_of("frames = 1\nframes = 2\n"),
              ::testing::AllOf(StartsWith("t.toml:2:"), HasSubstr("frames")));
}

TEST(SceneFileErrors, UnknownKeySuggestsTheNearest) {
  EXPECT_EQ(error_of("name = \"rain\"\n\n[[bodies]]\n  position = [1, 2]\n  mas = 1\n"),
            "t.toml:5:3: unknown key 'mas' in [[bodies]] (did you mean 'mass'?)");
  EXPECT_EQ(error_of("[[fields]]\ntype = \"gravity\"\nscale_by_mas = true\n"),
            "t.toml:3:1: unknown key 'scale_by_mas' in [[fields]] of type 'gravity' (did you mean "
            "'scale_by_mass'?)");
  EXPECT_EQ(error_of("[canvas]\nwidht = 10\n"),
            "t.toml:2:1: unknown key 'widht' in [canvas] (did you mean 'width'?)");
  EXPECT_EQ(error_of("[[bodys]]\nmass = 1\n"),
            "t.toml:1:3: unknown key 'bodys' in the top level (did you mean 'bodies'?)");
  // In an inline table.
  EXPECT_EQ(error_of("[[fields]]\ntype = \"attractor\"\nlaw = { g = 1 }\n"),
            "t.toml:3:9: unknown key 'g' in 'law' (did you mean 'G'?)");
  EXPECT_EQ(error_of("[[bodies]]\nposition = [0, 0]\nmass = { min = 1, mx = 2 }\n"),
            "t.toml:3:19: unknown key 'mx' in 'mass' (did you mean 'max'?)");
}

TEST(SceneFileErrors, UnknownKeyFarFromAnyListsTheValidKeys) {
  EXPECT_EQ(error_of("[[fields]]\ntype = \"wind\"\nstrength = 1\n"),
            "t.toml:3:1: unknown key 'strength' in [[fields]] of type 'wind' (valid keys: type, "
            "force, enabled, visible, while_pressed, follow_mouse, draggable)");
}

TEST(SceneFileErrors, TheFirstUnknownKeyInTheFile) {
  // toml++ keeps keys sorted; the error names the first one in the file.
  EXPECT_THAT(error_of("[[bodies]]\nzz = 1\naa = 2\nposition = [0, 0]\nmass = 1\n"),
              StartsWith("t.toml:2:1: unknown key 'zz'"));
}

TEST(SceneFileErrors, KeyOfTheOtherLayout) {
  EXPECT_EQ(error_of("[[bodies]]\nlayout = \"orbit\"\nx = 1\nmass = 1\n"),
            "t.toml:3:1: 'x' is not used with layout = \"orbit\" (it places bodies with center, "
            "distance and speed)");
  EXPECT_EQ(error_of("[[bodies]]\nposition = [0, 0]\nmass = 1\ndistance = 3\n"),
            "t.toml:4:1: 'distance' is used only with layout = \"orbit\"");
}

TEST(SceneFileErrors, WrongType) {
  EXPECT_EQ(error_of("[[bodies]]\nposition = [0, 0]\nmass = \"heavy\"\n"),
            "t.toml:3:8: 'mass' must be a number, { min = a, max = b } or { start = a, step = b }, "
            "got a string");
  EXPECT_EQ(error_of("[world]\ndt = \"1\"\n"),
            "t.toml:2:6: 'world.dt' must be a number, got a string");
  EXPECT_EQ(error_of("frames = 600.0\n"), "t.toml:1:10: 'frames' must be an integer, got a float");
  EXPECT_EQ(error_of("[[fields]]\ntype = \"gravity\"\ng = [0, \"down\"]\n"),
            "t.toml:3:9: 'g[1]' must be a number, got a string");
  EXPECT_EQ(error_of("[[fields]]\ntype = \"gravity\"\ng = [0, 1, 2]\n"),
            "t.toml:3:5: 'g' must be an array of 2 numbers [x, y], got an array of 3");
  EXPECT_EQ(error_of("[[fields]]\ntype = \"drag\"\nnever_reverse = 1\n"),
            "t.toml:3:17: 'never_reverse' must be true or false, got an integer");
  EXPECT_EQ(error_of("[bodies]\nmass = 1\n"),
            "t.toml:1:1: 'bodies' must be an array of tables ([[bodies]]), got a table");
  EXPECT_EQ(error_of("canvas = 3\n"), "t.toml:1:10: 'canvas' must be a table, got an integer");
}

TEST(SceneFileErrors, MissingRequiredKey) {
  EXPECT_EQ(error_of("[[fields]]\ng = [0, 1]\n"),
            "t.toml:1:1: missing required key 'type' in [[fields]]");
  EXPECT_EQ(error_of("frames = 10\n\n[[bodies]]\nposition = [0, 0]\n"),
            "t.toml:3:1: missing required key 'mass' in [[bodies]]");
  EXPECT_EQ(error_of("[[bodies]]\nmass = 1\n"),
            "t.toml:1:1: missing required key 'position' (or 'x' and 'y') in [[bodies]]");
  EXPECT_EQ(error_of("[[bodies]]\nmass = 1\nx = 3\n"),
            "t.toml:1:1: missing required key 'y' in [[bodies]]");
  EXPECT_EQ(error_of("[[bodies]]\nlayout = \"orbit\"\nmass = 1\nspeed = 1\n"),
            "t.toml:1:1: missing required key 'distance' in [[bodies]]");
  EXPECT_EQ(error_of("[boundary]\nrestitution = 0.9\n"),
            "t.toml:1:1: missing required key 'kind' in [boundary]");
  EXPECT_EQ(error_of("[[bodies]]\nposition = [0, 0]\nmass = { min = 1 }\n"),
            "t.toml:3:8: missing required key 'max' in 'mass'");
  EXPECT_EQ(error_of("[input]\nmoves = [{ position = [1, 2] }]\n"),
            "t.toml:2:10: missing required key 'frame' in 'input.moves[0]'");
}

TEST(SceneFileErrors, OutOfRange) {
  EXPECT_EQ(error_of("[[bodies]]\nposition = [0, 0]\nmass = 0\n"),
            "t.toml:3:8: 'mass' must be > 0, got 0");
  EXPECT_EQ(error_of("[[bodies]]\nposition = [0, 0]\nmass = -1.5\n"),
            "t.toml:3:8: 'mass' must be > 0, got -1.5");
  EXPECT_EQ(error_of("[[bodies]]\nposition = [0, 0]\nmass = { min = -1, max = 2 }\n"),
            "t.toml:3:16: 'mass.min' must be > 0, got -1");
  EXPECT_EQ(error_of("[[bodies]]\ncount = 3\nposition = [0, 0]\nmass = { start = 2, step = -1 }\n"),
            "t.toml:4:8: 'mass' of the last body (2) would be 0; masses must be > 0");
  EXPECT_EQ(error_of("[[bodies]]\ncount = -1\nposition = [0, 0]\nmass = 1\n"),
            "t.toml:2:9: 'count' must be between 0 and 10000000, got -1");
  EXPECT_EQ(error_of("[[bodies]]\ncount = 10000001\nposition = [0, 0]\nmass = 1\n"),
            "t.toml:2:9: 'count' must be between 0 and 10000000, got 10000001");
  EXPECT_EQ(error_of("[[bodies]]\ncount = 6000000\nposition = [0, 0]\nmass = 1\n"
                     "[[bodies]]\ncount = 6000000\nposition = [0, 0]\nmass = 1\n"),
            "t.toml:6:9: more than 10000000 bodies in all (6000000 before this group)");
  EXPECT_EQ(error_of("frames = -1\n"),
            "t.toml:1:10: 'frames' must be between 0 and 10000000, got -1");
  EXPECT_EQ(error_of("frames = 10_000_001\n"),
            "t.toml:1:10: 'frames' must be between 0 and 10000000, got 10000001");
  EXPECT_EQ(error_of("seed = 4294967296\n"),
            "t.toml:1:8: 'seed' must be between 0 and 4294967295, got 4294967296");
  EXPECT_EQ(error_of("seed = -1\n"), "t.toml:1:8: 'seed' must be between 0 and 4294967295, got -1");
  EXPECT_EQ(error_of("[world]\ndt = 0\n"), "t.toml:2:6: 'world.dt' must be > 0, got 0");
  EXPECT_EQ(error_of("[[fields]]\ntype = \"fan\"\nreach = 0\n"),
            "t.toml:3:9: 'reach' must be > 0, got 0");
  EXPECT_EQ(error_of("[[fields]]\ntype = \"liquid\"\nregion = [0, 0, -1, 10]\n"),
            "t.toml:3:17: 'region[2]' must be >= 0, got -1");
  EXPECT_EQ(error_of("[input]\nmouse_pressed = [[5, 3]]\n"),
            "t.toml:2:22: 'input.mouse_pressed[0][1]' must be between 5 and 9223372036854775807, "
            "got 3");
  EXPECT_EQ(error_of("[input]\nmoves = [{ frame = 5, position = [0, 0] }, { frame = 3, position = "
                     "[0, 0] }]\n"),
            "t.toml:2:54: mouse moves must be sorted by frame (frame 3 comes after frame 5)");
}

TEST(SceneFileErrors, NanAndInfinity) {
  EXPECT_EQ(error_of("[[bodies]]\nposition = [0, 0]\nmass = nan\n"),
            "t.toml:3:8: 'mass' must be a finite number, got nan");
  EXPECT_EQ(error_of("[[fields]]\ntype = \"gravity\"\ng = [0, -inf]\n"),
            "t.toml:3:9: 'g[1]' must be a finite number, got -inf");
  EXPECT_EQ(error_of("[canvas]\nwidth = +inf\n"),
            "t.toml:2:9: 'canvas.width' must be a finite number, got inf");
  EXPECT_EQ(error_of("[[fields]]\ntype = \"attractor\"\nlaw = { G = nan }\n"),
            "t.toml:3:13: 'law.G' must be a finite number, got nan");
}

TEST(SceneFileErrors, UnknownChoiceListsTheValidOnes) {
  EXPECT_EQ(error_of("[world]\nintegrator = \"rk5\"\n"),
            "t.toml:2:14: 'world.integrator' must be one of semi_implicit_euler, velocity_verlet, "
            "rk4, ias15, yoshida4, yoshida6 (got 'rk5'; did you mean 'rk4'?)");
  EXPECT_EQ(error_of("[boundary]\nkind = \"bounce\"\nedges = [\"left\", \"floor\"]\n"),
            "t.toml:3:18: 'boundary.edges[1]' must be one of left, right, top, bottom (got "
            "'floor')");
  EXPECT_EQ(
      error_of("[[fields]]\ntype = \"gravty\"\n"),
      "t.toml:2:8: 'type' must be one of gravity, wind, noise_wind, helium, fan, edge_force, "
      "friction, liquid, drag, lift, attractor, mutual_attraction (got 'gravty'; did you mean "
      "'gravity'?)");
  EXPECT_THAT(error_of("on_press = \"click\"\n"),
              StartsWith("t.toml:1:12: 'on_press' must be one of none, reset"));
}

TEST(SceneFileErrors, CustomForceCantBeWritten) {
  EXPECT_THAT(error_of("[[fields]]\ntype = \"custom_force\"\n"),
              StartsWith("t.toml:2:8: a custom_force can't be written in a scene file"));
}

TEST(SceneFileErrors, BindingsOnTheWrongField) {
  EXPECT_EQ(error_of("[[fields]]\ntype = \"gravity\"\nfollow_mouse = true\n"),
            "t.toml:3:16: only a fan or an attractor can follow the mouse");
  EXPECT_EQ(error_of("[[fields]]\ntype = \"fan\"\ndraggable = true\n"),
            "t.toml:3:13: only an attractor can be dragged");
}

TEST(SceneFileErrors, ConflictsAndDuplicates) {
  EXPECT_EQ(error_of("[[bodies]]\nposition = [0, 0]\nx = 1\nmass = 1\n"),
            "t.toml:2:12: give either 'position' or 'x' and 'y', not both");
  EXPECT_EQ(
      error_of("[[bodies]]\nposition = [0, 0]\nmass = { min = 1, max = 2, step = 1 }\n"),
      "t.toml:3:8: 'mass' is either { min = a, max = b } or { start = a, step = b }, not both");
  EXPECT_EQ(error_of("[boundary]\nkind = \"wrap\"\nedges = [\"top\", \"top\"]\n"),
            "t.toml:3:17: edge 'top' is listed twice");
  EXPECT_EQ(
      error_of("[world]\nintegrator = \"rk4\"\nupdate_order = \"sequential\"\n"),
      "t.toml:3:16: update_order = \"sequential\" needs integrator = \"semi_implicit_euler\"");
}

TEST(SceneFileErrors, ValidationOfALawPointsAtIt) {
  // AttractionLaw::validate's message, placed at the law.
  EXPECT_EQ(error_of("[[fields]]\ntype = \"attractor\"\nlaw = { min = 30, max = 25 }\n"),
            "t.toml:3:7: attractor: attraction law: min must not exceed max (got min 30, max 25)");
  // Softening under the default clamp ("distance") would be silently unused.
  EXPECT_EQ(error_of("[[fields]]\ntype = \"mutual_attraction\"\nlaw = { softening = 4 }\n"),
            "t.toml:3:7: mutual_attraction: attraction law: softening needs clamp \"none\" (got "
            "softening 4 with a clamped law, whose min bounds the force)");
}

TEST(SceneFileErrors, OneLine) {
  const std::string m = error_of("[[bodies]]\n\"a\\nb\" = 1\n");
  EXPECT_EQ(m.find('\n'), std::string::npos) << m;
}

// --- values -------------------------------------------------------------------------------

TEST(SceneFile, IntegersAreAcceptedAsFloats) {
  const Scene s = calder::parse_scene(R"(
[canvas]
width = 800
height = 600
[world]
dt = 2
[[bodies]]
position = [1, -2]
mass = 3
radius = 4
friction = 0
[[fields]]
type = "gravity"
g = [0, 1]
)",
                                      "t.toml");
  EXPECT_EQ(s.world.width, 800.0);
  EXPECT_EQ(s.world.height, 600.0);
  EXPECT_EQ(s.world.dt, 2.0);
  ASSERT_EQ(s.bodies.size(), 1u);
  EXPECT_EQ(s.bodies[0].x.value, 1.0);
  EXPECT_EQ(s.bodies[0].y.value, -2.0);
  EXPECT_EQ(s.bodies[0].mass.value, 3.0);
  EXPECT_EQ(s.bodies[0].radius.k, 4.0);
  EXPECT_EQ(s.bodies[0].friction, std::optional<double>(0.0));
  EXPECT_EQ(std::get<calder::Gravity>(s.fields[0].field).g, (calder::Vec2{0.0, 1.0}));
}

TEST(SceneFile, Defaults) {
  const Scene s = calder::parse_scene(R"(
[[bodies]]
position = [10, 20]
mass = 2
)",
                                      "some/dir/rain.toml");
  const Scene plain;
  EXPECT_EQ(s.name, "rain");  // the file's stem
  EXPECT_EQ(s.description, "");
  EXPECT_EQ(s.frames, 600);
  EXPECT_EQ(s.world.seed, 0u);
  EXPECT_EQ(s.world.width, 640.0);
  EXPECT_EQ(s.world.height, 240.0);
  EXPECT_EQ(s.world.dt, 1.0);
  EXPECT_EQ(s.world.integrator, calder::Integrator::semi_implicit_euler);
  EXPECT_EQ(s.world.update_order, calder::UpdateOrder::simultaneous);
  EXPECT_EQ(s.world.boundary.kind, calder::BoundaryKind::none);
  EXPECT_EQ(s.on_press, calder::PressAction::none);
  EXPECT_EQ(s.origin, calder::Vec2{});
  EXPECT_TRUE(s.input.mouse_pressed.empty());
  const calder::BodyGroup& g = s.bodies.at(0);
  EXPECT_EQ(g.count, 1u);
  EXPECT_EQ(g.layout, calder::BodyGroup::Layout::grid);
  EXPECT_EQ(g.vx.kind, calder::Draw::Kind::fixed);
  EXPECT_EQ(g.vx.value, 0.0);
  EXPECT_EQ(g.vy.value, 0.0);
  EXPECT_EQ(g.radius.kind, calder::RadiusRule::Kind::fixed);
  EXPECT_EQ(g.radius.k, 0.0);
  EXPECT_FALSE(g.friction.has_value());
  EXPECT_EQ(g.drag_area, 1.0);
  EXPECT_EQ(calder::to_toml(s).find("[input]"), std::string::npos);
  (void)plain;
}

TEST(SceneFile, BoundaryDefaultsOnceAKindIsGiven) {
  const Scene s = calder::parse_scene("[boundary]\nkind = \"bounce\"\n", "t.toml");
  const calder::Boundary& b = s.world.boundary;
  EXPECT_EQ(b.kind, calder::BoundaryKind::bounce);
  EXPECT_EQ(b.restitution, 1.0);
  EXPECT_FALSE(b.use_radius);
  EXPECT_TRUE(b.edges.left && b.edges.right && b.edges.top && b.edges.bottom);
  EXPECT_EQ(b.timing, calder::BoundaryTiming::after_update);
  const Scene none = calder::parse_scene("[boundary]\nkind = \"wrap\"\nedges = []\n", "t.toml");
  EXPECT_FALSE(none.world.boundary.edges.left || none.world.boundary.edges.right ||
               none.world.boundary.edges.top || none.world.boundary.edges.bottom);
}

TEST(SceneFile, FieldDefaultsAreTheStructDefaults) {
  std::string text;
  for (const char* type :
       {"gravity", "wind", "noise_wind", "helium", "fan", "edge_force", "friction", "liquid",
        "drag", "lift", "attractor", "mutual_attraction"}) {
    text += std::string("[[fields]]\ntype = \"") + type + "\"\n";
  }
  const Scene s = calder::parse_scene(text, "t.toml");
  ASSERT_EQ(s.fields.size(), 12u);
  // Each field, written, is the same as the default-constructed struct.
  const calder::Field expected[] = {
      calder::Gravity{}, calder::Wind{},      calder::NoiseWind{}, calder::Helium{},
      calder::Fan{},     calder::EdgeForce{}, calder::Friction{},  calder::Liquid{},
      calder::Drag{},    calder::Lift{},      calder::Attractor{}, calder::MutualAttraction{}};
  Scene reference;
  reference.name = s.name;
  for (const calder::Field& f : expected) reference.fields.push_back({f, {}});
  EXPECT_EQ(calder::to_toml(s), calder::to_toml(reference));
  for (const calder::SceneField& f : s.fields) {
    EXPECT_TRUE(std::visit([](const auto& field) { return field.enabled; }, f.field));
    EXPECT_TRUE(f.visible);
    EXPECT_FALSE(f.binding.while_pressed || f.binding.follow_mouse || f.binding.draggable);
  }
  const auto& law = std::get<calder::Attractor>(s.fields[10].field).law;
  const calder::AttractionLaw book{};
  EXPECT_EQ(law.G, book.G);
  EXPECT_EQ(law.clamp, book.clamp);
  EXPECT_EQ(law.min, book.min);
  EXPECT_EQ(law.max, book.max);
  EXPECT_EQ(law.product, book.product);
}

TEST(SceneFile, GridDrawsInTheDocumentedOrder) {
  const Scene s = calder::parse_scene(R"(
seed = 7
[[bodies]]
count = 4
x = { min = 0, max = 640 }
y = { start = 10, step = 5 }
mass = { min = 1, max = 2 }
vx = { min = -1, max = 1 }
vy = 0.5
radius = { per_mass = 8 }
[[bodies]]
count = 2
x = 3
y = { min = 100, max = 50 }
mass = 1
velocity = [0, 0]
)",
                                      "t.toml");
  Simulation sim(s);
  calder::Random rng(7);
  const calder::BodyView b = sim.world().bodies();
  ASSERT_EQ(b.size(), 6u);
  for (std::size_t i = 0; i < 4; ++i) {
    const double x = rng.random(0.0, 640.0);
    const double mass = rng.random(1.0, 2.0);
    const double vx = rng.random(-1.0, 1.0);
    EXPECT_EQ(bits(b.x[i]), bits(x)) << i;
    EXPECT_EQ(bits(b.y[i]), bits(10.0 + static_cast<double>(i) * 5.0)) << i;
    EXPECT_EQ(bits(b.mass[i]), bits(mass)) << i;
    EXPECT_EQ(bits(b.vx[i]), bits(vx)) << i;
    EXPECT_EQ(b.vy[i], 0.5);
    EXPECT_EQ(bits(b.radius[i]), bits(mass * 8.0));
  }
  for (std::size_t i = 4; i < 6; ++i) {
    EXPECT_EQ(b.x[i], 3.0);
    EXPECT_EQ(bits(b.y[i]), bits(rng.random(100.0, 50.0)));  // p5 swaps the bounds
  }
}

TEST(SceneFile, OrbitDrawsInTheDocumentedOrder) {
  const Scene s = calder::parse_scene(R"(
seed = 3
[[bodies]]
count = 3
layout = "orbit"
center = [5, 6]
distance = { min = 100, max = 150 }
speed = { min = 10, max = 15 }
mass = { min = 1, max = 4 }
radius = { per_sqrt_mass = 1 }
)",
                                      "t.toml");
  Simulation sim(s);
  calder::Random rng(3);
  const calder::BodyView b = sim.world().bodies();
  ASSERT_EQ(b.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    calder::Vec2 direction = rng.random2d();
    calder::Vec2 velocity = direction;
    velocity.set_mag(rng.random(10.0, 15.0));
    direction.set_mag(rng.random(100.0, 150.0));
    velocity.rotate(1.5707963267948966);
    const double mass = rng.random(1.0, 4.0);
    const calder::Vec2 position = calder::Vec2{5.0, 6.0} + direction;
    EXPECT_EQ(bits(b.x[i]), bits(position.x)) << i;
    EXPECT_EQ(bits(b.y[i]), bits(position.y)) << i;
    EXPECT_EQ(bits(b.vx[i]), bits(velocity.x)) << i;
    EXPECT_EQ(bits(b.vy[i]), bits(velocity.y)) << i;
    EXPECT_EQ(bits(b.mass[i]), bits(mass)) << i;
  }
}

// --- kepler = { ... }: a body at the pericentre of a Kepler orbit ------------------------

// A [[bodies]] table of one body on the orbit, after `extra` lines.
std::string kepler_body(std::string_view orbit, std::string_view extra = "") {
  return "[[bodies]]\n" + std::string(extra) + "kepler = " + std::string(orbit) + "\nmass = 1\n";
}

TEST(SceneFileKepler, TheOrbitStartsAtPericentreAtTheVisVivaSpeed) {
  // a = 2, e = 0.5 about a GM of 3 at (3, 4): q = a (1 - e) = 1, and
  // v^2 = GM (2 / q - 1 / a) = 4.5.
  const Scene s = calder::parse_scene(
      kepler_body("{ GM = 3, semi_major_axis = 2, eccentricity = 0.5, focus = [3, 4] }"), "t.toml");
  Simulation sim(s);
  const calder::BodyView b = sim.world().bodies();
  ASSERT_EQ(b.size(), 1u);
  EXPECT_DOUBLE_EQ(b.x[0], 4.0);
  EXPECT_DOUBLE_EQ(b.y[0], 4.0);
  EXPECT_EQ(b.vx[0], 0.0);
  EXPECT_DOUBLE_EQ(b.vy[0], std::sqrt(4.5));
  // Without eccentricity the orbit is a circle: v = sqrt(GM / a), at a from the origin.
  const Scene circle =
      calder::parse_scene(kepler_body("{ GM = 8, semi_major_axis = 2 }"), "t.toml");
  Simulation round(circle);
  EXPECT_EQ(round.world().bodies().x[0], 2.0);
  EXPECT_EQ(round.world().bodies().y[0], 0.0);
  EXPECT_DOUBLE_EQ(round.world().bodies().vy[0], 2.0);
}

TEST(SceneFileKepler, SceneFileGivesTheBuiltinBitsForEccentricity09) {
  // scenes/kepler.toml states the built-in's orbit as the key: the same bits
  // as the numbers the built-in had written out, (10, 0) and sqrt(190000).
  const Scene s = calder::load_scene_file(scene_path("kepler"));
  ASSERT_EQ(s.bodies.size(), 1u);
  EXPECT_EQ(bits(s.bodies[0].x.value), bits(10.0));
  EXPECT_EQ(bits(s.bodies[0].y.value), bits(0.0));
  EXPECT_EQ(bits(s.bodies[0].vx.value), bits(0.0));
  EXPECT_EQ(bits(s.bodies[0].vy.value), bits(std::sqrt(190000.0)));
}

TEST(SceneFileKepler, RefusesAnEccentricityOutsideTheEllipses) {
  for (const char* e : {"1", "1.5", "-0.1", "1e300"}) {
    const std::string orbit =
        std::string("{ GM = 1, semi_major_axis = 1, eccentricity = ") + e + " }";
    EXPECT_EQ(error_of(kepler_body(orbit)),
              std::string("t.toml:2:56: 'kepler.eccentricity' must be >= 0 and < 1 (an ellipse), "
                          "got ") +
                  (std::string(e) == "1e300" ? "1e+300" : e))
        << e;
  }
  EXPECT_EQ(error_of(kepler_body("{ GM = 1, semi_major_axis = 1, eccentricity = nan }")),
            "t.toml:2:56: 'kepler.eccentricity' must be a finite number, got nan");
  EXPECT_EQ(error_of(kepler_body("{ GM = 1, semi_major_axis = 1, eccentricity = \"high\" }")),
            "t.toml:2:56: 'kepler.eccentricity' must be a number, got a string");
  // A GM so large that the pericentre speed overflows.
  EXPECT_EQ(error_of(kepler_body("{ GM = 1e308, semi_major_axis = 1, eccentricity = 0.9 }")),
            "t.toml:2:10: 'kepler': the pericentre of GM 1e+308, a 1, e 0.9 is not a finite "
            "place and speed");
}

TEST(SceneFileKepler, RefusesWhatTheOrbitCannotBe) {
  EXPECT_EQ(error_of(kepler_body("{ semi_major_axis = 1 }")),
            "t.toml:2:10: missing required key 'GM' in 'kepler'");
  EXPECT_EQ(error_of(kepler_body("{ GM = 1, semi_major_axis = 0 }")),
            "t.toml:2:38: 'kepler.semi_major_axis' must be > 0, got 0");
  EXPECT_EQ(error_of(kepler_body("{ GM = -1, semi_major_axis = 1 }")),
            "t.toml:2:17: 'kepler.GM' must be > 0, got -1");
  EXPECT_THAT(error_of(kepler_body("{ GM = 1, semi_major_axis = 1, eccentricty = 0.5 }")),
              StartsWith("t.toml:2:41: unknown key 'eccentricty' in 'kepler' (did you mean "
                         "'eccentricity'?)"));
  EXPECT_EQ(error_of(kepler_body("0.9")),
            "t.toml:2:10: 'kepler' must be an inline table { GM = ..., semi_major_axis = ... }, "
            "got a float");
  EXPECT_EQ(error_of(kepler_body("{ GM = 1, semi_major_axis = 1 }", "position = [0, 0]\n")),
            "t.toml:2:1: 'position' can't be given with 'kepler' (it places the body at the "
            "orbit's pericentre, moving)");
  EXPECT_EQ(error_of(kepler_body("{ GM = 1, semi_major_axis = 1 }", "count = 2\n")),
            "t.toml:2:1: 'kepler' starts one body, but 'count' is 2 (one [[bodies]] table per "
            "orbit)");
  EXPECT_EQ(error_of(kepler_body("{ GM = 1, semi_major_axis = 1 }", "layout = \"orbit\"\n")),
            "t.toml:3:1: 'kepler' is not used with layout = \"orbit\" (it places bodies with "
            "center, distance and speed)");
}

// The physics of another eccentricity from the key: e = 0.5 for 1,000
// orbits (period 2 pi: a = 100 px, GM = 100^3), one frame per orbit. The
// energy stays -GM m / (2 a) to 1e-12, and after each orbit the body is back
// at its pericentre, (a (1 - e), 0) = (50, 0), moving along +y.
TEST(SceneFileKepler, Eccentricity05Over1000OrbitsKeepsEnergyAndPericentre) {
  Scene s = calder::parse_scene(R"(
frames = 1000
[world]
dt = 6.283185307179586
integrator = "ias15"
[[bodies]]
kepler = { GM = 1e6, semi_major_axis = 100, eccentricity = 0.5 }
mass = 1
[[fields]]
type = "attractor"
position = [0, 0]
mass = 1
law = { G = 1e6, clamp = "none" }
)",
                                "t.toml");
  Simulation sim(s);
  calder::World& world = sim.world();
  const double e0 = calder::total_energy(world);
  EXPECT_NEAR(e0, -0.5 * 1e4, 1e-9);
  double worst = 0.0;
  while (sim.frame() < sim.scene().frames) {
    sim.step();
    worst = std::max(worst, std::fabs((calder::total_energy(world) - e0) / e0));
  }
  EXPECT_LT(worst, 1e-12);
  const calder::Vec2 p = world.position(world.body(0));
  const calder::Vec2 v = world.velocity(world.body(0));
  EXPECT_NEAR(p.x, 50.0, 1e-7);
  EXPECT_NEAR(p.y, 0.0, 1e-6);  // the phase after 1,000 orbits: 1e-6 px / 173 px per unit time
  EXPECT_NEAR(v.x, 0.0, 1e-6);
  EXPECT_GT(v.y, 0.0);
  // The eccentricity vector (v x (r x v)) / GM - r / |r| points at the pericentre.
  const double h = p.x * v.y - p.y * v.x;
  const calder::Vec2 ecc{v.y * h / 1e6 - p.x / p.mag(), -v.x * h / 1e6 - p.y / p.mag()};
  EXPECT_NEAR(ecc.mag(), 0.5, 1e-11);
  EXPECT_NEAR(std::atan2(ecc.y, ecc.x), 0.0, 1e-11);
}

TEST(SceneFile, InputScript) {
  const Scene s = calder::parse_scene(R"(
[input]
mouse_pressed = [[100, 160], [200, 200]]
mouse = [320, 120]
moves = [{ frame = 130, position = [300, 100] }, { frame = 140, position = [10, 20] }]
)",
                                      "t.toml");
  EXPECT_FALSE(s.input.pressed_at(99));
  EXPECT_TRUE(s.input.pressed_at(100));
  EXPECT_TRUE(s.input.pressed_at(160));
  EXPECT_FALSE(s.input.pressed_at(161));
  EXPECT_TRUE(s.input.pressed_at(200));
  EXPECT_EQ(s.input.mouse_at(129), (calder::Vec2{320.0, 120.0}));
  EXPECT_EQ(s.input.mouse_at(130), (calder::Vec2{300.0, 100.0}));
  EXPECT_EQ(s.input.mouse_at(1000), (calder::Vec2{10.0, 20.0}));
}

// --- to_toml ------------------------------------------------------------------------------

TEST(SceneFileToToml, NumbersRoundTripExactly) {
  Scene s;
  s.name = "numbers \"quoted\"\tand\\escaped\n";
  const double values[] = {0.1,     -0.0,  1e-300,    123456789012345680000.0, 1e21,
                           -2.5e-7, 640.0, 1.0 / 3.0, 9007199254740993.0,      -1e16};
  for (const double v : values) {
    calder::BodyGroup g;
    g.x = calder::Draw::fixed(v);
    g.y = calder::Draw::linear(v, v);
    g.mass = calder::Draw::uniform(1.0 / 3.0, 5e-324 + 1.0);
    s.bodies.push_back(g);
  }
  const std::string text = calder::to_toml(s);
  const Scene back = calder::parse_scene(text, "t.toml");
  EXPECT_EQ(back.name, s.name);
  ASSERT_EQ(back.bodies.size(), std::size(values));
  for (std::size_t i = 0; i < back.bodies.size(); ++i) {
    EXPECT_EQ(bits(back.bodies[i].x.value), bits(values[i])) << values[i];
    EXPECT_EQ(bits(back.bodies[i].y.value), bits(values[i])) << values[i];
    EXPECT_EQ(bits(back.bodies[i].y.step), bits(values[i])) << values[i];
  }
  EXPECT_EQ(calder::to_toml(back), text);
  EXPECT_EQ(text.find("nan"), std::string::npos);
  EXPECT_THAT(text, HasSubstr("-0.0"));
}

TEST(SceneFileToToml, RefusesWhatAFileCantHold) {
  Scene custom;
  custom.fields.push_back(
      {calder::CustomForce{[](const calder::FieldContext&, std::size_t) { return calder::Vec2{}; }},
       {}});
  EXPECT_THROW((void)calder::to_toml(custom), calder::Error);
  Scene law;
  law.fields.push_back({calder::Attractor{.law = calder::AttractionLaw::from(
                                              [](double, double, double) { return 1.0; })},
                        {}});
  EXPECT_THROW((void)calder::to_toml(law), calder::Error);
  Scene bad;
  bad.world.dt = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW((void)calder::to_toml(bad), calder::Error);
}

TEST(SceneFileToToml, EverythingRoundTrips) {
  Scene s = calder::builtin_scene("example-2.4");
  s.world.integrator = calder::Integrator::rk4;
  s.world.dt = 0.5;
  s.world.seed = 4294967295u;
  s.world.boundary = calder::Boundary::wrap(true);
  s.world.boundary.edges.top = false;
  s.frames = 10'000'000;
  s.on_press = calder::PressAction::reset;
  s.origin = {1.5, -2.5};
  s.input = press_script();
  s.bodies.at(0).friction = 0.25;
  s.bodies.at(0).drag_area = 2.0;
  s.bodies.at(0).vx = calder::Draw::uniform(-1.0, 1.0);
  s.fields.push_back(
      {calder::Fan{.position = {1, 2}, .strength = 3, .reach = 4}, {.follow_mouse = true}});
  s.fields.push_back({calder::Drag{.c = 0.5, .never_reverse = true, .enabled = false}, {}});
  s.fields.push_back({calder::MutualAttraction{.law = calder::AttractionLaw::newtonian(2.0, 0.25),
                                               .order = calder::PairOrder::by_source,
                                               .central = calder::CentralBody{{3, 4}, 50}},
                      {}});
  s.fields.back().visible = false;
  const std::string text = calder::to_toml(s);
  const Scene back = calder::parse_scene(text, "t.toml");
  EXPECT_EQ(calder::to_toml(back), text);
  Simulation a(s, 1);
  Simulation b(back, 1);
  for (int i = 0; i < 200; ++i) {
    a.step();
    b.step();
  }
  EXPECT_EQ(calder::state_hash(a.world()), calder::state_hash(b.world()));
}

// --- docs/SCENES.md: every ```toml block is a scene that parses and runs ------------------

TEST(SceneFileDocs, EveryExampleParsesAndRuns) {
  const std::string path = std::string(CALDER_SOURCE_DIR) + "/docs/SCENES.md";
  std::ifstream file(path);
  ASSERT_TRUE(file.good()) << path;
  std::string line;
  int number = 0;
  int start = 0;
  bool inside = false;
  std::string block;
  int blocks = 0;
  while (std::getline(file, line)) {
    ++number;
    if (!inside && line == "```toml") {
      inside = true;
      start = number + 1;
      block.clear();
    } else if (inside && line == "```") {
      inside = false;
      ++blocks;
      const std::string where = path + ":" + std::to_string(start);
      SCOPED_TRACE(where);
      try {
        const Scene s = calder::parse_scene(block, where);
        Simulation sim(s, 1);
        for (int i = 0; i < 10; ++i) sim.step();
        EXPECT_EQ(calder::to_toml(calder::parse_scene(calder::to_toml(s), where)),
                  calder::to_toml(s));
      } catch (const calder::Error& e) {
        ADD_FAILURE() << e.what();
      }
    } else if (inside) {
      block += line;
      block += '\n';
    }
  }
  EXPECT_FALSE(inside) << "unterminated ```toml block at line " << start;
  EXPECT_GE(blocks, 14);  // one per force at least
}

// --- limits on the raw text -------------------------------------------------------

std::string message_of_text(const std::string& text) {
  try {
    (void)calder::parse_scene(text, "t.toml");
  } catch (const SceneFileError& e) {
    return e.what();
  }
  return "";
}

std::string dotted_key(std::size_t parts) {
  std::string key = "a";
  for (std::size_t i = 1; i < parts; ++i) key += ".a";
  return key;
}

TEST(SceneFileLimits, NestingUpTo32IsParsedDeeperIsRefusedBeforeToml) {
  // 32 parts reach toml++ (an unknown key then), 33 are refused by the limit.
  EXPECT_THAT(message_of_text(dotted_key(32) + " = 1\n"), HasSubstr("unknown key 'a'"));
  EXPECT_EQ(message_of_text(dotted_key(33) + " = 1\n"),
            "t.toml:1:1: keys, tables and arrays nested more than 32 deep (the limit of scene "
            "files)");
  EXPECT_THAT(message_of_text("[" + dotted_key(33) + "]\n"), HasSubstr("nested more than 32"));
  // A table header's parts add to its keys' parts.
  EXPECT_THAT(message_of_text("[" + dotted_key(20) + "]\n" + dotted_key(13) + " = 1\n"),
              HasSubstr("t.toml:2:1: keys, tables and arrays nested"));
  // Arrays and inline tables within each other.
  EXPECT_THAT(message_of_text("x = " + std::string(32, '[') + "\n"), HasSubstr("nested more"));
  EXPECT_THAT(message_of_text("x = " + std::string(31, '[') + std::string(31, ']') + "\n"),
              Not(HasSubstr("nested more")));
  // Dots in strings and numbers are no key parts.
  EXPECT_THAT(message_of_text("name = \"" + dotted_key(100) + "\"\nx = [1.5, 2.5]\n"),
              HasSubstr("unknown key 'x'"));
}

TEST(SceneFileLimits, KeysLinesAndFileSize) {
  EXPECT_THAT(message_of_text(std::string(256, 'k') + " = 1\n"), HasSubstr("unknown key 'kkk"));
  EXPECT_EQ(message_of_text(std::string(257, 'k') + " = 1\n"),
            "t.toml:1:1: a key longer than 256 bytes (the limit of scene files)");
  EXPECT_EQ(message_of_text("\"" + std::string(300, 'k') + "\" = 1\n"),
            "t.toml:1:1: a key longer than 256 bytes (the limit of scene files)");
  EXPECT_EQ(message_of_text("name = \"" + std::string(70000, 'n') + "\"\n"),
            "t.toml:1:1: a line longer than 65536 bytes (the limit of scene files)");
  EXPECT_EQ(message_of_text(std::string((std::size_t{4} << 20) + 1, '\n')),
            "t.toml:1:1: larger than 4 MiB, the limit of scene files");
}

TEST(SceneFileLimits, EncodingAndControlCharacters) {
  EXPECT_EQ(message_of_text("name = \"\xC0\xAF\"\n"), "t.toml:1:9: the file is not valid UTF-8");
  EXPECT_EQ(message_of_text("name = \"\xED\xA0\x80\"\n"),
            "t.toml:1:9: the file is not valid UTF-8");  // a surrogate
  EXPECT_EQ(message_of_text("x = \xEF\xB0\x80\n"),
            "t.toml:1:5: non-ASCII character U+FC00 outside a string or comment (TOML allows it "
            "only there)");
  EXPECT_EQ(message_of_text("name = \"a\x1b[2J\"\n"),
            "t.toml:1:10: control character U+001B (only tab and line breaks may appear)");
  // In strings and comments non-ASCII text is fine.
  EXPECT_EQ(calder::parse_scene("name = \"\xEF\xB0\x80 \xC3\xA9\" # \xEF\xBB\xBE\n", "t.toml").name,
            "\xEF\xB0\x80 \xC3\xA9");
  // Escaped control characters reach messages escaped.
  EXPECT_THAT(message_of_text("\"a\\u001bb\" = 1\n"), HasSubstr("unknown key 'a\\x1bb'"));
}

TEST(SceneFileLimits, DidYouMeanCostsNoMoreForAHugeKey) {
  // A key within the limits but unlike any: no suggestion, the key cut short.
  const std::string message = message_of_text(std::string(200, 'q') + " = 1\n");
  EXPECT_THAT(message, HasSubstr("unknown key 'qqqq"));
  EXPECT_THAT(message, HasSubstr("...'"));
  EXPECT_THAT(message, Not(HasSubstr("did you mean")));
  EXPECT_LT(message.size(), 400u);
}

// --- property: random scenes, valid and slightly invalid ------------------------------
// Each built-in scene file with its numbers replaced at random (seeded) by
// extreme but finite values, zero, negatives and huge counts: each either
// runs a few hundred frames with finite bodies, or stops with a one-line
// error naming the file; never a crash, a hang or a silent NaN.
TEST(SceneFileProperty, RandomisedScenesRunOrFailWithOneLine) {
  const std::vector<std::string> pool = {"0",       "-1",       "1e-300", "1e300", "-1e300",
                                         "1.7e308", "5e-324",   "1e6",    "1e15",  "2",
                                         "0.5",     "10000001", "-0.0",   "3",     "1e-3"};
  std::mt19937 generator(20261124);
  std::size_t ran = 0;
  std::size_t refused = 0;
  std::size_t failed_in_run = 0;
  for (const calder::SceneInfo& info : calder::builtin_scenes()) {
    std::ifstream in(scene_path(info.name));
    std::stringstream buffer;
    buffer << in.rdbuf();
    const std::string original = buffer.str();
    for (int variant = 0; variant < 12; ++variant) {
      // Replace numbers (not inside strings: scene files quote no digits
      // but in names and descriptions, which stay valid either way).
      std::string text;
      std::uniform_real_distribution<double> coin(0.0, 1.0);
      for (std::size_t i = 0; i < original.size();) {
        const bool starts_number =
            (std::isdigit(static_cast<unsigned char>(original[i])) != 0) &&
            (i == 0 || original[i - 1] == ' ' || original[i - 1] == '[' || original[i - 1] == '-');
        if (!starts_number) {
          text += original[i++];
          continue;
        }
        std::size_t end = i;
        while (end < original.size() &&
               (std::isalnum(static_cast<unsigned char>(original[end])) != 0 ||
                original[end] == '.' || original[end] == '_' ||
                ((original[end] == '-' || original[end] == '+') && original[end - 1] == 'e'))) {
          ++end;
        }
        text +=
            coin(generator) < 0.3
                ? pool[std::uniform_int_distribution<std::size_t>(0, pool.size() - 1)(generator)]
                : original.substr(i, end - i);
        i = end;
      }
      const std::string source = info.name + "-variant-" + std::to_string(variant) + ".toml";
      std::optional<Scene> scene;
      try {
        scene = calder::parse_scene(text, source);
      } catch (const SceneFileError& e) {
        const std::string message = e.what();
        EXPECT_THAT(message, StartsWith(source + ":"));
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        ++refused;
        continue;
      }
      std::size_t bodies = 0;
      for (const calder::BodyGroup& group : scene->bodies) bodies += group.count;
      if (bodies > 300) continue;  // the work budget's business, not this test's
      scene->frames = std::min<std::int64_t>(scene->frames, 300);
      try {
        Simulation simulation(*scene);
        while (simulation.frame() < scene->frames) {
          simulation.step();
          const calder::BodyView view = simulation.world().bodies();
          for (std::size_t i = 0; i < view.size(); ++i) {
            ASSERT_TRUE(std::isfinite(view.x[i]) && std::isfinite(view.y[i]))
                << source << ": body " << i << " not finite at frame " << simulation.frame();
          }
        }
        ++ran;
      } catch (const calder::Error& e) {
        const std::string message = e.what();
        EXPECT_FALSE(message.empty());
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        ++failed_in_run;
      }
    }
  }
  // The mix is broad: some variants run, some are refused, some fail in the run.
  EXPECT_GT(ran, 20u);
  EXPECT_GT(refused, 20u);
  std::cout << "randomised scenes: " << ran << " ran, " << refused << " refused, " << failed_in_run
            << " stopped with an error\n";
}

// --- every field kind, as its FieldKind describes it (calder/fields.hpp) ------------------
//
// The kinds are enumerated from the Field variant, so a kind added later is
// checked here without a line of this test changing.

template <class Check>
void for_each_field_kind(Check check) {
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (check.template operator()<std::variant_alternative_t<I, calder::Field>>(), ...);
  }
  (std::make_index_sequence<std::variant_size_v<calder::Field>>());
}

// A valid value unlike the default, so that a round trip that drops it fails.
double changed(double v, calder::Range range) {
  return range == calder::Range::unit_interval ? v / 2.0 + 0.125 : v * 1.5 + 0.75;
}
int changed(int v, calder::Range) { return v + 3; }
bool changed(bool v, calder::Range) { return !v; }
calder::Vec2 changed(calder::Vec2 v, calder::Range) { return v + calder::Vec2{1.25, -2.5}; }
calder::Rect changed(calder::Rect r, calder::Range) {
  return {r.x + 1.0, r.y - 2.0, r.w + 3.0, r.h + 4.0};
}
calder::AttractionLaw changed(const calder::AttractionLaw&, calder::Range) {
  return calder::AttractionLaw::newtonian(2.5, 0.25);
}
std::optional<calder::CentralBody> changed(const std::optional<calder::CentralBody>&,
                                           calder::Range) {
  return calder::CentralBody{{3.0, 4.0}, 50.0};
}
template <class E>
requires std::is_enum_v<E> E
changed(E v, calder::Range) {  // every enumeration has a value 0 and a value 1
  return static_cast<E>(static_cast<int>(v) == 0 ? 1 : 0);
}

bool same(double a, double b) { return bits(a) == bits(b); }
bool same(calder::Vec2 a, calder::Vec2 b) { return same(a.x, b.x) && same(a.y, b.y); }
bool same(const calder::Rect& a, const calder::Rect& b) {
  return same(a.x, b.x) && same(a.y, b.y) && same(a.w, b.w) && same(a.h, b.h);
}
bool same(const calder::AttractionLaw& a, const calder::AttractionLaw& b) {
  return same(a.G, b.G) && a.clamp == b.clamp && same(a.min, b.min) && same(a.max, b.max) &&
         same(a.softening, b.softening) && a.product == b.product && same(a.exponent, b.exponent) &&
         same(a.repulsion, b.repulsion) && same(a.repulsion_exponent, b.repulsion_exponent);
}
bool same(const std::optional<calder::CentralBody>& a,
          const std::optional<calder::CentralBody>& b) {
  return a.has_value() == b.has_value() &&
         (!a || (same(a->position, b->position) && same(a->mass, b->mass)));
}
template <class T>
requires std::is_integral_v<T> || std::is_enum_v<T>
bool same(T a, T b) { return a == b; }

// A value validate must refuse (none for a boolean or an enumeration).
std::optional<double> refused(double, calder::Range range) {
  return range == calder::Range::finite ? std::numeric_limits<double>::quiet_NaN() : -1.0;
}
std::optional<int> refused(int, calder::Range) { return -1; }
std::optional<calder::Vec2> refused(calder::Vec2, calder::Range) {
  return calder::Vec2{std::numeric_limits<double>::infinity(), 0.0};
}
std::optional<calder::Rect> refused(calder::Rect, calder::Range) {
  return calder::Rect{0.0, 0.0, -1.0, 1.0};
}
std::optional<calder::AttractionLaw> refused(const calder::AttractionLaw&, calder::Range) {
  return calder::AttractionLaw::book(std::numeric_limits<double>::quiet_NaN(), 5.0, 25.0);
}
std::optional<std::optional<calder::CentralBody>> refused(const std::optional<calder::CentralBody>&,
                                                          calder::Range) {
  return std::optional<calder::CentralBody>{calder::CentralBody{{0.0, 0.0}, 0.0}};
}
template <class T>
requires std::is_same_v<T, bool> || std::is_enum_v<T> std::optional<T> refused(T, calder::Range) {
  return std::nullopt;
}

TEST(FieldKinds, EachHasItsOwnName) {
  std::vector<std::string> names;
  for_each_field_kind([&]<class F>() {
    const std::string name = calder::FieldKind<F>::name;
    EXPECT_FALSE(name.empty());
    EXPECT_EQ(calder::field_name(F{}), name);
    names.push_back(name);
  });
  std::sort(names.begin(), names.end());
  EXPECT_EQ(std::adjacent_find(names.begin(), names.end()), names.end());
  EXPECT_EQ(names.size(), std::variant_size_v<calder::Field>);
}

TEST(FieldKinds, EveryParameterRoundTripsThroughAFile) {
  int kinds = 0;
  for_each_field_kind([&]<class F>() {
    using Kind = calder::FieldKind<F>;
    if (!calder::in_scene_files<F>()) return;
    SCOPED_TRACE(Kind::name);
    ++kinds;
    F field;
    std::vector<std::string> keys;
    std::apply(
        [&](const auto&... p) {
          ((field.*p.member = changed(field.*p.member, p.range), keys.emplace_back(p.key)), ...);
        },
        Kind::parameters);
    EXPECT_FALSE(keys.empty());
    std::sort(keys.begin(), keys.end());
    EXPECT_EQ(std::adjacent_find(keys.begin(), keys.end()), keys.end()) << "a key twice";
    ASSERT_NO_THROW(calder::validate(field));
    Scene s;
    s.fields.push_back({field, {}});
    const std::string text = calder::to_toml(s);
    const Scene back = calder::parse_scene(text, "t.toml");
    ASSERT_EQ(back.fields.size(), 1u);
    const F* read = std::get_if<F>(&back.fields[0].field);
    ASSERT_NE(read, nullptr) << text;
    const F plain{};
    const auto check = [&](const auto& p) {
      EXPECT_FALSE(same(plain.*p.member, field.*p.member)) << p.key << ": not changed";
      EXPECT_TRUE(same(read->*p.member, field.*p.member)) << p.key << " in\n" << text;
    };
    std::apply([&](const auto&... p) { (check(p), ...); }, Kind::parameters);
    EXPECT_EQ(calder::to_toml(back), text);
  });
  EXPECT_EQ(kinds, static_cast<int>(std::variant_size_v<calder::Field>) - 1);  // custom_force
}

TEST(FieldKinds, EveryNumberIsValidated) {
  for_each_field_kind([&]<class F>() {
    using Kind = calder::FieldKind<F>;
    SCOPED_TRACE(Kind::name);
    std::apply(
        [&](const auto&... p) {
          [[maybe_unused]] const auto check = [&](const auto& parameter) {
            F field;
            const auto bad = refused(field.*parameter.member, parameter.range);
            if (!bad) return;
            field.*parameter.member = *bad;
            try {
              calder::validate(field);
              ADD_FAILURE() << parameter.key << ": no error";
            } catch (const calder::Error& e) {
              EXPECT_THAT(e.what(), StartsWith(std::string("field ") + Kind::name + ": "));
              EXPECT_THAT(e.what(), HasSubstr(parameter.key));
            }
          };
          (check(p), ...);
        },
        Kind::parameters);
  });
}

}  // namespace
