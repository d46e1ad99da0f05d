// SPDX-License-Identifier: MIT
#include "calder/trajectory.hpp"

#include "calder/error.hpp"
#include "calder/world.hpp"

namespace calder {

std::string format_number(double value) { return detail::format_number(value); }

TrajectoryWriter::TrajectoryWriter(std::ostream& out) : out_(&out) {
  *out_ << "frame,body,x,y,vx,vy\n";
}

void TrajectoryWriter::write(std::int64_t frame, const World& world) {
  const BodyView b = world.bodies();
  std::string line;
  for (std::size_t i = 0; i < b.size(); ++i) {
    line.clear();
    line += std::to_string(frame);
    line += ',';
    line += std::to_string(i);
    for (const double v : {b.x[i], b.y[i], b.vx[i], b.vy[i]}) {
      line += ',';
      line += detail::format_number(v);
    }
    line += '\n';
    *out_ << line;
  }
}

}  // namespace calder
