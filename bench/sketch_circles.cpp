// SPDX-License-Identifier: MIT
// A sketch that draws 10,000 circles a frame (the book's bodies' look: stroke
// 2, fill(127, 127)), moving a little each frame, and says how fast it drew:
// bench/sketch_fps.sh runs it headless and in a window beside `calder render`
// of a 10,000-body scene.
//
//   sketch_circles [sketch flags]   e.g. --headless --frames 120, --window --frames 120
#include <calder/calder.hpp>
#include <calder/sketch.hpp>
#include <chrono>
#include <cstdio>
#include <vector>

class Circles : public calder::Sketch {
 public:
  static constexpr int kCircles = 10'000;

  void report() const {
    if (draws_ < 2) return;
    const double seconds = std::chrono::duration<double>(last_ - first_).count();
    std::printf("sketch_circles: %d circles, %lld frames in %.3f s: %.1f frames/s\n", kCircles,
                static_cast<long long>(draws_ - 1), seconds,
                static_cast<double>(draws_ - 1) / seconds);
  }

 private:
  void setup() override {
    create_canvas(640, 240);
    for (int i = 0; i < kCircles; ++i) {
      points_.push_back({random(width()), random(height())});
      speeds_.push_back({random(-1, 1), random(-1, 1)});
    }
  }

  void draw() override {
    const auto now = std::chrono::steady_clock::now();
    if (draws_ == 0) first_ = now;
    background(255);
    stroke(0);
    stroke_weight(2);
    fill(127, 127);
    for (std::size_t i = 0; i < points_.size(); ++i) {
      calder::Vec2& p = points_[i];
      p += speeds_[i];
      if (p.x < 0 || p.x > width()) speeds_[i].x = -speeds_[i].x;
      if (p.y < 0 || p.y > height()) speeds_[i].y = -speeds_[i].y;
      circle(p.x, p.y, 8);
    }
    ++draws_;
    last_ = std::chrono::steady_clock::now();
  }

  std::vector<calder::Vec2> points_;
  std::vector<calder::Vec2> speeds_;
  std::int64_t draws_ = 0;
  std::chrono::steady_clock::time_point first_;
  std::chrono::steady_clock::time_point last_;
};

int main(int argc, char** argv) {
  int status = 0;
  {
    Circles sketch;
    status = calder::run_sketch(sketch, argc, argv);
    if (status == 0) sketch.report();
  }
  calder::release_render_caches();
  return status;
}
