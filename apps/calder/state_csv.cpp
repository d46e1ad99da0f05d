// SPDX-License-Identifier: MIT
#include "state_csv.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string_view>
#include <system_error>

#include "calder/error.hpp"
#include "calder/scene.hpp"
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

// Text of a field for a message: quoted, control characters escaped, cut short if long.
std::string shown(std::string_view field) { return "'" + detail::printable(field, 40) + "'"; }

// One line of at most max_state_line_bytes bytes into `line` (without its
// '\n'); false at the end of the input. Throws on a longer line, before
// storing it.
bool read_line(std::istream& in, std::string& line,
               const std::function<InputError(std::string)>& fail) {
  line.clear();
  std::streambuf* buffer = in.rdbuf();
  while (true) {
    const std::streambuf::int_type c = buffer->sbumpc();
    if (std::streambuf::traits_type::eq_int_type(c, std::streambuf::traits_type::eof())) {
      if (line.empty()) {
        in.setstate(std::ios::eofbit);
        return false;
      }
      return true;
    }
    if (c == '\n') return true;
    if (line.size() >= max_state_line_bytes) {
      throw fail("a line longer than " + std::to_string(max_state_line_bytes) +
                 " bytes (the limit of --state files)");
    }
    line += std::streambuf::traits_type::to_char_type(c);
  }
}

}  // namespace

std::vector<StateRow> parse_state_csv(std::istream& in, const std::string& source_name) {
  const auto fail = [&](std::size_t line, const std::string& what) -> InputError {
    return InputError(source_name + ":" + std::to_string(line) + ": " + what);
  };
  std::string text;
  std::size_t line = 0;
  const auto fail_here = [&](const std::string& what) { return fail(line + 1, what); };
  if (!read_line(in, text, fail_here)) {
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
  while (read_line(in, text, fail_here)) {
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
    if (rows.size() == max_bodies) {
      throw fail(line, "more than " + std::to_string(max_bodies) +
                           " rows (the limit of bodies in a scene)");
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
  const std::string name = detail::printable(path, 240);
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError(name + ": is a directory, not a CSV file");
  }
  // O_NONBLOCK: opening a FIFO must not wait for a writer (it is refused below).
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    const int error = errno;
    throw InputError(name + ": cannot open: " + std::strerror(error));
  }
  struct stat info {};
  const bool regular = ::fstat(fd, &info) == 0 && S_ISREG(info.st_mode);
  ::close(fd);
  if (!regular) {
    throw InputError(name +
                     ": not a regular file (--state files are read whole; a device, "
                     "FIFO or socket is refused)");
  }
  if (static_cast<std::uint64_t>(info.st_size) > max_state_file_bytes) {
    throw InputError(name + ": larger than " + std::to_string(max_state_file_bytes >> 20) +
                     " MiB, the limit of --state files");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const int error = errno;
    throw InputError(name + ": cannot open: " + std::strerror(error));
  }
  // Count the rows before storing any: too many are refused at once.
  std::size_t rows = 0;
  bool blank = true;
  std::array<char, 65536> chunk{};
  while (in) {
    in.read(chunk.data(), chunk.size());
    for (std::streamsize i = 0; i < in.gcount(); ++i) {
      const char c = chunk[static_cast<std::size_t>(i)];
      if (c == '\n') {
        rows += blank ? 0 : 1;
        blank = true;
      } else if (c != ' ' && c != '\t' && c != '\r') {
        blank = false;
      }
    }
  }
  rows += blank ? 0 : 1;
  if (rows > max_bodies + 1) {  // + 1: the header
    throw InputError(name + ": " + std::to_string(rows - 1) + " rows, more than " +
                     std::to_string(max_bodies) + " (the limit of bodies in a scene)");
  }
  in.clear();
  in.seekg(0);
  return parse_state_csv(in, name);
}

}  // namespace calder::app
