// SPDX-License-Identifier: MIT
#include "progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

namespace calder::app {

namespace {

// Shown only for jobs that take longer than this, redrawn at most this often.
constexpr double kShowAfterSeconds = 0.3;
constexpr double kRedrawSeconds = 0.1;
constexpr int kBarWidth = 24;

std::string duration_text(double seconds) {
  const auto s = static_cast<long long>(std::lround(seconds));
  char text[32];
  if (s >= 3600) {
    std::snprintf(text, sizeof text, "%lldh%02lldm", s / 3600, (s / 60) % 60);
  } else if (s >= 60) {
    std::snprintf(text, sizeof text, "%lldm%02llds", s / 60, s % 60);
  } else {
    std::snprintf(text, sizeof text, "%llds", s);
  }
  return text;
}

}  // namespace

bool stderr_is_terminal() { return ::isatty(STDERR_FILENO) == 1; }

Progress::Progress(std::ostream& err, std::string label, std::int64_t total, bool enabled)
    : err_(err),
      label_(std::move(label)),
      total_(std::max<std::int64_t>(total, 1)),
      enabled_(enabled),
      start_(Clock::now()),
      last_draw_(start_) {}

Progress::~Progress() { finish(); }

std::string Progress::line(const std::string& label, std::int64_t done, std::int64_t total,
                           double elapsed_seconds) {
  total = std::max<std::int64_t>(total, 1);
  done = std::clamp<std::int64_t>(done, 0, total);
  const double fraction = static_cast<double>(done) / static_cast<double>(total);
  const auto filled = static_cast<int>(fraction * kBarWidth);
  std::string text = label;
  text += " [";
  text.append(static_cast<std::size_t>(filled), '#');
  text.append(static_cast<std::size_t>(kBarWidth - filled), '.');
  char numbers[96];
  std::snprintf(numbers, sizeof numbers, "] %3d%% %lld/%lld", static_cast<int>(fraction * 100.0),
                static_cast<long long>(done), static_cast<long long>(total));
  text += numbers;
  if (done > 0 && done < total) {
    const double left = elapsed_seconds / fraction - elapsed_seconds;
    text += ", ";
    text += duration_text(left);
    text += " left";
  }
  return text;
}

void Progress::update(std::int64_t done) {
  if (!enabled_) return;
  const Clock::time_point now = Clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  if (elapsed < kShowAfterSeconds) return;
  if (shown_ && std::chrono::duration<double>(now - last_draw_).count() < kRedrawSeconds &&
      done < total_) {
    return;
  }
  std::string text = line(label_, done, total_, elapsed);
  const std::size_t length = text.size();
  if (length < width_) text.append(width_ - length, ' ');  // covers a longer last line
  err_ << '\r' << text;
  err_.flush();
  width_ = length;
  shown_ = true;
  last_draw_ = now;
}

void Progress::finish() {
  if (!shown_) return;
  err_ << '\r' << std::string(width_, ' ') << '\r';
  err_.flush();
  shown_ = false;
}

}  // namespace calder::app
