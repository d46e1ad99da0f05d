// SPDX-License-Identifier: MIT
// calder-bench: the rain scene through calder::bulk against the floor and Box2D.
#include "bench_parts.hpp"
#include "peers/box2d_rain.hpp"
#include "peers/rain_world.hpp"
#include "peers/soa_rain.hpp"

namespace calder::app::bench {

// Steps the world body by body (no kernels) while alive.
class PlainLoops {
 public:
  PlainLoops() { set_step_batch_backend(nullptr); }
  ~PlainLoops() { set_step_batch_backend(bulk::step_batch); }
  PlainLoops(const PlainLoops&) = delete;
  PlainLoops& operator=(const PlainLoops&) = delete;
};

namespace {

// One size's rows: the floor (by precision and threads) and Box2D's rate
// that the others are compared with.
struct BulkRun {
  const Plan& plan;
  Runner& runner;
  Results& results;
  Table& table;
  bool avx2;
  std::string floor_flags;
  std::map<std::pair<bool, int>, double> floor;  // (float32, threads)
  double box2d_rate = 0.0;
  std::string vs_floor(double rate, bool float32, int threads) {
    return ratio_text(rate / floor[{float32, threads}]);
  }
};

std::vector<std::vector<std::string>> floor_rows(BulkRun& run, const World& proto, std::size_t n) {
  Runner& runner = run.runner;
  const double bodies = static_cast<double>(n);
  std::map<std::pair<bool, int>, double>& floor = run.floor;
  floor.clear();
  // The floor: the plain SoA loop of the same physics, in each precision.
  std::vector<std::vector<std::string>> rows;
  for (const bool float32 : {false, true}) {
    for (int threads : {1, 2}) {
      runner.status(std::string("SoA floor, N = ") + count_text(n) + ", " +
                    precision_name(float32) + ", " + std::to_string(threads) + " thread(s)");
      peers::SoaRain soa(proto, float32, run.avx2, threads);
      run.floor_flags = soa.flags();
      const Measured m = runner.measure([&] {
        soa.step(World::kBatchSteps);
        return bodies * World::kBatchSteps;
      });
      floor[{float32, threads}] = m.rate;
      run.results.bulk_floor[{n, float32, threads}] = m.rate;
      rows.push_back({"floor: plain SoA loop", count_text(n), precision_name(float32),
                      std::to_string(threads), rate_text(m.rate), "", "1x",
                      timing_note(m, "batch")});
    }
  }
  return rows;
}

void box2d_rows(BulkRun& run, const World& proto, std::size_t n) {
  Runner& runner = run.runner;
  Table& table = run.table;
  const double bodies = static_cast<double>(n);
  for (const peers::Box2dBodies kind : {peers::Box2dBodies::circles, peers::Box2dBodies::points}) {
    const bool circles = kind == peers::Box2dBodies::circles;
    runner.status("Box2D " + std::string(circles ? "circles" : "points") +
                  ", N = " + count_text(n));
    const Clock::time_point built = Clock::now();
    peers::Box2dRain box2d = peers::box2d_rain(proto, kind);
    const double build_seconds = seconds_since(built);
    const Measured m = runner.measure([&] {
      box2d.step();
      return bodies;
    });
    if (circles) run.box2d_rate = m.rate;
    std::string note = timing_note(m, "step");
    if (build_seconds >= 1.0) {
      note += (note.empty() ? "" : "; ") + std::string("building it took ") +
              seconds_text(build_seconds) + " (not counted)";
    }
    table.rows.push_back({circles ? "Box2D 2.4: circles, collisions filtered out"
                                  : "Box2D 2.4: bodies without shapes",
                          count_text(n), "float32", "1", rate_text(m.rate),
                          ratio_text(m.rate / run.box2d_rate), run.vs_floor(m.rate, true, 1),
                          note});
  }
}

void plain_row(BulkRun& run, const World& proto, std::size_t n) {
  Runner& runner = run.runner;
  const double bodies = static_cast<double>(n);
  {
    runner.status("plain loops, N = " + count_text(n));
    World world = proto;
    const PlainLoops plain;
    const Measured m = runner.measure([&] {
      world.step();
      return bodies;
    });
    run.table.rows.push_back({"calder, plain loops (no kernels)", count_text(n), "book", "1",
                              rate_text(m.rate), ratio_text(m.rate / run.box2d_rate),
                              run.vs_floor(m.rate, false, 1), timing_note(m, "step")});
  }
}

void calder_rows(BulkRun& run, const World& proto, std::size_t n) {
  Runner& runner = run.runner;
  const double bodies = static_cast<double>(n);
  for (int a = 0; a < 3; ++a) {
    for (int threads : {1, 2}) {
      runner.status(std::string("calder::bulk, N = ") + count_text(n) + ", " + arithmetic_text(a) +
                    ", " + std::to_string(threads) + " thread(s)");
      World world = proto;
      world.set_arithmetic(kArithmeticNames[static_cast<std::size_t>(a)].value);
      world.set_threads(threads);
      const Measured m = runner.measure([&] {
        world.step(World::kBatchSteps);
        return bodies * World::kBatchSteps;
      });
      run.results.bulk[{n, a, threads}] = m.rate;
      run.table.rows.push_back({"calder::bulk", count_text(n), arithmetic_text(a),
                                std::to_string(threads), rate_text(m.rate),
                                ratio_text(m.rate / run.box2d_rate),
                                run.vs_floor(m.rate, a == 2, threads), timing_note(m, "batch")});
    }
  }
}

std::vector<std::string> bulk_notes(const std::string& floor_flags) {
  return {
      "body-steps/s: bodies x steps per second. The rain scene (scenes/rain.toml): gravity scaled "
      "by mass, quadratic drag, a bounce on the radius off the walls and the floor, no body-body "
      "collisions; the canvas grows with N so that the density stays that of 1000 drops on "
      "640 x 240.",
      std::string("calder::bulk: World::step(") + std::to_string(World::kBatchSteps) +
          ") through calder::bulk's " + bulk::kernel_name() +
          " kernels; book is bit-identical to the plain loops, float64 and float32 trade the "
          "last bits for speed (calder/bulk.hpp). plain loops: the same world stepped body by "
          "body by calder's core.",
      "floor: the rain physics as the plain structure-of-arrays loop anyone would write "
      "(bench/peers/soa_rain_loop.cpp: one pass over the arrays per step, branch-free, "
      "gravity, drag, the bounce), compiled " +
          floor_flags +
          "; on 2 threads each runs every step on its own half of the arrays. vs floor: "
          "against the floor of the same precision (book: float64) and threads.",
      "Box2D 2.4 (single-threaded, float): forces applied per body (ApplyForceToCenter), "
      "b2World::Step, then the bounce per body. vs Box2D compares with its circles row: a circle "
      "fixture per body in the broad phase, body-body collisions filtered out, like for like. "
      "Bodies without shapes skip the broad phase: what Box2D costs at the least.",
  };
}

}  // namespace

Section bulk_section(const Plan& plan, Runner& runner, Results& results) {
  set_step_batch_backend(bulk::step_batch);  // the kernels, whatever ran before
  Section section;
  section.title = "calder::bulk, the rain scene: body-steps per second";
  Table table;
  table.columns = {"what",          ">N",        "arithmetic", ">threads",
                   ">body-steps/s", ">vs Box2D", ">vs floor",  "note"};
  // The floor's copy for calder::bulk's instruction set: AVX2 + FMA alone
  // when calder::bulk runs its AVX2 kernels, else -march=native.
  BulkRun run{plan, runner, results, table, std::string(bulk::kernel_name()) == "avx2+fma", {}, {}};
  for (const std::size_t n : plan.bulk_n) {
    const World proto = peers::rain_world(n, Arithmetic::book, 1);
    std::vector<std::vector<std::string>> floors = floor_rows(run, proto, n);
    box2d_rows(run, proto, n);
    for (std::vector<std::string>& row : floors) {
      row[5] = ratio_text(run.floor[{row[2] == "float32", std::stoi(row[3])}] / run.box2d_rate);
      table.rows.push_back(std::move(row));
    }
    plain_row(run, proto, n);
    calder_rows(run, proto, n);
  }
  section.tables.push_back(std::move(table));
  section.notes = bulk_notes(run.floor_flags);
  return section;
}

}  // namespace calder::app::bench
