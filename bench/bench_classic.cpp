// SPDX-License-Identifier: MIT
// bench_classic: calder's side of bench/rebound_compare.sh. The classic
// problems under ias15 (tolerance 1e-9) as `calder run` runs them (a
// Simulation of the built-in scene, frame by frame), each timed whole, best
// of REPETITIONS:
//
//   pythagorean    Burrau's three bodies to t = 70 (700 frames of 0.1)
//   figure-eight   the figure-eight choreography, ten periods (1200 frames)
//   kepler         the built-in Kepler orbit (e = 0.9) for 1,000 orbits,
//                  one frame of 2 pi per orbit
//
//   bench_classic [REPETITIONS]
//
// prints one tab-separated line per problem, as bench/peers/rebound_classic.c
// does for REBOUND:
//   calder  PROBLEM  frames  STEPS  FORCE_EVALUATIONS  BEST_WALL_S  ENERGY_ERROR  ITERATIONS
//   REJECTED
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>

#include "calder/calder.hpp"

namespace {

calder::Scene problem(const std::string& name) {
  calder::Scene scene = calder::builtin_scene(name);
  if (name == "kepler") {
    scene.world.dt = 2.0 * 3.141592653589793;
    scene.frames = 1000;
  }
  return scene;
}

struct Outcome {
  calder::AdaptiveStats stats;
  double energy_error = 0.0;
  double wall = 0.0;
};

Outcome run(const std::string& name) {
  const auto start = std::chrono::steady_clock::now();
  calder::Simulation sim(problem(name));
  const double e0 = calder::total_energy(sim.world());
  while (sim.frame() < sim.scene().frames) sim.step();
  Outcome o;
  o.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  o.stats = sim.world().adaptive_stats();
  o.energy_error = std::fabs((calder::total_energy(sim.world()) - e0) / e0);
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const int repetitions = argc > 1 ? std::atoi(argv[1]) : 5;
  if (repetitions < 1) {
    std::fprintf(stderr, "bench_classic: REPETITIONS must be a positive integer\n");
    return 2;
  }
  const std::string version(calder::version());
  std::printf("# calder %s, ias15 tolerance 1e-9; best of %d\n", version.c_str(), repetitions);
  for (const char* name : {"pythagorean", "figure-eight", "kepler"}) {
    Outcome best = run(name);
    for (int k = 1; k < repetitions; ++k) {
      const Outcome o = run(name);
      if (o.wall < best.wall) best.wall = o.wall;
    }
    std::printf("calder\t%s\tframes\t%lld\t%lld\t%.6g\t%.3g\t%lld\t%lld\n", name,
                static_cast<long long>(best.stats.steps),
                static_cast<long long>(best.stats.force_evaluations), best.wall, best.energy_error,
                static_cast<long long>(best.stats.iterations),
                static_cast<long long>(best.stats.rejected));
  }
  return 0;
}
