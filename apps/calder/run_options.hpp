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
#include <span>
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
  std::optional<std::string> integrator;
  std::optional<std::string> tolerance;
  bool no_work_limit = false;  // --no-work-limit
};

// The work budget of one run, every cost that grows with the input, counted
// before the work: frames x (bodies x fields + the scripted mouse's press
// ranges and moves + bodies^2 for each exact or direct mutual attraction,
// barnes_hut_work for Barnes-Hut, plus, once the bodies are placed, m^2 for
// each point that m > 32 bodies share under Barnes-Hut), plus what the
// diagnostics and drawings cost (WorkExtras). Over it the run is refused
// (exit 2) unless --no-work-limit is given: 10^12 pair evaluations take tens
// of minutes to hours on one machine.
constexpr double max_run_work = 1e12;
// The bodies a run may step: `bodies`, or the scene's body groups when a press
// resets them (on_press = reset) and they are more.
std::size_t budget_bodies(const Scene& scene, std::size_t bodies);
// The work of a scene with this many bodies, per the scene alone (see max_run_work).
double run_work(const Scene& scene, std::size_t bodies);
// Barnes-Hut's pairs a frame for n bodies at opening angle theta:
// n x min(n, log2(n) x max(1, (0.7 / theta)^2)); all n^2 pairs at theta = 0.
double barnes_hut_work(double n, double theta);
// Barnes-Hut's pairs a frame among bodies that share a point: the tree can't
// split a cell of its finest grid (2^24 per side of the bounding square), so
// m > 32 bodies there are m^2 pairs; the sum over such cells.
double coincident_work(std::span<const double> x, std::span<const double> y);
// Throws InputError naming `source` when run_work is over max_run_work.
void check_work_budget(const Scene& scene, std::size_t bodies, const std::string& source);

// The processors this process may use (std::thread::hardware_concurrency).
int usable_threads();
// Caps the scene's thread counts ([world] threads, each mutual attraction's)
// to usable_threads(): more add nothing, results do not depend on them, and
// OpenMP aborts the process when it can't start one. Throws InputError naming
// `source` when even that many threads can't be started (a memory limit).
void limit_threads(Scene& scene, const std::string& source);

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
  bool no_work_limit = false;

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

// What a verb adds to the work of the frames: `per_image` for each of
// `images` drawings (the HUD's energy, the force overlay), `once` (the
// summary's potential energy).
struct WorkExtras {
  double per_image = 0.0;
  double images = 0.0;
  double once = 0.0;
};
// The budget again with the bodies placed (before the first step): the scene's
// work, the bodies that share a point under Barnes-Hut, and `extras`. Throws
// InputError naming the source when over max_run_work (unless --no-work-limit).
void check_world_work(const PreparedInput& input, const Simulation& simulation,
                      const WorkExtras& extras);

}  // namespace calder::app
