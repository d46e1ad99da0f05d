// SPDX-License-Identifier: MIT
// calder command: initial states from CSV (calder run --state FILE).
//
// The file has the header `x,y,vx,vy,mass` or `x,y,vx,vy,mass,radius`
// (exactly, in that order) and one row of numbers per body. Numbers are read
// exactly (shortest round-trip text gives back the same double); spaces
// around a field and a final '\r' are ignored, and so are empty lines.
// Every number must be finite, mass > 0 and radius >= 0. Errors are one line
// naming the file and line: "state.csv:3: mass must be > 0 (got -1)".
#pragma once

#include <cstddef>
#include <istream>
#include <optional>
#include <string>
#include <vector>

namespace calder::app {

// Limits of --state files, checked before the data is stored: the file's
// size (and that it is a regular file), each line's length, and the rows
// (at most calder::max_bodies).
constexpr std::size_t max_state_file_bytes = std::size_t{1} << 30;  // 1 GiB
constexpr std::size_t max_state_line_bytes = 4096;

struct StateRow {
  double x = 0.0;
  double y = 0.0;
  double vx = 0.0;
  double vy = 0.0;
  double mass = 1.0;
  std::optional<double> radius;  // absent without a radius column
};

// Reads rows from `in`; `source_name` stands for the file in messages.
// Throws InputError.
std::vector<StateRow> parse_state_csv(std::istream& in, const std::string& source_name);
// Opens and reads the file. Throws InputError (naming the file) if it can't.
std::vector<StateRow> read_state_csv(const std::string& path);

}  // namespace calder::app
