// SPDX-License-Identifier: MIT
// trajectory_diff: compares a candidate trajectory CSV with a reference one.
//
//   trajectory_diff REFERENCE.csv CANDIDATE.csv [--tolerance 1e-9]
//
// Both files have the header `frame,body,x,y,vx,vy` and one row of numbers per
// body and frame (shortest round-trip form, read back exactly with strtod).
// The files match when they have the same header, the same number of rows, the
// same (frame, body) key in every row, and for x, y, vx and vy
//
//   |reference - candidate| <= tolerance * max(1, |reference|)
//
// (absolute below magnitude 1, relative above). The error reported is
// |reference - candidate| / max(1, |reference|), the quantity held against the
// tolerance. NaN or infinite values only match the identical value.
//
// Output, one line on stdout:
//   OK: N rows, max error E at frame F body B                       exit 0
//   FAIL: first frame F body B column C: reference R candidate C (error E)
//   FAIL: ... (header, row count or key mismatch)                   exit 1
// Unreadable files, malformed rows and bad arguments: one line on stderr naming
// the file and line, exit 2.
#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace {

constexpr std::string_view kExpectedHeader = "frame,body,x,y,vx,vy";
constexpr std::array<std::string_view, 6> kColumns = {"frame", "body", "x", "y", "vx", "vy"};
constexpr std::size_t kFirstValueColumn = 2;
constexpr double kDefaultTolerance = 1e-9;

constexpr int kExitOk = 0;
constexpr int kExitFail = 1;
constexpr int kExitError = 2;

struct Row {
  std::size_t line = 0;  // 1-based line number in its file
  std::array<double, kColumns.size()> values{};
};

struct Trajectory {
  std::string path;
  std::string header;
  std::vector<Row> rows;
};

// An input problem: the one line printed before exiting with status 2.
struct InputError {
  std::string message;
};

// Shortest round-trip text of a double (what the reference files contain).
std::string format(double value) {
  std::array<char, 64> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return {buffer.data(), result.ptr};
}

std::string_view trim(std::string_view text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string_view::npos) {
    return {};
  }
  const auto last = text.find_last_not_of(" \t");
  return text.substr(first, last - first + 1);
}

// The whole field must be one number, as strtod reads it.
std::optional<double> parse_number(std::string_view field) {
  const std::string text(trim(field));
  if (text.empty()) {
    return std::nullopt;
  }
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size()) {
    return std::nullopt;
  }
  // ERANGE on underflow still gives the nearest representable value; overflow
  // gives +-HUGE_VAL, which only matches the same infinity.
  return value;
}

std::string location(const std::string& path, std::size_t line) {
  return path + ":" + std::to_string(line);
}

std::string quoted(std::string_view text) {
  constexpr std::size_t kMaxShown = 80;
  std::string shown(text.substr(0, kMaxShown));
  if (text.size() > kMaxShown) {
    shown += "...";
  }
  return "\"" + shown + "\"";
}

Trajectory read_trajectory(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InputError{"cannot read " + path + ": " + std::strerror(errno)};
  }
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') {
      line.pop_back();
    }
    lines.push_back(std::move(line));
  }
  if (in.bad()) {
    throw InputError{"cannot read " + path + ": read error"};
  }
  while (!lines.empty() && trim(lines.back()).empty()) {
    lines.pop_back();  // blank lines at the end are allowed
  }
  if (lines.empty()) {
    throw InputError{location(path, 1) + ": empty file, expected the header " +
                     std::string(kExpectedHeader)};
  }

  Trajectory trajectory;
  trajectory.path = path;
  trajectory.header = lines.front();
  trajectory.rows.reserve(lines.size() - 1);
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const std::string_view text = lines[i];
    Row row;
    row.line = i + 1;
    std::size_t column = 0;
    std::size_t start = 0;
    while (true) {
      const std::size_t comma = text.find(',', start);
      const std::string_view field = text.substr(
          start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
      if (column >= kColumns.size()) {
        throw InputError{location(path, row.line) + ": malformed row, more than " +
                         std::to_string(kColumns.size()) + " fields: " + quoted(text)};
      }
      const std::optional<double> value = parse_number(field);
      if (!value) {
        throw InputError{location(path, row.line) + ": malformed row, column " +
                         std::string(kColumns[column]) + " is not a number (" + quoted(field) +
                         "): " + quoted(text)};
      }
      row.values[column] = *value;
      ++column;
      if (comma == std::string_view::npos) {
        break;
      }
      start = comma + 1;
    }
    if (column != kColumns.size()) {
      throw InputError{location(path, row.line) + ": malformed row, expected " +
                       std::to_string(kColumns.size()) + " fields, got " + std::to_string(column) +
                       ": " + quoted(text)};
    }
    trajectory.rows.push_back(row);
  }
  return trajectory;
}

std::string key_text(const Row& row) {
  return "frame " + format(row.values[0]) + " body " + format(row.values[1]);
}

// |reference - candidate| / max(1, |reference|); 0 for identical values
// (infinities included), NaN when either side is NaN.
double scaled_error(double reference, double candidate) {
  if (reference == candidate) {
    return 0.0;
  }
  return std::fabs(reference - candidate) / std::max(1.0, std::fabs(reference));
}

// Prints the verdict line on stdout and returns the exit status.
int verdict(int status, const std::string& line) {
  std::cout << line << '\n';
  return status;
}

int compare(const Trajectory& reference, const Trajectory& candidate, double tolerance) {
  if (reference.header != kExpectedHeader) {
    throw InputError{location(reference.path, 1) + ": expected the header " +
                     std::string(kExpectedHeader) + ", got " + quoted(reference.header)};
  }
  if (candidate.header != reference.header) {
    return verdict(kExitFail, "FAIL: header differs: reference " + quoted(reference.header) +
                                  " candidate " + quoted(candidate.header));
  }

  const std::size_t common = std::min(reference.rows.size(), candidate.rows.size());
  std::string count_note;  // appended to a FAIL line when the row counts differ too
  if (reference.rows.size() != candidate.rows.size()) {
    count_note = "row count differs: reference " + std::to_string(reference.rows.size()) +
                 " candidate " + std::to_string(candidate.rows.size());
  }
  const std::string count_suffix = count_note.empty() ? "" : "; " + count_note;

  double max_error = 0.0;
  std::size_t max_row = 0;
  for (std::size_t i = 0; i < common; ++i) {
    const Row& ref = reference.rows[i];
    const Row& cand = candidate.rows[i];
    if (ref.values[0] != cand.values[0] || ref.values[1] != cand.values[1]) {
      return verdict(kExitFail, "FAIL: row " + std::to_string(i + 1) + " (line " +
                                    std::to_string(ref.line) + "): reference " + key_text(ref) +
                                    ", candidate " + key_text(cand) + count_suffix);
    }
    for (std::size_t c = kFirstValueColumn; c < kColumns.size(); ++c) {
      const double error = scaled_error(ref.values[c], cand.values[c]);
      if (!(error <= tolerance)) {  // also catches NaN
        return verdict(kExitFail, "FAIL: first " + key_text(ref) + " column " +
                                      std::string(kColumns[c]) + ": reference " +
                                      format(ref.values[c]) + " candidate " +
                                      format(cand.values[c]) + " (error " + format(error) + ")" +
                                      count_suffix);
      }
      if (error > max_error) {
        max_error = error;
        max_row = i;
      }
    }
  }
  if (!count_note.empty()) {
    return verdict(kExitFail, "FAIL: " + count_note + " (the first " + std::to_string(common) +
                                  " rows match)");
  }
  if (reference.rows.empty()) {
    return verdict(kExitOk, "OK: 0 rows");
  }
  return verdict(kExitOk, "OK: " + std::to_string(reference.rows.size()) + " rows, max error " +
                              format(max_error) + " at " + key_text(reference.rows[max_row]));
}

void print_usage(std::ostream& stream) {
  stream << "usage: trajectory_diff REFERENCE.csv CANDIDATE.csv [--tolerance 1e-9]\n";
}

double parse_tolerance(std::string_view text) {
  const std::optional<double> value = parse_number(text);
  if (!value || !std::isfinite(*value) || *value < 0.0) {
    throw InputError{"--tolerance must be a finite number >= 0 (got " + quoted(text) + ")"};
  }
  return *value;
}

int run(int argc, char** argv) {
  std::vector<std::string> paths;
  double tolerance = kDefaultTolerance;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "-h" || arg == "--help") {
      print_usage(std::cout);
      return kExitOk;
    }
    if (arg == "--tolerance") {
      if (i + 1 >= argc) {
        throw InputError{"--tolerance needs a value"};
      }
      tolerance = parse_tolerance(argv[++i]);
    } else if (arg.starts_with("--tolerance=")) {
      tolerance = parse_tolerance(arg.substr(std::string_view("--tolerance=").size()));
    } else if (arg.starts_with("--")) {
      throw InputError{"unknown option " + std::string(arg)};
    } else {
      paths.emplace_back(arg);
    }
  }
  if (paths.size() != 2) {
    print_usage(std::cerr);
    return kExitError;
  }
  const Trajectory reference = read_trajectory(paths[0]);
  const Trajectory candidate = read_trajectory(paths[1]);
  return compare(reference, candidate, tolerance);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const InputError& error) {
    std::cerr << "trajectory_diff: " << error.message << '\n';
    return kExitError;
  } catch (const std::exception& error) {
    std::cerr << "trajectory_diff: " << error.what() << '\n';
    return kExitError;
  }
}
