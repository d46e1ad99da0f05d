// SPDX-License-Identifier: MIT
#include "run_options.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
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

double run_work(const Scene& scene, std::size_t bodies) {
  const auto n = static_cast<double>(bodies);
  double per_frame = n;
  for (const SceneField& f : scene.fields) {
    if (const auto* mutual = std::get_if<MutualAttraction>(&f.field)) {
      if (!mutual->enabled) continue;
      per_frame +=
          mutual->method == NBodyMethod::barnes_hut ? n * std::max(1.0, std::log2(n)) : n * n;
    }
  }
  return per_frame * static_cast<double>(std::max<std::int64_t>(scene.frames, 1));
}

void check_work_budget(const Scene& scene, std::size_t bodies, const std::string& source) {
  const double work = run_work(scene, bodies);
  if (work <= max_run_work) return;
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", work);
  throw InputError(detail::printable(source, 240) + ": " + std::to_string(bodies) + " bodies for " +
                   std::to_string(scene.frames) + " frames is about " + text +
                   " units of work (pair evaluations), over the budget of 1e12; use fewer "
                   "bodies or --frames, or --no-work-limit to run it anyway");
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
  input.seed = flags.seed;
  if (flags.state_path) {
    const std::vector<StateRow> rows = read_state_csv(*flags.state_path);
    if (rows.size() > max_bodies) {
      throw InputError(*flags.state_path + ": more than " + std::to_string(max_bodies) + " bodies");
    }
    input.bodies = bodies_from_state(rows, input.scene);
    input.state_path = flags.state_path;
  }
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
