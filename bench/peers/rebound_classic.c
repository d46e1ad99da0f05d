// SPDX-License-Identifier: MIT
// rebound_classic: REBOUND's IAS15 on the three classic problems of
// bench_classic (calder's side), through REBOUND's public C API. Built and
// run only by bench/rebound_compare.sh, against a REBOUND it fetches: this
// file is calder's (MIT), REBOUND (GPL-3) is never part of a calder build.
//
//   rebound_classic [REPETITIONS]
//
// prints, per problem and mode, one tab-separated line
//   rebound  PROBLEM  MODE  STEPS  FORCE_EVALUATIONS  BEST_WALL_S  ENERGY_ERROR
// MODE "frames" integrates to each of calder's frame ends in turn (REBOUND's
// exact_finish_time, its default), as calder's World::step does; "whole"
// integrates to the end in one call. IAS15 with epsilon 1e-9 and REBOUND 5's
// default step criterion (Pham, Rein & Spiegel 2024, adaptive_mode PRS23);
// the first step is REBOUND's default dt, 0.001.
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "rebound.h"

struct body {
  double m, x, y, vx, vy;
};

// G = 1 and the literature's units (calder's built-in scenes are these in
// pixels: the same problem, the same times).
struct problem {
  const char* name;
  int n;
  struct body bodies[3];
  double frame;  // calder's frame dt
  int frames;
  int kepler;  // a test particle around a fixed unit mass: its energy per mass
};

static uint64_t evaluations = 0;

static void count_evaluation(struct reb_simulation* const r) {
  (void)r;
  ++evaluations;
}

static struct reb_simulation* make(const struct problem* p, int counting) {
  struct reb_simulation* r = reb_simulation_create();
  r->G = 1.0;
  struct reb_integrator_ias15_state* ias15 = reb_simulation_set_integrator(r, "ias15");
  ias15->epsilon = 1e-9;
  ias15->adaptive_mode = REB_IAS15_ADAPTIVEMODE_PRS23;
  for (int i = 0; i < p->n; ++i) {
    struct reb_particle particle = {0};
    particle.m = p->bodies[i].m;
    particle.x = p->bodies[i].x;
    particle.y = p->bodies[i].y;
    particle.vx = p->bodies[i].vx;
    particle.vy = p->bodies[i].vy;
    reb_simulation_add(r, particle);
  }
  // A no-op force counts the evaluations (one call per evaluation; the
  // forces are not velocity dependent, so IAS15 takes the same path).
  if (counting) r->additional_forces = count_evaluation;
  return r;
}

// Kinetic plus pair potential energy; for the Kepler problem the test
// particle's energy per unit mass around particle 0, calder's energy of a
// unit mass around its fixed attractor.
static double energy(const struct reb_simulation* r, const struct problem* p) {
  const struct reb_particle* b = r->particles;
  if (p->kepler) {
    const double dx = b[1].x - b[0].x, dy = b[1].y - b[0].y, dz = b[1].z - b[0].z;
    const double v2 = b[1].vx * b[1].vx + b[1].vy * b[1].vy + b[1].vz * b[1].vz;
    return 0.5 * v2 - r->G * b[0].m / sqrt(dx * dx + dy * dy + dz * dz);
  }
  double e = 0.0;
  for (size_t i = 0; i < r->N; ++i) {
    e += 0.5 * b[i].m * (b[i].vx * b[i].vx + b[i].vy * b[i].vy + b[i].vz * b[i].vz);
    for (size_t j = i + 1; j < r->N; ++j) {
      const double dx = b[j].x - b[i].x, dy = b[j].y - b[i].y, dz = b[j].z - b[i].z;
      e -= r->G * b[i].m * b[j].m / sqrt(dx * dx + dy * dy + dz * dz);
    }
  }
  return e;
}

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

struct outcome {
  uint64_t steps;
  double energy_error;
  double wall;
};

static struct outcome run(const struct problem* p, int by_frames, int counting) {
  const double start = now();
  struct reb_simulation* r = make(p, counting);
  const double e0 = energy(r, p);
  if (by_frames) {
    for (int k = 1; k <= p->frames; ++k) reb_simulation_integrate(r, k * p->frame);
  } else {
    reb_simulation_integrate(r, p->frames * p->frame);
  }
  struct outcome o;
  o.wall = now() - start;
  o.steps = r->steps_done;
  o.energy_error = fabs((energy(r, p) - e0) / e0);
  if (r->status != REB_STATUS_SUCCESS) {
    fprintf(stderr, "rebound_classic: %s ended with REBOUND status %d\n", p->name, (int)r->status);
    exit(1);
  }
  reb_simulation_free(r);
  return o;
}

int main(int argc, char** argv) {
  const int repetitions = argc > 1 ? atoi(argv[1]) : 5;
  if (repetitions < 1) {
    fprintf(stderr, "rebound_classic: REPETITIONS must be a positive integer\n");
    return 2;
  }
  const double pi = 3.141592653589793;
  const double e = 0.9;
  // Burrau (1913); Szebehely & Peters (1967): t = 70 in 700 frames of 0.1.
  // Chenciner & Montgomery (2000), after Simo: ten periods, 120 frames each.
  // Kepler, e = 0.9, a = 1: 1,000 orbits, one frame per orbit.
  const struct problem problems[] = {
      {"pythagorean", 3, {{3, 1, 3, 0, 0}, {4, -2, -1, 0, 0}, {5, 1, -1, 0, 0}}, 0.1, 700, 0},
      {"figure-eight",
       3,
       {{1, 0.97000436, -0.24308753, 0.466203685, 0.43236573},
        {1, -0.97000436, 0.24308753, 0.466203685, 0.43236573},
        {1, 0, 0, -0.93240737, -0.86473146}},
       6.32591398 / 120.0,
       1200,
       0},
      {"kepler", 2, {{1, 0, 0, 0, 0}, {0, 1 - e, 0, 0, sqrt((1 + e) / (1 - e))}}, 2 * pi, 1000, 1},
  };
  printf("# REBOUND IAS15, epsilon 1e-9, adaptive_mode PRS23; best of %d\n", repetitions);
  for (size_t k = 0; k < sizeof problems / sizeof problems[0]; ++k) {
    const struct problem* p = &problems[k];
    for (int by_frames = 1; by_frames >= 0; --by_frames) {
      evaluations = 0;
      const struct outcome counted = run(p, by_frames, 1);
      double best = INFINITY;
      for (int rep = 0; rep < repetitions; ++rep) {
        const struct outcome o = run(p, by_frames, 0);
        if (o.steps != counted.steps) {
          fprintf(stderr, "rebound_classic: %s took %llu steps counting, %llu timed\n", p->name,
                  (unsigned long long)counted.steps, (unsigned long long)o.steps);
          return 1;
        }
        if (o.wall < best) best = o.wall;
      }
      printf("rebound\t%s\t%s\t%llu\t%llu\t%.6g\t%.3g\n", p->name, by_frames ? "frames" : "whole",
             (unsigned long long)counted.steps, (unsigned long long)evaluations, best,
             counted.energy_error);
    }
  }
  return 0;
}
