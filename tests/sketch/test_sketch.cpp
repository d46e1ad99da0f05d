// SPDX-License-Identifier: MIT
// calder::sketch: each word of the vocabulary (docs/SKETCH.md's table), the
// runner's flags, scripted mouse and seeds, run headless.
#include <gtest/gtest.h>

#include <array>
#include <calder/calder.hpp>
#include <calder/render.hpp>
#include <calder/sketch.hpp>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

#include "runner.hpp"

namespace {

// Cairo's and fontconfig's caches (text()) freed at the end, for leak checkers.
class ReleaseRenderCaches : public ::testing::Environment {
 public:
  void TearDown() override { calder::release_render_caches(); }
};
[[maybe_unused]] ::testing::Environment* const release_caches =
    ::testing::AddGlobalTestEnvironment(new ReleaseRenderCaches);

using Pixel = std::array<int, 4>;

Pixel pixel(const calder::Canvas& canvas, int x, int y) {
  const std::vector<std::uint8_t> rgba = canvas.rgba();
  const std::size_t i =
      (static_cast<std::size_t>(y) * static_cast<std::size_t>(canvas.pixel_width()) +
       static_cast<std::size_t>(x)) *
      4u;
  return {rgba[i], rgba[i + 1], rgba[i + 2], rgba[i + 3]};
}

// A sketch whose setup() and draw() are the test's; the rest of Sketch's
// vocabulary is reachable through `self`.
class Probe : public calder::Sketch {
 public:
  std::function<void(Probe&)> on_setup;
  std::function<void(Probe&)> on_draw;
  std::function<void(Probe&)> on_press;
  std::function<void(Probe&)> on_release;
  std::function<void(Probe&)> on_key;
  void setup() override {
    if (on_setup) on_setup(*this);
  }
  void draw() override {
    if (on_draw) on_draw(*this);
  }
  void mouse_pressed() override {
    if (on_press) on_press(*this);
  }
  void mouse_released() override {
    if (on_release) on_release(*this);
  }
  void key_pressed() override {
    if (on_key) on_key(*this);
  }
  // The protected vocabulary, for the tests.
  using Sketch::background;
  using Sketch::canvas;
  using Sketch::circle;
  using Sketch::create_canvas;
  using Sketch::ellipse;
  using Sketch::exit_sketch;
  using Sketch::fill;
  using Sketch::frame_count;
  using Sketch::frame_rate;
  using Sketch::height;
  using Sketch::key;
  using Sketch::line;
  using Sketch::mouse_is_pressed;
  using Sketch::mouse_x;
  using Sketch::mouse_y;
  using Sketch::no_fill;
  using Sketch::no_loop;
  using Sketch::no_stroke;
  using Sketch::noise;
  using Sketch::pmouse_x;
  using Sketch::pmouse_y;
  using Sketch::point;
  using Sketch::pop;
  using Sketch::push;
  using Sketch::random;
  using Sketch::record;
  using Sketch::rect;
  using Sketch::rotate;
  using Sketch::save_frame;
  using Sketch::seed;
  using Sketch::stroke;
  using Sketch::stroke_weight;
  using Sketch::text;
  using Sketch::translate;
  using Sketch::triangle;
  using Sketch::width;
};

calder::SketchOptions headless(std::int64_t frames) {
  calder::SketchOptions options;
  options.mode = calder::SketchOptions::Mode::headless;
  options.frames = frames;
  options.quiet = true;
  return options;
}

// Runs one draw() of `paint` on a 40 x 30 white canvas and returns what `look` saw.
void draw_once(const std::function<void(Probe&)>& paint, const std::function<void(Probe&)>& look,
               double scale = 1.0) {
  Probe p;
  p.on_setup = [](Probe& s) { s.create_canvas(40, 30); };
  p.on_draw = [&](Probe& s) {
    s.background(255);
    paint(s);
    look(s);
  };
  calder::SketchOptions options = headless(1);
  options.scale = scale;
  calder::run_sketch(p, options);
}

TEST(Sketch, CreateCanvasWidthHeightAndScale) {
  draw_once([](Probe&) {},
            [](Probe& s) {
              EXPECT_EQ(s.width(), 40);
              EXPECT_EQ(s.height(), 30);
              EXPECT_EQ(s.canvas().pixel_width(), 80);
              EXPECT_EQ(s.canvas().pixel_height(), 60);
            },
            2.0);
}

TEST(Sketch, WithoutCreateCanvasTheCanvasIs100By100) {
  Probe p;
  int w = 0;
  p.on_draw = [&](Probe& s) { w = s.width() * 1000 + s.height(); };
  calder::run_sketch(p, headless(1));
  EXPECT_EQ(w, 100100);
}

TEST(Sketch, BackgroundPaintsEveryPixel) {
  draw_once([](Probe& s) { s.background(10, 20, 30); },
            [](Probe& s) {
              EXPECT_EQ(pixel(s.canvas(), 0, 0), (Pixel{10, 20, 30, 255}));
              EXPECT_EQ(pixel(s.canvas(), 39, 29), (Pixel{10, 20, 30, 255}));
            });
}

TEST(Sketch, FillAndStrokeAndStrokeWeightAndNoFillNoStroke) {
  draw_once(
      [](Probe& s) {
        s.fill(255, 0, 0);
        s.stroke(0, 0, 255);
        s.stroke_weight(4);
        s.rect(5, 5, 20, 20);  // stroke 3..7, fill inside
        s.no_fill();
        s.rect(30, 5, 8, 8);  // only the outline
        s.no_stroke();
        s.fill(0, 255, 0);
        s.rect(0, 26, 4, 4);  // no outline: the fill to its edge
      },
      [](Probe& s) {
        EXPECT_EQ(pixel(s.canvas(), 15, 15), (Pixel{255, 0, 0, 255}));     // fill
        EXPECT_EQ(pixel(s.canvas(), 5, 15), (Pixel{0, 0, 255, 255}));      // stroke
        EXPECT_EQ(pixel(s.canvas(), 34, 9), (Pixel{255, 255, 255, 255}));  // no fill
        EXPECT_EQ(pixel(s.canvas(), 30, 9), (Pixel{0, 0, 255, 255}));
        EXPECT_EQ(pixel(s.canvas(), 0, 29), (Pixel{0, 255, 0, 255}));
        EXPECT_EQ(pixel(s.canvas(), 3, 26), (Pixel{0, 255, 0, 255}));
      });
}

TEST(Sketch, CircleIsTheBodyCalderRenderDraws) {
  // One body of radius 8 at (20, 15), drawn by Canvas::draw in the book's look...
  calder::World world({.width = 40, .height = 30});
  world.add_body({.position = {20.25, 15.5}, .mass = 1, .radius = 8});
  calder::Canvas expected(40, 30, 2.0);
  expected.draw(world, calder::RenderStyle{}, 0);
  // ... and by a sketch: background(255); stroke(0); strokeWeight(2); fill(127, 127).
  draw_once(
      [](Probe& s) {
        s.stroke(0);
        s.stroke_weight(2);
        s.fill(127, 127);
        s.circle(20.25, 15.5, 16);
      },
      [&](Probe& s) { EXPECT_EQ(s.canvas().rgba(), expected.rgba()); }, 2.0);
}

TEST(Sketch, EllipseIsWiderThanHigh) {
  draw_once(
      [](Probe& s) {
        s.no_stroke();
        s.fill(0);
        s.ellipse(20, 15, 30, 10);
      },
      [](Probe& s) {
        EXPECT_EQ(pixel(s.canvas(), 7, 15)[0], 0);     // inside: 13 px from the centre in x
        EXPECT_EQ(pixel(s.canvas(), 20, 22)[0], 255);  // outside: 7 px in y
        EXPECT_EQ(pixel(s.canvas(), 20, 18)[0], 0);
      });
}

TEST(Sketch, LineAndPointUseTheStroke) {
  draw_once(
      [](Probe& s) {
        s.fill(255, 0, 0);  // not used by line or point
        s.stroke(0);
        s.stroke_weight(2);
        s.line(0, 10, 39, 10);
        s.stroke_weight(6);
        s.point(20, 22);
      },
      [](Probe& s) {
        EXPECT_EQ(pixel(s.canvas(), 20, 9), (Pixel{0, 0, 0, 255}));
        EXPECT_EQ(pixel(s.canvas(), 20, 13), (Pixel{255, 255, 255, 255}));
        EXPECT_EQ(pixel(s.canvas(), 20, 22), (Pixel{0, 0, 0, 255}));
        EXPECT_EQ(pixel(s.canvas(), 20, 26), (Pixel{255, 255, 255, 255}));  // 3 px radius
      });
}

TEST(Sketch, TriangleFillsItsInside) {
  draw_once(
      [](Probe& s) {
        s.no_stroke();
        s.fill(0);
        s.triangle(0, 0, 39, 0, 0, 29);
      },
      [](Probe& s) {
        EXPECT_EQ(pixel(s.canvas(), 5, 5)[0], 0);
        EXPECT_EQ(pixel(s.canvas(), 35, 25)[0], 255);
      });
}

TEST(Sketch, PushPopTranslateRotate) {
  draw_once(
      [](Probe& s) {
        s.no_stroke();
        s.fill(0);
        s.push();
        s.translate(20, 15);
        s.rotate(std::acos(-1.0) / 2);  // x now points down the screen
        s.rect(2, -1, 10, 2);           // a bar from (20, 17) down to (20, 27)
        s.pop();
        s.rect(0, 0, 2, 2);  // back at the origin: the transform was popped
      },
      [](Probe& s) {
        EXPECT_EQ(pixel(s.canvas(), 20, 24)[0], 0);
        EXPECT_EQ(pixel(s.canvas(), 26, 15)[0], 255);
        EXPECT_EQ(pixel(s.canvas(), 0, 0)[0], 0);
        EXPECT_THROW(s.pop(), calder::Error);
      });
}

TEST(Sketch, TheTransformStartsAfreshEachDraw) {
  Probe p;
  p.on_setup = [](Probe& s) { s.create_canvas(40, 30); };
  std::vector<int> corner;
  p.on_draw = [&](Probe& s) {
    s.background(255);
    s.no_stroke();
    s.fill(0);
    s.rect(0, 0, 2, 2);
    corner.push_back(pixel(s.canvas(), 0, 0)[0]);
    s.translate(10, 10);  // not carried into the next draw()
  };
  calder::run_sketch(p, headless(2));
  EXPECT_EQ(corner, (std::vector<int>{0, 0}));
}

TEST(Sketch, TextDrawsInTheFill) {
  draw_once(
      [](Probe& s) {
        s.fill(0);
        s.text("M", 5, 25);
      },
      [](Probe& s) {
        int dark = 0;
        for (int y = 10; y < 26; ++y) {
          for (int x = 4; x < 20; ++x) dark += pixel(s.canvas(), x, y)[0] < 128 ? 1 : 0;
        }
        EXPECT_GT(dark, 10);
      });
}

TEST(Sketch, BadColoursAndWeightsThrow) {
  draw_once([](Probe&) {},
            [](Probe& s) {
              EXPECT_THROW(s.fill(256), calder::Error);
              EXPECT_THROW(s.stroke(-1), calder::Error);
              EXPECT_THROW(s.stroke_weight(std::nan("")), calder::Error);
              EXPECT_THROW(s.circle(std::nan(""), 0, 1), calder::Error);
            });
}

TEST(Sketch, FrameCountFrameRateAndNoLoop) {
  Probe p;
  std::vector<std::int64_t> frames;
  p.on_setup = [](Probe& s) { s.frame_rate(30); };
  p.on_draw = [&](Probe& s) {
    frames.push_back(s.frame_count());
    EXPECT_EQ(s.frame_rate(), 30.0);
    if (s.frame_count() == 3) s.no_loop();
  };
  calder::run_sketch(p, headless(100));
  EXPECT_EQ(frames, (std::vector<std::int64_t>{1, 2, 3}));
}

TEST(Sketch, ExitSketchStopsAfterThisDraw) {
  Probe p;
  std::int64_t last = 0;
  p.on_draw = [&](Probe& s) {
    last = s.frame_count();
    if (last == 5) s.exit_sketch();
  };
  calder::run_sketch(p, headless(100));
  EXPECT_EQ(last, 5);
}

TEST(Sketch, ScriptedMouseIsPressedAndEvents) {
  Probe p;
  std::vector<std::int64_t> pressed;
  std::vector<std::int64_t> events;
  p.on_draw = [&](Probe& s) {
    if (s.mouse_is_pressed()) pressed.push_back(s.frame_count());
    EXPECT_EQ(s.mouse_x(), 12.5);
    EXPECT_EQ(s.mouse_y(), 7.0);
  };
  p.on_press = [&](Probe& s) { events.push_back(s.frame_count() + 1); };  // before draw()
  p.on_release = [&](Probe& s) { events.push_back(-(s.frame_count() + 1)); };
  calder::SketchOptions options = headless(10);
  options.mouse_pressed = {{3, 4}, {8, 8}};
  options.mouse = calder::Vec2{12.5, 7.0};
  calder::run_sketch(p, options);
  EXPECT_EQ(pressed, (std::vector<std::int64_t>{3, 4, 8}));
  EXPECT_EQ(events, (std::vector<std::int64_t>{3, -5, 8, -9}));
}

TEST(Sketch, LiveMouseAndPmouse) {
  // The window's events, as window.cpp hands them to the runner.
  Probe p;
  calder::SketchOptions options = headless(3);
  calder::SketchRunner runner(p, options);
  std::vector<std::array<double, 4>> seen;
  p.on_draw = [&](Probe& s) {
    seen.push_back({s.mouse_x(), s.mouse_y(), s.pmouse_x(), s.pmouse_y()});
  };
  runner.setup();
  runner.mouse_moved(5, 6);
  runner.draw_frame();
  runner.mouse_down(7, 8);
  EXPECT_TRUE(p.mouse_is_pressed());
  runner.draw_frame();
  runner.mouse_up(9, 10);
  EXPECT_FALSE(p.mouse_is_pressed());
  runner.draw_frame();
  ASSERT_EQ(seen.size(), 3u);
  EXPECT_EQ(seen[0], (std::array<double, 4>{5, 6, 0, 0}));
  EXPECT_EQ(seen[1], (std::array<double, 4>{7, 8, 5, 6}));
  EXPECT_EQ(seen[2], (std::array<double, 4>{9, 10, 7, 8}));
}

TEST(Sketch, KeyIsTheLastKeyPressed) {
  Probe p;
  calder::SketchOptions options = headless(1);
  calder::SketchRunner runner(p, options);
  std::vector<std::string> keys;
  p.on_key = [&](Probe& s) { keys.push_back(s.key()); };
  runner.setup();
  runner.key_down("a", false);
  runner.key_down("Enter", false);
  EXPECT_EQ(keys, (std::vector<std::string>{"a", "Enter"}));
  EXPECT_EQ(p.key(), "Enter");
}

TEST(Sketch, RandomAndNoiseAreP5sSeededWithSeed) {
  Probe p;
  std::vector<double> drawn;
  p.on_setup = [&](Probe& s) {
    drawn = {s.random(), s.random(10), s.random(-1, 1), s.noise(0.5, 1.5),
             static_cast<double>(s.seed())};
  };
  calder::SketchOptions options = headless(1);
  options.seed = 7;
  calder::run_sketch(p, options);
  calder::Random random(7);
  const calder::Noise noise(7);
  const std::vector<double> expected = {random.random(), random.random(10), random.random(-1, 1),
                                        noise.noise(0.5, 1.5), 7.0};
  EXPECT_EQ(drawn, expected);
}

TEST(Sketch, SaveFrameWritesThePng) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "calder-sketch-save-frame.png";
  std::filesystem::remove(path);
  draw_once([&](Probe& s) { s.save_frame(path.string()); }, [](Probe&) {});
  EXPECT_TRUE(std::filesystem::exists(path));
  EXPECT_GT(std::filesystem::file_size(path), 50u);
  std::filesystem::remove(path);
}

TEST(Sketch, TrajectoryOfTheRecordedWorld) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "calder-sketch-trajectory.csv";
  std::filesystem::remove(path);
  calder::World world({.width = 40, .height = 30});
  const calder::BodyId body = world.add_body({.position = {1, 2}, .mass = 1});
  Probe p;
  p.on_setup = [&](Probe& s) { s.record(world); };
  p.on_draw = [&](Probe&) {
    world.apply_force(body, {1, 0});
    world.update(body);
  };
  calder::SketchOptions options = headless(2);
  options.trajectory = path.string();
  calder::run_sketch(p, options);
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "frame,body,x,y,vx,vy\n0,0,1,2,0,0\n1,0,2,2,1,0\n2,0,4,2,2,0\n");
  std::filesystem::remove(path);
}

TEST(SketchOptions, TheFlagsOfCalderRender) {
  const char* argv[] = {"forces", "--frames", "12", "--gif",           "a.gif", "--png",
                        "dir",    "--scale",  "2",  "--mouse-pressed", "1-3",   "--mouse",
                        "4,5.5",  "--seed",   "9",  "--trajectory=-",  "--fps", "20"};
  const calder::SketchOptions o = calder::parse_sketch_options(18, argv);
  EXPECT_EQ(o.program, "forces");
  EXPECT_EQ(o.frames, 12);
  EXPECT_EQ(o.gif, "a.gif");
  EXPECT_EQ(o.png, "dir");
  EXPECT_EQ(o.scale, 2.0);
  ASSERT_EQ(o.mouse_pressed.size(), 1u);
  EXPECT_EQ(o.mouse_pressed[0], (std::pair<std::int64_t, std::int64_t>{1, 3}));
  EXPECT_EQ(o.mouse->x, 4.0);
  EXPECT_EQ(o.mouse->y, 5.5);
  EXPECT_EQ(o.seed, 9u);
  EXPECT_EQ(o.trajectory, "-");
  EXPECT_EQ(o.gif_fps, 20.0);
}

TEST(SketchOptions, BadFlagsSayWhichAndWhy) {
  const auto message = [](std::vector<const char*> argv) {
    argv.insert(argv.begin(), "s");
    try {
      (void)calder::parse_sketch_options(static_cast<int>(argv.size()), argv.data());
    } catch (const calder::Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message({"--frames", "-1"}),
            "--frames: expected an integer from 0 to 10000000, got '-1'");
  EXPECT_EQ(message({"--scale", "9"}), "--scale: expected a number in (0, 8], got '9'");
  EXPECT_EQ(message({"--mouse-pressed", "5-2"}),
            "--mouse-pressed: expected A-B, frames with 1 <= A <= B <= 10000000, got '5-2'");
  EXPECT_EQ(message({"--mouse", "1"}), "--mouse: expected X,Y (two finite numbers), got '1'");
  EXPECT_EQ(message({"--seed", "4294967296"}),
            "--seed: expected an integer from 0 to 4294967295, got '4294967296'");
  EXPECT_EQ(message({"--gif", "/no/such/folder/a.gif"}),
            "--gif: no folder '/no/such/folder' for '/no/such/folder/a.gif'");
  EXPECT_EQ(message({"--frames"}), "--frames: expects a value");
  EXPECT_EQ(message({"--bogus"}), "unknown flag '--bogus' (--help lists them)");
}

TEST(SketchOptions, AGifOfNoFrameIsAnErrorAndLeavesNoFile) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "calder-sketch-no-frame.gif";
  std::filesystem::remove(path);
  Probe p;
  calder::SketchOptions options = headless(0);
  options.gif = path.string();
  EXPECT_THROW(calder::run_sketch(p, options), calder::InputError);
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(SketchOptions, TrajectoryWithoutARecordedWorldIsAnError) {
  Probe p;
  calder::SketchOptions options = headless(1);
  options.trajectory = "-";
  EXPECT_THROW(calder::run_sketch(p, options), calder::Error);
}

}  // namespace
