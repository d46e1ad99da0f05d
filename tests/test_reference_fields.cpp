// SPDX-License-Identifier: MIT
// The p5.js reference trajectories of tests/reference/, reproduced through
// the field path: a World holding fields and a boundary, advanced by
// world.step() alone, with no per-body code. (examples/*.cpp reproduce the
// same references book-style with Mover; a separate ctest compares those.)
//
// Every value of every frame must match within 1e-9: absolute, or relative
// to the reference value where its magnitude is above 1 (tests/reference/
// README.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "calder/fields.hpp"
#include "calder/forces.hpp"
#include "calder/world.hpp"

#ifndef CALDER_REFERENCE_DIR
#error "CALDER_REFERENCE_DIR must name tests/reference (CMake defines it)"
#endif

namespace {

using calder::AttractionLaw;
using calder::Boundary;
using calder::BoundaryTiming;
using calder::World;

constexpr double kTolerance = 1e-9;

struct Row {
  long frame = 0;
  long body = 0;
  double value[4] = {};  // x, y, vx, vy
};

std::string reference_path(const std::string& name, const char* file) {
  return std::string(CALDER_REFERENCE_DIR) + "/" + name + "/" + file;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Parses `frame,body,x,y,vx,vy` with strtod (the numbers are in shortest
// round-trip form, so strtod gives back the exact doubles).
std::vector<Row> read_trajectory(const std::string& path) {
  std::ifstream in(path);
  std::vector<Row> rows;
  if (!in) {
    ADD_FAILURE() << "cannot open " << path;
    return rows;
  }
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "frame,body,x,y,vx,vy") << path;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    Row row;
    const char* p = line.c_str();
    char* end = nullptr;
    row.frame = std::strtol(p, &end, 10);
    EXPECT_EQ(*end, ',') << line;
    row.body = std::strtol(end + 1, &end, 10);
    for (double& v : row.value) {
      EXPECT_EQ(*end, ',') << line;
      v = std::strtod(end + 1, &end);
    }
    EXPECT_EQ(*end, '\0') << line;
    rows.push_back(row);
  }
  return rows;
}

// |a - b|, relative to |reference| where that is above 1.
double error_of(double value, double reference) {
  return std::abs(value - reference) / std::max(1.0, std::abs(reference));
}

struct Scene {
  std::string name;
  World world;
  // Called before step k (k = 1, 2, ...): the frame's input (the mouse).
  std::function<void(long frame)> before_frame = [](long) {};
};

// Steps the scene once per reference frame and compares every body's state
// after every step with the reference. Returns the largest error.
double run_and_compare(Scene& scene) {
  const std::vector<Row> rows = read_trajectory(reference_path(scene.name, "trajectory.csv"));
  World& world = scene.world;
  const long bodies = static_cast<long>(world.body_count());
  EXPECT_GT(bodies, 0);
  if (rows.empty() || bodies == 0) {
    ADD_FAILURE() << scene.name << ": no reference rows";
    return 0.0;
  }
  EXPECT_EQ(static_cast<long>(rows.size()) % bodies, 0) << scene.name;
  const long frames = rows.back().frame;
  EXPECT_EQ(static_cast<long>(rows.size()), (frames + 1) * bodies) << scene.name;
  EXPECT_GE(frames, 600) << scene.name;

  double max_error = 0.0;
  long worst_frame = 0;
  std::size_t next = 0;
  for (long frame = 0; frame <= frames; ++frame) {
    if (frame > 0) {
      scene.before_frame(frame);
      world.step();
    }
    const calder::BodyView b = world.bodies();
    for (long body = 0; body < bodies; ++body, ++next) {
      if (next >= rows.size()) {
        ADD_FAILURE() << scene.name << ": reference ends at frame " << frame;
        return max_error;
      }
      const Row& r = rows[next];
      if (r.frame != frame || r.body != body) {
        ADD_FAILURE() << scene.name << ": expected row " << frame << "," << body << ", got "
                      << r.frame << "," << r.body;
        return max_error;
      }
      const auto i = static_cast<std::size_t>(body);
      const double mine[4] = {b.x[i], b.y[i], b.vx[i], b.vy[i]};
      for (int k = 0; k < 4; ++k) {
        const double e = error_of(mine[k], r.value[k]);
        if (e > max_error) {
          max_error = e;
          worst_frame = frame;
        }
        if (!(e <= kTolerance)) {
          ADD_FAILURE() << scene.name << ": frame " << frame << ", body " << body << ", column "
                        << k << ": calder " << mine[k] << ", p5.js " << r.value[k] << " (error "
                        << e << ")";
          return max_error;  // the first divergence is the informative one
        }
      }
    }
  }
  std::printf("[ reference ] %s: %ld frames x %ld bodies, max error %.3g (frame %ld)\n",
              scene.name.c_str(), frames, bodies, max_error, worst_frame);
  ::testing::Test::RecordProperty("max_error", std::to_string(max_error));
  return max_error;
}

// The scenario's scripted mouse: the wind blows during draw() 100..160,
// inclusive. Checked against scenario.json so that a changed script is noticed.
bool mouse_is_pressed(long frame) { return frame >= 100 && frame <= 160; }

void expect_mouse_script(const std::string& name) {
  const std::string json = read_text(reference_path(name, "scenario.json"));
  EXPECT_NE(json.find("\"mouseIsPressed_frames\":[[100,160]]"), std::string::npos) << name;
}

// --------------------------------------------------------------- 2.1 ---

TEST(ReferenceFields, Example21Forces) {
  // Gravity (0, 0.1) and, while the mouse is pressed, wind (0.1, 0); update;
  // then edges on the centre: right/left and bottom, no top, vx *= -1.
  const std::string name = "example_2_1_forces";
  expect_mouse_script(name);
  Scene scene{name, World({.width = 640,
                           .height = 240,
                           .boundary = Boundary::bounce(1.0, false, {.top = false})})};
  scene.world.add_body({.position = {320, 30}, .mass = 1});
  scene.world.add(calder::Gravity{.g = {0, 0.1}});
  auto& wind = scene.world.add(calder::Wind{.force = {0.1, 0}, .enabled = false});
  scene.before_frame = [&wind](long frame) { wind.enabled = mouse_is_pressed(frame); };
  EXPECT_LE(run_and_compare(scene), kTolerance);
}

// --------------------------------------------------------------- 2.2 ---

TEST(ReferenceFields, Example22TwoObjects) {
  // As 2.1 with A (200, 30, mass 10) and B (440, 30, mass 2). The book does
  // A.update(); A.checkEdges(); B.update(); B.checkEdges() -- the world
  // updates and bounces body by body in the same order; without interaction
  // the forces do not depend on the other body's move, so the bits agree.
  const std::string name = "example_2_2_forces_acting_on_two_objects";
  expect_mouse_script(name);
  Scene scene{name, World({.width = 640,
                           .height = 240,
                           .boundary = Boundary::bounce(1.0, false, {.top = false})})};
  scene.world.add_body({.position = {200, 30}, .mass = 10});
  scene.world.add_body({.position = {440, 30}, .mass = 2});
  scene.world.add(calder::Gravity{.g = {0, 0.1}});  // NOT scaled: the heavy one falls slower
  auto& wind = scene.world.add(calder::Wind{.force = {0.1, 0}, .enabled = false});
  scene.before_frame = [&wind](long frame) { wind.enabled = mouse_is_pressed(frame); };
  EXPECT_LE(run_and_compare(scene), kTolerance);
}

// --------------------------------------------------------------- 2.3 ---

TEST(ReferenceFields, Example23GravityScaledByMass) {
  // Gravity (0, 0.1) * mass, radius = mass * 8, edges on the radius (no top).
  const std::string name = "example_2_3_gravity_scaled_by_mass";
  expect_mouse_script(name);
  Scene scene{name, World({.width = 640,
                           .height = 240,
                           .boundary = Boundary::bounce(1.0, true, {.top = false})})};
  scene.world.add_body({.position = {200, 30}, .mass = 10, .radius = 80});
  scene.world.add_body({.position = {440, 30}, .mass = 2, .radius = 16});
  scene.world.add(calder::Gravity{.g = {0, 0.1}, .scale_by_mass = true});
  auto& wind = scene.world.add(calder::Wind{.force = {0.1, 0}, .enabled = false});
  scene.before_frame = [&wind](long frame) { wind.enabled = mouse_is_pressed(frame); };
  EXPECT_LE(run_and_compare(scene), kTolerance);
}

// --------------------------------------------------------------- 2.4 ---

TEST(ReferenceFields, Example24IncludingFriction) {
  // Gravity (0, 1), wind (0.5, 0) while pressed, friction mu 0.1 on contact
  // (y > height - r - 1, on the position before this frame's move), then the
  // bounce (restitution 0.9, on the radius, no top) BEFORE the update.
  const std::string name = "example_2_4_including_friction";
  expect_mouse_script(name);
  Boundary bounce = Boundary::bounce(0.9, true, {.top = false});
  bounce.timing = BoundaryTiming::before_update;
  Scene scene{name, World({.width = 640, .height = 240, .boundary = bounce})};
  scene.world.add_body({.position = {320, 30}, .mass = 5, .radius = 40});
  scene.world.add(calder::Gravity{.g = {0, 1}});
  auto& wind = scene.world.add(calder::Wind{.force = {0.5, 0}, .enabled = false});
  scene.world.add(calder::Friction{.mu = 0.1});  // normal 1, bottom, tolerance 1
  scene.before_frame = [&wind](long frame) { wind.enabled = mouse_is_pressed(frame); };
  EXPECT_LE(run_and_compare(scene), kTolerance);
}

// --------------------------------------------------------------- 2.8 ---

TEST(ReferenceFields, Example28TwoBodyAttraction) {
  // A (320, 40), B (320, 200), mass 8, v = (1, 0) and (-1, 0); G (mA mB) / d^2
  // with d clamped to [5, 25], both forces from the start-of-frame positions,
  // then update A, update B. No edges.
  const std::string name = "example_2_8_two_body_attraction";
  Scene scene{name, World({.width = 640, .height = 240})};
  scene.world.add_body({.position = {320, 40}, .velocity = {1, 0}, .mass = 8});
  scene.world.add_body({.position = {320, 200}, .velocity = {-1, 0}, .mass = 8});
  scene.world.add(calder::MutualAttraction{
      .law = AttractionLaw::book(1, 5, 25, calder::MassProduct::masses_first)});
  EXPECT_LE(run_and_compare(scene), kTolerance);
}

// A check of the checker: a scene that differs from its reference (wind
// never blowing in 2.1) must be caught, so a passing comparison means something.
TEST(ReferenceFields, AWrongSceneIsCaught) {
  const std::vector<Row> rows =
      read_trajectory(reference_path("example_2_1_forces", "trajectory.csv"));
  ASSERT_GT(rows.size(), 200U);
  World world(
      {.width = 640, .height = 240, .boundary = Boundary::bounce(1.0, false, {.top = false})});
  world.add_body({.position = {320, 30}, .mass = 1});
  world.add(calder::Gravity{.g = {0, 0.1}});
  world.step(200);
  const calder::BodyView b = world.bodies();
  const Row& r = rows[200];
  ASSERT_EQ(r.frame, 200);
  EXPECT_GT(error_of(b.x[0], r.value[0]), 1e-3);  // the wind moved the reference by pixels
}

}  // namespace
