// SPDX-License-Identifier: MIT
// calder: trajectories as CSV, `frame,body,x,y,vx,vy`.
//
// Numbers are written in the shortest form that reads back to the same
// double with strtod, so a trajectory file is an exact record of the run.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>

namespace calder {

class World;

// The shortest decimal form of value that strtod turns back into value
// ("0.1", "30.599999999999998", "1e-300"); "nan", "inf", "-inf" otherwise.
std::string format_number(double value);

class TrajectoryWriter {
 public:
  // Writes the header line at once.
  explicit TrajectoryWriter(std::ostream& out);
  // One row per body of the world: `frame,index,x,y,vx,vy`.
  void write(std::int64_t frame, const World& world);

 private:
  std::ostream* out_;
};

}  // namespace calder
