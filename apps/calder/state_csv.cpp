// SPDX-License-Identifier: MIT
#include "state_csv.hpp"

#include <array>
#include <cerrno>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string_view>
#include <system_error>

#include "calder/trajectory.hpp"
#include "errors.hpp"
#include "parse.hpp"

namespace calder::app {

namespace {

constexpr std::string_view kHeader = "x,y,vx,vy,mass";
constexpr std::string_view kHeaderWithRadius = "x,y,vx,vy,mass,radius";
constexpr std::array<const char*, 6> kColumns = {"x", "y", "vx", "vy", "mass", "radius"};

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

std::string_view strip_cr(std::string_view s) {
  if (!s.empty() && s.back() == '\r') s.remove_suffix(1);
  return s;
}

// Text of a field for a message: quoted, cut short if long.
std::string shown(std::string_view field) {
  constexpr std::size_t kMax = 40;
  if (field.size() > kMax) return "'" + std::string(field.substr(0, kMax)) + "...'";
  return "'" + std::string(field) + "'";
}

}  // namespace

std::vector<StateRow> parse_state_csv(std::istream& in, const std::string& source_name) {
  const auto fail = [&](std::size_t line, const std::string& what) -> InputError {
    return InputError(source_name + ":" + std::to_string(line) + ": " + what);
  };
  std::string text;
  std::size_t line = 0;
  if (!std::getline(in, text)) {
    throw fail(1, "empty file: expected the header '" + std::string(kHeader) + "' or '" +
                      std::string(kHeaderWithRadius) + "'");
  }
  ++line;
  std::string_view header = strip_cr(text);
  if (header.substr(0, 3) == "\xEF\xBB\xBF") header.remove_prefix(3);  // UTF-8 BOM
  std::size_t columns = 0;
  if (header == kHeader) {
    columns = 5;
  } else if (header == kHeaderWithRadius) {
    columns = 6;
  } else {
    throw fail(line, "expected the header '" + std::string(kHeader) + "' or '" +
                         std::string(kHeaderWithRadius) + "', got " + shown(header));
  }

  std::vector<StateRow> rows;
  while (std::getline(in, text)) {
    ++line;
    const std::string_view row = strip_cr(text);
    if (trim(row).empty()) continue;
    std::array<double, 6> values{};
    std::size_t count = 0;
    std::size_t start = 0;
    while (true) {
      const std::size_t comma = row.find(',', start);
      const std::string_view field =
          trim(row.substr(start, comma == std::string_view::npos ? row.npos : comma - start));
      if (count < columns) {
        const auto value = to_double(field);
        if (!value) {
          throw fail(line, std::string(kColumns[count]) + ": " + shown(field) + " is not a number");
        }
        if (!std::isfinite(*value)) {
          throw fail(line,
                     std::string(kColumns[count]) + " must be finite (got " + shown(field) + ")");
        }
        values[count] = *value;
      }
      ++count;
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    if (count != columns) {
      throw fail(line, "expected " + std::to_string(columns) + " fields (" +
                           std::string(columns == 5 ? kHeader : kHeaderWithRadius) + "), got " +
                           std::to_string(count));
    }
    StateRow r;
    r.x = values[0];
    r.y = values[1];
    r.vx = values[2];
    r.vy = values[3];
    r.mass = values[4];
    if (!(r.mass > 0.0)) {
      throw fail(line, "mass must be > 0 (got " + format_number(r.mass) + ")");
    }
    if (columns == 6) {
      if (values[5] < 0.0) {
        throw fail(line, "radius must be >= 0 (got " + format_number(values[5]) + ")");
      }
      r.radius = values[5];
    }
    rows.push_back(r);
  }
  if (in.bad()) throw fail(line + 1, "read error");
  return rows;
}

std::vector<StateRow> read_state_csv(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError(path + ": is a directory, not a CSV file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const int error = errno;
    throw InputError(path + ": cannot open: " + std::strerror(error));
  }
  return parse_state_csv(in, path);
}

}  // namespace calder::app
