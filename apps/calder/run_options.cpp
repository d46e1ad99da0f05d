// SPDX-License-Identifier: MIT
#include "run_options.hpp"

#include <pthread.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <span>
#include <thread>
#include <utility>
#include <variant>

#include "calder/error.hpp"
#include "calder/fields.hpp"
#include "errors.hpp"
#include "parse.hpp"
#include "scene_source.hpp"
#include "snapshot_io.hpp"
#include "state_csv.hpp"

namespace calder::app {

namespace {

// The input flags whose value changes the scene, each written once: its name,
// the placeholder of its value, its help, where CLI11 puts its text, and how
// that text is checked and applied (throwing InputError that names the flag).
// A new flag of this kind is a row here and its text in InputOptions.
struct SceneFlag {
  const char* name;
  const char* type_name;
  const char* help;
  std::optional<std::string> InputOptions::*text;
  void (*apply)(const std::string& flag, const std::string& text, Scene& scene);
};

const SceneFlag kSceneFlags[] = {
    {"--frames", "N", "Frames to run, 0 to 10000000 (default: the scene's)", &InputOptions::frames,
     [](const std::string& flag, const std::string& text, Scene& scene) {
       scene.frames = parse_frames(flag, text);
     }},
    {"--dt", "X", "Time step, a number > 0 (default: the scene's)", &InputOptions::dt,
     [](const std::string& flag, const std::string& text, Scene& scene) {
       scene.world.dt = parse_dt(flag, text);
     }},
    {"--mouse", "X,Y",
     "The mouse stays at X,Y for the whole run (replaces the scene's scripted mouse position and "
     "moves)",
     &InputOptions::mouse,
     [](const std::string& flag, const std::string& text, Scene& scene) {
       scene.input.mouse = parse_point(flag, text);
       scene.input.moves.clear();
     }},
    {"--integrator", "NAME",
     "semi_implicit_euler, velocity_verlet, rk4, ias15, yoshida4 or yoshida6, replacing the "
     "scene's (see "
     "docs/SCENES.md)",
     &InputOptions::integrator,
     [](const std::string& flag, const std::string& text, Scene& scene) {
       scene.world.integrator = parse_integrator(flag, text);
     }},
    {"--tolerance", "X", "ias15's tolerance, a number > 0 (default: the scene's, else 1e-9)",
     &InputOptions::tolerance,
     [](const std::string& flag, const std::string& text, Scene& scene) {
       scene.world.tolerance = parse_dt(flag, text);
     }},
};

}  // namespace

void add_input_options(CLI::App& command, InputOptions& options) {
  command
      .add_option("scene", options.scene,
                  "A built-in scene (see `calder list`) or a scene file: an argument that "
                  "names an existing file, ends in .toml or contains a '/' is read as a file")
      ->required()
      ->type_name("SCENE|FILE");
  for (const SceneFlag& flag : kSceneFlags) {
    command.add_option(flag.name, options.*flag.text, flag.help)->type_name(flag.type_name);
  }
  command
      .add_option("--seed", options.seed,
                  "Random seed, 0 to 4294967295, replacing the scene's (default: the scene's)")
      ->type_name("S");
  command
      .add_option("--state", options.state,
                  "CSV with the header x,y,vx,vy,mass or x,y,vx,vy,mass,radius and one row per "
                  "body: replaces the bodies after setup (without radius, each body gets the "
                  "radius the scene's first body group gives its mass)")
      ->type_name("FILE");
  command
      .add_option("--mouse-pressed", options.mouse_pressed,
                  "Frames A to B (1-based draw numbers, inclusive) with the mouse held; "
                  "repeat for more ranges. Given, these REPLACE the scene's scripted presses; "
                  "'none' clears them")
      ->type_name("A-B")
      ->allow_extra_args(false)  // one range per flag: `--mouse-pressed 1-2 SCENE` stays clear
      ->take_all();
  command.add_flag("--no-work-limit", options.no_work_limit,
                   "Run even when the work (bodies^2 x frames with mutual attraction, bodies x "
                   "frames otherwise) is over the budget of 10^12");
}

std::size_t budget_bodies(const Scene& scene, std::size_t bodies) {
  // A press that resets rebuilds the scene's body groups (whatever --state
  // or a snapshot started with): the run may step that many bodies.
  if (scene.on_press != PressAction::reset) return bodies;
  std::size_t rebuilt = 0;
  for (const BodyGroup& group : scene.bodies) rebuilt += group.count;
  return std::max(bodies, rebuilt);
}

double run_work(const Scene& scene, std::size_t bodies) {
  const auto n = static_cast<double>(budget_bodies(scene, bodies));
  // Every field visits every body each frame; the scripted mouse is looked up
  // in its press ranges and moves each frame.
  double per_frame = n * static_cast<double>(std::max<std::size_t>(scene.fields.size(), 1)) +
                     static_cast<double>(scene.input.mouse_pressed.size()) +
                     static_cast<double>(scene.input.moves.size());
  for (const SceneField& f : scene.fields) {
    if (const auto* mutual = std::get_if<MutualAttraction>(&f.field)) {
      if (!mutual->enabled) continue;
      per_frame +=
          mutual->method == NBodyMethod::barnes_hut ? barnes_hut_work(n, mutual->theta) : n * n;
    }
  }
  return per_frame * static_cast<double>(std::max<std::int64_t>(scene.frames, 1));
}

double barnes_hut_work(double n, double theta) {
  // n log2 n at the default opening angle; below it the pairs a tree walk
  // opens grow as 1 / theta^2, up to all n^2 pairs at theta = 0 (the direct
  // sum); above it the leaves' direct sums keep the cost from falling much.
  const double per_body = std::max(1.0, std::log2(std::max(n, 1.0))) *
                          std::max(1.0, std::pow(kDefaultTheta / theta, 2.0));
  return n * std::min(n, std::isfinite(per_body) ? per_body : n);
}

double coincident_work(std::span<const double> x, std::span<const double> y) {
  constexpr std::size_t kLeaf = 32;
  const std::size_t n = std::min(x.size(), y.size());
  if (n <= kLeaf) return 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(x[i]) || !std::isfinite(y[i])) return 0.0;  // the first step fails anyway
  }
  double x0 = x[0], x1 = x[0], y0 = y[0], y1 = y[0];
  for (std::size_t i = 1; i < n; ++i) {
    x0 = std::min(x0, x[i]);
    x1 = std::max(x1, x[i]);
    y0 = std::min(y0, y[i]);
    y1 = std::max(y1, y[i]);
  }
  const double side = std::max(x1 - x0, y1 - y0);
  if (!std::isfinite(side)) return 0.0;  // a spread of 1e308: no shared cell to speak of
  constexpr double kCells = 16777216.0;  // 2^24
  const double scale = side > 0.0 ? (kCells - 1.0) / side : 0.0;
  std::vector<std::uint64_t> cells(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto cx = static_cast<std::uint64_t>((x[i] - x0) * scale);
    const auto cy = static_cast<std::uint64_t>((y[i] - y0) * scale);
    cells[i] = (cx << 24U) | cy;
  }
  std::sort(cells.begin(), cells.end());
  double work = 0.0;
  for (std::size_t i = 0; i < cells.size();) {
    std::size_t j = i;
    while (j < cells.size() && cells[j] == cells[i]) ++j;
    const auto m = static_cast<double>(j - i);
    if (j - i > kLeaf) work += m * m;
    i = j;
  }
  return work;
}

namespace {

void refuse_work(const std::string& source, std::size_t bodies, std::int64_t frames, double work,
                 const std::string& why) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", work);
  throw InputError(detail::printable(source, 240) + ": " + std::to_string(bodies) + " bodies for " +
                   std::to_string(frames) + " frames is about " + text +
                   " units of work (pair evaluations" + why +
                   "), over the budget of 1e12; use fewer bodies or --frames, or "
                   "--no-work-limit to run it anyway");
}

}  // namespace

namespace {

// Whether `count` threads (besides this one) can be started at once with the
// default stack, as OpenMP would start them: each is started and waits until
// all are, so that they hold their stacks together.
bool can_start_threads(int count) {
  std::mutex mutex;
  std::condition_variable all_started;
  bool release = false;
  std::vector<pthread_t> threads;
  threads.reserve(static_cast<std::size_t>(count));
  struct Shared {
    std::mutex* mutex;
    std::condition_variable* cv;
    bool* release;
  } shared{&mutex, &all_started, &release};
  const auto body = [](void* arg) -> void* {
    auto* s = static_cast<Shared*>(arg);
    std::unique_lock<std::mutex> lock(*s->mutex);
    s->cv->wait(lock, [s] { return *s->release; });
    return nullptr;
  };
  bool ok = true;
  for (int i = 0; i < count; ++i) {
    pthread_t thread{};
    if (::pthread_create(&thread, nullptr, body, &shared) != 0) {
      ok = false;
      break;
    }
    threads.push_back(thread);
  }
  {
    const std::lock_guard<std::mutex> lock(mutex);
    release = true;
  }
  all_started.notify_all();
  for (const pthread_t thread : threads) ::pthread_join(thread, nullptr);
  return ok;
}

}  // namespace

int usable_threads() {
  const unsigned cpus = std::thread::hardware_concurrency();
  return cpus == 0 ? 1 : static_cast<int>(cpus);
}

void limit_threads(Scene& scene, const std::string& source) {
  const int cpus = usable_threads();
  int most = scene.world.threads > 0 ? scene.world.threads : cpus;
  // More threads than processors add nothing (results do not depend on the
  // thread count): capped to the processors.
  scene.world.threads = std::min(scene.world.threads, cpus);
  for (SceneField& f : scene.fields) {
    if (auto* mutual = std::get_if<MutualAttraction>(&f.field)) {
      most = std::max(most, mutual->threads > 0 ? mutual->threads : cpus);
      mutual->threads = std::min(mutual->threads, cpus);
    }
  }
  most = std::min(most, cpus);
  // OpenMP ends the process when it can't start a thread (a memory limit,
  // ulimit -v): refused here, with one line, before anything is written.
  if (most > 1 && !can_start_threads(most - 1)) {
    throw InputError(detail::printable(source, 240) + ": cannot start " + std::to_string(most) +
                     " threads (a limit on memory or processes?); set threads to fewer in the "
                     "scene's [world] or mutual attraction");
  }
}

void check_work_budget(const Scene& scene, std::size_t bodies, const std::string& source) {
  const double work = run_work(scene, bodies);
  if (work > max_run_work)
    refuse_work(source, budget_bodies(scene, bodies), scene.frames, work, "");
}

void check_world_work(const PreparedInput& input, const Simulation& simulation,
                      const WorkExtras& extras) {
  if (input.no_work_limit) return;
  const World& world = simulation.world();
  const std::size_t n = world.body_count();
  const auto frames = static_cast<double>(std::max<std::int64_t>(input.scene.frames, 1));
  double clustered = 0.0;
  for (const SceneField& f : input.scene.fields) {
    const auto* mutual = std::get_if<MutualAttraction>(&f.field);
    if (mutual != nullptr && mutual->enabled && mutual->method == NBodyMethod::barnes_hut) {
      if (clustered == 0.0) clustered = coincident_work(world.bodies().x, world.bodies().y);
    }
  }
  const double work = run_work(input.scene, n) + clustered * frames +
                      extras.per_image * extras.images + extras.once;
  if (work > max_run_work) {
    refuse_work(input.source, budget_bodies(input.scene, n), input.scene.frames, work,
                clustered > 0.0 ? ", with bodies that share a point" : ", with diagnostics");
  }
}

InputFlags parse_input_flags(const InputOptions& options) {
  InputFlags flags;
  Scene checked;  // the scene flags are checked before the scene is read
  for (const SceneFlag& flag : kSceneFlags) {
    if (options.*flag.text) flag.apply(flag.name, *(options.*flag.text), checked);
  }
  flags.options = &options;
  if (options.seed) flags.seed = parse_seed("--seed", *options.seed);
  if (!options.mouse_pressed.empty()) {
    std::vector<FrameRange> ranges;
    for (const std::string& text : options.mouse_pressed) {
      for (const FrameRange& r : parse_frame_range("--mouse-pressed", text)) ranges.push_back(r);
    }
    flags.mouse_pressed = std::move(ranges);
  }
  if (options.state) {
    if (options.state->empty()) throw InputError("--state: the file name is empty");
    flags.state_path = *options.state;
  }
  return flags;
}

void apply_input_flags(const InputFlags& flags, Scene& scene) {
  if (flags.options != nullptr) {
    for (const SceneFlag& flag : kSceneFlags) {
      if (flags.options->*flag.text) flag.apply(flag.name, *(flags.options->*flag.text), scene);
    }
  }
  if (flags.mouse_pressed) scene.input.mouse_pressed = *flags.mouse_pressed;
}

std::vector<BodyDef> bodies_from_state(const std::vector<StateRow>& rows, const Scene& scene) {
  const BodyGroup* group = scene.bodies.empty() ? nullptr : &scene.bodies.front();
  std::vector<BodyDef> bodies;
  bodies.reserve(rows.size());
  for (const StateRow& row : rows) {
    BodyDef def;
    def.position = {row.x, row.y};
    def.velocity = {row.vx, row.vy};
    def.mass = row.mass;
    if (row.radius) {
      def.radius = *row.radius;
    } else if (group != nullptr) {
      def.radius = group->radius.radius_for(row.mass);
    }
    if (group != nullptr) {
      def.friction = group->friction;
      def.drag_area = group->drag_area;
    }
    bodies.push_back(def);
  }
  return bodies;
}

PreparedInput prepare_input(const InputOptions& options) {
  if (names_snapshot(options.scene)) return prepare_resume(options);
  const InputFlags flags = parse_input_flags(options);
  PreparedInput input;
  input.source = options.scene;
  input.scene = load_scene_argument(options.scene);
  apply_input_flags(flags, input.scene);
  limit_threads(input.scene, input.source);
  input.seed = flags.seed;
  if (flags.state_path) {
    const std::vector<StateRow> rows = read_state_csv(*flags.state_path);
    if (rows.size() > max_bodies) {
      throw InputError(*flags.state_path + ": more than " + std::to_string(max_bodies) + " bodies");
    }
    input.bodies = bodies_from_state(rows, input.scene);
    input.state_path = flags.state_path;
  }
  input.no_work_limit = options.no_work_limit;
  if (!options.no_work_limit) {
    std::size_t bodies = 0;
    if (input.bodies) {
      bodies = input.bodies->size();
    } else {
      for (const BodyGroup& group : input.scene.bodies) bodies += group.count;
    }
    check_work_budget(input.scene, bodies, input.source);
  }
  return input;
}

Simulation start_simulation(const PreparedInput& input) {
  if (input.resumed) return *input.resumed;
  std::optional<Simulation> simulation;
  try {
    simulation.emplace(input.scene, input.seed);
  } catch (const Error& e) {
    rethrow_with_context(e, input.source + ": ");
  }
  if (input.bodies) {
    try {
      simulation->set_bodies(*input.bodies);
    } catch (const Error& e) {
      rethrow_with_context(e, *input.state_path + ": ");
    }
  }
  return std::move(*simulation);
}

}  // namespace calder::app
