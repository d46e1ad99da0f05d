// SPDX-License-Identifier: MIT
#include "trajectory_json.hpp"

#include <nlohmann/json.hpp>

#include "calder/trajectory.hpp"
#include "calder/world.hpp"

namespace calder::app {

std::string json_string(const std::string& text) {
  return nlohmann::json(text).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

TrajectoryJsonWriter::TrajectoryJsonWriter(std::ostream& out, const TrajectoryInfo& info)
    : out_(&out) {
  *out_ << "{\"scene\": " << json_string(info.scene) << ", \"frames\": " << info.frames
        << ", \"bodies\": " << info.bodies << ", \"dt\": " << format_number(info.dt)
        << ", \"seed\": " << info.seed
        << ",\n \"columns\": [\"frame\", \"body\", \"x\", \"y\", \"vx\", \"vy\"],\n \"rows\": [";
}

void TrajectoryJsonWriter::write(std::int64_t frame, const World& world) {
  const BodyView b = world.bodies();
  std::string line;
  for (std::size_t i = 0; i < b.size(); ++i) {
    line.clear();
    line += first_row_ ? "\n[" : ",\n[";
    first_row_ = false;
    line += std::to_string(frame);
    line += ", ";
    line += std::to_string(i);
    for (const double v : {b.x[i], b.y[i], b.vx[i], b.vy[i]}) {
      line += ", ";
      line += format_number(v);
    }
    line += ']';
    *out_ << line;
  }
}

void TrajectoryJsonWriter::finish() { *out_ << "\n]}\n"; }

}  // namespace calder::app
