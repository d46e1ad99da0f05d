// SPDX-License-Identifier: MIT
// The C++ side of python/bench/bench_python.py: the same three workloads,
// written as a C++ program would, timed the same way (best of --repeat).
// Prints one JSON object; the state hashes let the script check that both
// sides did the same work.
#include <calder/bulk.hpp>
#include <calder/diagnostics.hpp>
#include <calder/fields.hpp>
#include <calder/random.hpp>
#include <calder/world.hpp>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

struct Drops {
  std::vector<double> x, y, vx, vy, mass, radius;
};

// The rain scene's drops, drawn as bench_python.py draws them.
Drops drops(std::size_t n, double width, double height) {
  calder::Random rng(1);
  Drops d;
  for (std::size_t i = 0; i < n; ++i) {
    d.x.push_back(rng.random(width));
    d.y.push_back(rng.random(height));
    d.mass.push_back(rng.random(0.5, 3.0));
    d.radius.push_back(d.mass.back() * 2.0);
    d.vx.push_back(0.0);
    d.vy.push_back(0.0);
  }
  return d;
}

calder::World rain(const Drops& d, double width, double height, bool add_fields) {
  calder::World world({.width = width,
                       .height = height,
                       .boundary = calder::Boundary::bounce(0.9, true, {.top = false}),
                       .threads = 1});
  world.add_bodies(
      {.x = d.x, .y = d.y, .vx = d.vx, .vy = d.vy, .mass = d.mass, .radius = d.radius});
  if (add_fields) {
    world.add(calder::Gravity{.g = {0.0, 0.1}, .scale_by_mass = true});
    world.add(calder::Drag{.c = 0.01});
  }
  return world;
}

}  // namespace

int main(int argc, char** argv) {
  const int repeat = argc > 1 ? std::atoi(argv[1]) : 5;
  const int small_calls = 200'000;
  const int rain_steps = 1000;
  const std::size_t rain_bodies = 100'000;
  const int add_tries = 10;                      // as bench_python.py's ADD_TRIES
  const double width = 6400.0, height = 2400.0;  // the rain scene's density at 10^5 drops

  double small_best = 1e300, rain_best = 1e300, add_best = 1e300;
  std::uint64_t small_hash = 0, rain_hash = 0;
  const Drops ten = drops(10, 640.0, 240.0);
  const Drops many = drops(rain_bodies, width, height);
  for (int r = 0; r < repeat; ++r) {
    calder::World small = rain(ten, 640.0, 240.0, true);
    auto start = Clock::now();
    for (int k = 0; k < small_calls; ++k) small.step();
    small_best = std::min(small_best, seconds_since(start));
    small_hash = calder::state_hash(small);

    // Added again into the emptied world: its memory is mapped already, so
    // this times the adding, not the system's page faults.
    calder::World added = rain(many, width, height, false);
    for (int k = 0; k < add_tries; ++k) {
      added.clear_bodies();
      start = Clock::now();
      added.add_bodies({.x = many.x,
                        .y = many.y,
                        .vx = many.vx,
                        .vy = many.vy,
                        .mass = many.mass,
                        .radius = many.radius});
      add_best = std::min(add_best, seconds_since(start));
    }

    added.add(calder::Gravity{.g = {0.0, 0.1}, .scale_by_mass = true});
    added.add(calder::Drag{.c = 0.01});
    start = Clock::now();
    added.step(rain_steps);
    rain_best = std::min(rain_best, seconds_since(start));
    rain_hash = calder::state_hash(added);
  }
  std::printf(
      "{\"step_calls_per_s\": %.6g, \"rain_body_steps_per_s\": %.6g, \"add_bodies_per_s\": %.6g, "
      "\"small_hash\": %llu, \"rain_hash\": %llu}\n",
      small_calls / small_best, static_cast<double>(rain_bodies) * rain_steps / rain_best,
      static_cast<double>(rain_bodies) / add_best, static_cast<unsigned long long>(small_hash),
      static_cast<unsigned long long>(rain_hash));
  return 0;
}
