// SPDX-License-Identifier: MIT
// cli_json_check: checks a JSON trajectory written by `calder run` against the
// CSV trajectory of the same run.
//
//   cli_json_check OUT.json OUT.csv [--scene NAME] [--frames N] [--bodies B]
//                  [--dt X] [--seed S]
//
// The JSON must parse, hold "scene", "frames", "bodies", "dt", "seed",
// "columns" = ["frame","body","x","y","vx","vy"] and "rows" with
// (frames + 1) * bodies rows of 6 numbers, equal bit for bit to the CSV's
// rows (both read back exactly). Prints "OK: N rows" and exits 0, or one line
// naming the first difference and exits 1.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace {

int fail(const std::string& message) {
  std::cerr << "cli_json_check: " << message << '\n';
  return 1;
}

bool same(double a, double b) {
  return (std::isnan(a) && std::isnan(b)) || (a == b && std::signbit(a) == std::signbit(b));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3 || (argc - 3) % 2 != 0) {
    std::cerr << "usage: cli_json_check OUT.json OUT.csv [--scene NAME] [--frames N] "
                 "[--bodies B] [--dt X] [--seed S]\n";
    return 2;
  }
  std::map<std::string, std::string> expected;
  for (int i = 3; i + 1 < argc; i += 2) expected[argv[i] + 2] = argv[i + 1];

  std::ifstream json_in(argv[1]);
  if (!json_in) return fail(std::string(argv[1]) + ": cannot open");
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(json_in);
  } catch (const nlohmann::json::exception& e) {
    return fail(std::string(argv[1]) + ": not JSON: " + e.what());
  }
  for (const char* key : {"scene", "frames", "bodies", "dt", "seed", "columns", "rows"}) {
    if (!doc.contains(key)) return fail(std::string("no key '") + key + "'");
  }
  if (doc["columns"] != nlohmann::json({"frame", "body", "x", "y", "vx", "vy"})) {
    return fail("columns are " + doc["columns"].dump());
  }
  if (expected.count("scene") && doc["scene"] != expected["scene"]) {
    return fail("scene is " + doc["scene"].dump());
  }
  for (const char* key : {"frames", "bodies", "seed"}) {
    if (expected.count(key) &&
        doc[key].get<std::int64_t>() != std::strtoll(expected[key].c_str(), nullptr, 10)) {
      return fail(std::string(key) + " is " + doc[key].dump());
    }
  }
  if (expected.count("dt") &&
      doc["dt"].get<double>() != std::strtod(expected["dt"].c_str(), nullptr)) {
    return fail("dt is " + doc["dt"].dump());
  }

  std::ifstream csv_in(argv[2]);
  if (!csv_in) return fail(std::string(argv[2]) + ": cannot open");
  std::string line;
  std::getline(csv_in, line);
  if (line != "frame,body,x,y,vx,vy") return fail("CSV header is " + line);
  std::vector<std::vector<double>> csv;
  while (std::getline(csv_in, line)) {
    std::vector<double> row;
    std::stringstream fields(line);
    std::string field;
    while (std::getline(fields, field, ',')) row.push_back(std::strtod(field.c_str(), nullptr));
    csv.push_back(row);
  }

  const auto& rows = doc["rows"];
  const auto frames = doc["frames"].get<std::int64_t>();
  const auto bodies = doc["bodies"].get<std::int64_t>();
  if (!rows.is_array() || static_cast<std::int64_t>(rows.size()) != (frames + 1) * bodies) {
    return fail("expected (frames + 1) * bodies rows, got " + std::to_string(rows.size()));
  }
  if (rows.size() != csv.size()) {
    return fail("JSON has " + std::to_string(rows.size()) + " rows, CSV " +
                std::to_string(csv.size()));
  }
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const auto& row = rows[r];
    if (!row.is_array() || row.size() != 6 || csv[r].size() != 6) {
      return fail("row " + std::to_string(r) + " does not have 6 values");
    }
    if (!row[0].is_number_integer() || !row[1].is_number_integer()) {
      return fail("row " + std::to_string(r) + ": frame and body must be integers");
    }
    for (std::size_t c = 0; c < 6; ++c) {
      if (!row[c].is_number()) return fail("row " + std::to_string(r) + " holds a non-number");
      const double value = row[c].get<double>();
      if (!same(value, csv[r][c])) {
        return fail("row " + std::to_string(r) + " column " + std::to_string(c) + ": JSON " +
                    row[c].dump() + ", CSV " + std::to_string(csv[r][c]));
      }
    }
  }
  std::cout << "OK: " << rows.size() << " rows\n";
  return 0;
}
