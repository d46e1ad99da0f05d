// SPDX-License-Identifier: MIT
// calder command: the input flags shared by the verbs that run a scene
// (`calder run`, `calder render`, `calder window`), and how they change a
// Scene. Their names and help are written once, in run_options.cpp (the flags
// that change the scene are rows of one table there): `calder run --help`
// shows them, apps/README.md documents them.
//
// A verb adds them with add_input_options(), and after parsing turns them into
// a ready Simulation with prepare_input() and start_simulation().
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "calder/scene.hpp"
#include "calder/vec2.hpp"
#include "calder/world.hpp"

namespace CLI {
class App;
}

namespace calder::app {

struct StateRow;

// The input flags as typed (unset when not given).
struct InputOptions {
  std::string scene;
  std::optional<std::string> frames;
  std::optional<std::string> dt;
  std::optional<std::string> seed;
  std::optional<std::string> state;
  std::vector<std::string> mouse_pressed;
  std::optional<std::string> mouse;
  bool no_work_limit = false;  // --no-work-limit
};

// The work budget of one run: frames x (bodies + bodies^2 for each exact or
// direct mutual attraction, bodies x log2(bodies) for Barnes-Hut). Over it,
// prepare_input refuses the run (exit 2) unless --no-work-limit is given:
// 10^12 pair evaluations take tens of minutes to hours on one machine.
constexpr double max_run_work = 1e12;
// The work of a scene with this many bodies (see max_run_work).
double run_work(const Scene& scene, std::size_t bodies);
// Throws InputError naming `source` when run_work is over max_run_work.
void check_work_budget(const Scene& scene, std::size_t bodies, const std::string& source);

// Adds the SCENE|FILE argument and the input flags to a verb.
void add_input_options(CLI::App& command, InputOptions& options);

// The input flags, checked and converted.
struct InputFlags {
  const InputOptions* options = nullptr;  // the texts of the flags that change the scene
  std::optional<std::uint32_t> seed;
  std::optional<std::vector<FrameRange>> mouse_pressed;  // set: replaces the scene's
  std::optional<std::string> state_path;
};

// Checks and converts the flags (not the scene, not the state file).
// Throws InputError naming the flag.
InputFlags parse_input_flags(const InputOptions& options);

// Applies the flags that change the scene (--frames, --dt, --mouse, ...: the
// table in run_options.cpp) and --mouse-pressed to it (--seed goes to the
// Simulation, --state replaces the bodies after setup).
void apply_input_flags(const InputFlags& flags, Scene& scene);

// A scene with the flags applied, and what replaces its seed and bodies.
struct PreparedInput {
  std::string source;  // the SCENE|FILE argument
  Scene scene;
  std::optional<std::uint32_t> seed;
  std::optional<std::vector<BodyDef>> bodies;  // from --state
  std::optional<std::string> state_path;
  // A run resumed from a snapshot (snapshot_io.hpp): start_simulation returns it.
  std::optional<Simulation> resumed;

  // The seed the run uses: --seed, or the scene's.
  [[nodiscard]] std::uint32_t effective_seed() const { return seed ? *seed : scene.world.seed; }
};

// Loads the scene, applies the flags, reads the --state file (or, for a
// snapshot, prepare_resume of snapshot_io.hpp). Throws
// InputError or calder::SceneFileError (bad input: exit 2).
PreparedInput prepare_input(const InputOptions& options);

// The bodies for --state rows: position, velocity, mass, the radius of the row
// or else the radius the scene's first body group gives that mass (0 if the
// scene has no body groups); friction and drag area as that group's.
std::vector<BodyDef> bodies_from_state(const std::vector<StateRow>& rows, const Scene& scene);

// Builds the world (setup) and, with --state, replaces its bodies. Throws
// InputError when the scene or the bodies are invalid.
Simulation start_simulation(const PreparedInput& input);

}  // namespace calder::app
