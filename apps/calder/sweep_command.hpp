// SPDX-License-Identifier: MIT
// calder command: `calder sweep`, many members of one scene on the local
// cores, one CSV row per member and recorded frame.
//
//   calder sweep exercise-2.16 --seeds 0-99 --set fields[0].law.G=0.5,1,2
//       --frames 300 --output results.csv   (one line)
//
// Members: every combination of the --set values (in the order given, the
// last changing fastest), each with every seed, member i being the
// (i / seeds)-th combination with the (i % seeds)-th seed: the members of
// calder.Ensemble(scene, seeds=[...], vary={KEY: [...], ...}) in Python,
// with the same numbers. A parameter path names a value of the scene file
// (world.dt, bodies[0].count, fields[2].law.G); each member's scene is read
// by calder's scene reader, so an unknown key or a value out of range is
// refused (exit 2) before any member runs.
#pragma once

#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace calder::app {

struct SweepOptions {
  std::string scene;
  std::optional<std::string> seeds;  // "0-99", "1,5,9", "0-9,20"
  std::vector<std::string> set;      // "KEY=V1,V2,..."
  std::optional<std::string> frames;
  std::optional<std::string> every;
  std::string record = "state_hash,diagnostics";
  std::optional<std::string> jobs;
  std::string output;
};

// At most this many members in one sweep.
constexpr std::int64_t max_sweep_members = 1'000'000;

CLI::App* add_sweep_command(CLI::App& app, SweepOptions& options);

// Runs the sweep and writes the table to options.output. Throws InputError
// or SceneFileError for bad input (exit 2) before any member runs; members
// that fail are reported on `err` one line each and the others go on, then
// RunError (exit 1) says how many failed, after the table of the others is
// written.
void sweep_command(const SweepOptions& options, std::ostream& out, std::ostream& err);

}  // namespace calder::app
