// SPDX-License-Identifier: MIT
// calder command: trajectories as JSON (calder run --trajectory FILE.json).
//
// The same rows as the CSV of calder::TrajectoryWriter, with the run's
// parameters, one row per line:
//
//   {"scene": "example-2.1", "frames": 600, "bodies": 1, "dt": 1, "seed": 1,
//    "columns": ["frame", "body", "x", "y", "vx", "vy"],
//    "rows": [
//   [0, 0, 320, 30, 0, 0],
//   [1, 0, 320, 30.1, 0, 0.1],
//   ...
//   ]}
//
// "frames" is the number of steps (rows hold frames 0..frames, frame 0 being
// the state after setup); numbers are in the shortest form that reads back to
// the same double (calder::format_number), so the JSON is as exact as the CSV.
// The file is written as the run goes (no document is built in memory).
#pragma once

#include <cstddef>
#include <cstdint>
#include <ostream>
#include <string>

namespace calder {
class World;
}

namespace calder::app {

struct TrajectoryInfo {
  std::string scene;
  std::int64_t frames = 0;
  std::size_t bodies = 0;
  double dt = 1.0;
  std::uint32_t seed = 0;
};

class TrajectoryJsonWriter {
 public:
  // Writes everything up to the opening bracket of "rows".
  TrajectoryJsonWriter(std::ostream& out, const TrajectoryInfo& info);
  // One row per body of the world, as TrajectoryWriter::write.
  void write(std::int64_t frame, const World& world);
  // Closes "rows" and the object.
  void finish();

 private:
  std::ostream* out_;
  bool first_row_ = true;
};

// A JSON string literal (quoted, escaped) for text; invalid UTF-8 is replaced.
std::string json_string(const std::string& text);

}  // namespace calder::app
