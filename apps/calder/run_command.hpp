// SPDX-License-Identifier: MIT
// calder command: `calder run` and `calder list`.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <ostream>
#include <string>

#include "calder/diagnostics.hpp"
#include "calder/scene.hpp"
#include "run_options.hpp"
#include "snapshot_io.hpp"

namespace CLI {
class App;
}

namespace calder::app {

// --trajectory writes at most this many rows, (frames + 1) * bodies.
constexpr std::int64_t max_trajectory_rows = 50'000'000;

enum class TrajectoryFormat { csv, json };

struct RunOptions {
  InputOptions input;
  std::optional<std::string> trajectory;   // a path, or "-" for stdout
  std::optional<std::string> format;       // "csv" or "json"
  SnapshotOptions snapshot;                // --save, --archive, --every
  std::optional<std::string> device;       // --device (devices_command.hpp)
  std::int64_t energy_every = 0;           // --energy-every: a line every K frames
  std::optional<double> energy_threshold;  // --energy-threshold
  bool fail_on_energy = false;             // --fail-on-energy
};

// Adds the `run` verb with its flags to the application.
CLI::App* add_run_command(CLI::App& app, RunOptions& options);

// Runs it: the summary goes to `out` (or the trajectory, for "-").
// Throws InputError or calder::SceneFileError for bad input (exit 2),
// RunError when a step or a write fails (exit 1).
void run_command(const RunOptions& options, std::ostream& out, std::ostream& err);

// --format, or else json for a path ending in ".json", csv otherwise.
TrajectoryFormat trajectory_format(const std::optional<std::string>& format,
                                   const std::string& path);

// Throws InputError when (frames + 1) * bodies is over max_trajectory_rows.
void check_trajectory_rows(std::int64_t frames, std::size_t bodies);

// Steps the simulation to `frames` frames, calling after_step(frame) after
// each. A calder::Error thrown by a step becomes a RunError naming `source`
// and the frame.
void run_frames(Simulation& simulation, std::int64_t frames, const std::string& source,
                const std::function<void(std::int64_t)>& after_step);

// `calder list`: the built-in scenes and their descriptions, aligned.
void print_scene_list(std::ostream& out);

}  // namespace calder::app
