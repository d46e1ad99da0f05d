// SPDX-License-Identifier: MIT
// calder scene files: reading a toml++ document with every problem placed
// (see toml_reading.hpp).
#include "toml_reading.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "calder/error.hpp"
#include "calder/scene_file.hpp"
#include "calder/trajectory.hpp"

namespace calder::scene_file_detail {

// --- words for messages ---

// See calder::detail::closest.
std::optional<std::string_view> nearest(std::string_view word, const Keys& candidates) {
  return detail::closest(word, candidates);
}

std::string join(const Keys& words) {
  std::string out;
  for (const std::string_view w : words) {
    if (!out.empty()) out += ", ";
    out += w;
  }
  return out;
}

std::string quote(std::string_view s) { return cat("'", detail::printable(s), "'"); }
std::string shown(std::string_view path) { return detail::printable(path, 240); }

const char* type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a float";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::table:
      return "a table";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    case toml::node_type::none:
      break;
  }
  return "nothing";
}

std::string one_line(std::string s) {
  for (char& c : s) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return s;
}

bool before(const toml::source_position& a, const toml::source_position& b) {
  return a.line < b.line || (a.line == b.line && a.column < b.column);
}

// --- values ---

void TomlReader::fail(const toml::source_position& at, const std::string& problem) const {
  const toml::source_position where = at ? at : toml::source_position{1, 1};
  throw SceneFileError(one_line(cat(shown(source_), ":", std::to_string(where.line), ":",
                                    std::to_string(where.column), ": ", problem)));
}

void TomlReader::fail(const toml::node& n, const std::string& problem) const {
  fail(n.source().begin, problem);
}

double TomlReader::number(const toml::node& n, const std::string& label, Check check) const {
  double v = 0.0;
  if (const auto* i = n.as_integer()) {
    v = static_cast<double>(i->get());
  } else if (const auto* f = n.as_floating_point()) {
    v = f->get();
  } else {
    fail(n, quote(label) + " must be a number, got " + type_name(n));
  }
  if (!std::isfinite(v)) {
    fail(n, cat(quote(label), " must be a finite number, got ", format_number(v)));
  }
  if (check == Check::positive && !(v > 0.0)) {
    fail(n, cat(quote(label), " must be > 0, got ", format_number(v)));
  }
  if (check == Check::non_negative && !(v >= 0.0)) {
    fail(n, cat(quote(label), " must be >= 0, got ", format_number(v)));
  }
  return v;
}

std::int64_t TomlReader::integer(const toml::node& n, const std::string& label, std::int64_t min,
                                 std::int64_t max) const {
  const auto* i = n.as_integer();
  if (i == nullptr) fail(n, quote(label) + " must be an integer, got " + type_name(n));
  const std::int64_t v = i->get();
  if (v < min || v > max) {
    fail(n, cat(quote(label), " must be between ", std::to_string(min), " and ",
                std::to_string(max), ", got ", std::to_string(v)));
  }
  return v;
}

bool TomlReader::boolean(const toml::node& n, const std::string& label) const {
  const auto* b = n.as_boolean();
  if (b == nullptr) fail(n, quote(label) + " must be true or false, got " + type_name(n));
  return b->get();
}

std::string TomlReader::string(const toml::node& n, const std::string& label) const {
  const auto* s = n.as_string();
  if (s == nullptr) fail(n, quote(label) + " must be a string, got " + type_name(n));
  return s->get();
}

const toml::array& TomlReader::array_of(const toml::node& n, const std::string& label,
                                        const char* shape) const {
  const auto* a = n.as_array();
  if (a == nullptr) fail(n, quote(label) + " must be " + shape + ", got " + type_name(n));
  return *a;
}

const toml::table& TomlReader::table_of(const toml::node& n, const std::string& label,
                                        const char* shape) const {
  const auto* t = n.as_table();
  if (t == nullptr) fail(n, quote(label) + " must be " + shape + ", got " + type_name(n));
  return *t;
}

std::vector<double> TomlReader::numbers(const toml::node& n, const std::string& label,
                                        std::size_t size, const char* shape) const {
  const toml::array& a = array_of(n, label, shape);
  if (a.size() != size) {
    fail(n, cat(quote(label), " must be ", shape, ", got an array of ", std::to_string(a.size())));
  }
  std::vector<double> out;
  for (std::size_t i = 0; i < size; ++i) {
    out.push_back(number(a[i], cat(label, "[", std::to_string(i), "]")));
  }
  return out;
}

Vec2 TomlReader::vec2(const toml::node& n, const std::string& label) const {
  const std::vector<double> v = numbers(n, label, 2, "an array of 2 numbers [x, y]");
  return {v[0], v[1]};
}

std::string TomlReader::unknown_choice(const std::string& label, const std::string& got,
                                       const Keys& valid) {
  std::string m = cat(quote(label), " must be one of ", join(valid), " (got ", quote(got));
  if (const auto near = nearest(got, valid)) m += cat("; did you mean ", quote(*near), "?");
  return m + ")";
}

// --- tables ---

void Tbl::allow(const Keys& keys) const {
  const toml::key* first = nullptr;
  for (auto&& [key, value] : *t_) {
    (void)value;
    if (std::find(keys.begin(), keys.end(), key.str()) != keys.end()) continue;
    if (first == nullptr || before(key.source().begin, first->source().begin)) first = &key;
  }
  if (first == nullptr) return;
  std::string m = cat("unknown key ", quote(first->str()), " in ", context_);
  if (const auto near = nearest(first->str(), keys)) {
    m += cat(" (did you mean ", quote(*near), "?)");
  } else {
    m += cat(" (valid keys: ", join(keys), ")");
  }
  const bool top_level_key = std::find(r_->top_level_keys().begin(), r_->top_level_keys().end(),
                                       first->str()) != r_->top_level_keys().end();
  if (top_level_key && t_->source().begin.line < first->source().begin.line) {
    // TOML's rule that surprises: every key after a [table] or [[table]]
    // header belongs to that table, up to the next header.
    m += cat("; '", first->str(),
             "' is a top-level key, but keys after a table header belong to "
             "that table: write it above the first [table] or [[table]] header");
  }
  r_->fail(first->source().begin, m);
}

const toml::node& Tbl::require(std::string_view key) const {
  const toml::node* n = find(key);
  if (n == nullptr) r_->fail(*t_, cat("missing required key ", quote(key), " in ", context_));
  return *n;
}

double Tbl::number(std::string_view key, double fallback, Check check) const {
  const toml::node* n = find(key);
  return n != nullptr ? r_->number(*n, label(key), check) : fallback;
}

bool Tbl::boolean(std::string_view key, bool fallback) const {
  const toml::node* n = find(key);
  return n != nullptr ? r_->boolean(*n, label(key)) : fallback;
}

std::string Tbl::string(std::string_view key, std::string fallback) const {
  const toml::node* n = find(key);
  return n != nullptr ? r_->string(*n, label(key)) : fallback;
}

Vec2 Tbl::vec2(std::string_view key, Vec2 fallback) const {
  const toml::node* n = find(key);
  return n != nullptr ? r_->vec2(*n, label(key)) : fallback;
}

const toml::table* Tbl::table(std::string_view key) const {
  const toml::node* n = find(key);
  return n != nullptr ? &r_->table_of(*n, label(key)) : nullptr;
}

const toml::array* Tbl::array(std::string_view key) const {
  const toml::node* n = find(key);
  return n != nullptr ? &r_->array_of(*n, label(key), "an array") : nullptr;
}
}  // namespace calder::scene_file_detail
