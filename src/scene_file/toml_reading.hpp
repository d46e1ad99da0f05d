// SPDX-License-Identifier: MIT
// calder scene files: reading a toml++ document with every problem placed.
//
// TomlReader converts a value (a number, a [x, y], one of a list of names)
// and fails with "FILE:LINE:COLUMN: problem"; Tbl is a table of the document
// with what messages call it, whose keys are checked against a list of the
// keys it may hold. The scene reader (scene_file.cpp) is built on them.
#pragma once

#include <toml++/toml.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "calder/vec2.hpp"
#include "names.hpp"

namespace calder::scene_file_detail {

using Keys = std::vector<std::string_view>;

enum class Check { any, positive, non_negative };

// --- words for messages ---

// The candidate closest to word when it is close enough to be a likely typo.
std::optional<std::string_view> nearest(std::string_view word, const Keys& candidates);
std::string join(const Keys& words);
// Input shown in a message: control characters escaped, cut to a readable length.
std::string quote(std::string_view s);
std::string shown(std::string_view path);
// "a string", "an integer", ... for "must be a number, got a string".
const char* type_name(const toml::node& n);
// Messages are one line, whatever a key or a file name holds.
std::string one_line(std::string s);
bool before(const toml::source_position& a, const toml::source_position& b);

template <class E, std::size_t N>
Keys names(const std::array<Choice<E>, N>& choices) {
  Keys out;
  for (const Choice<E>& c : choices) out.push_back(c.name);
  return out;
}

// --- values ---

class TomlReader {
 public:
  // source: the file name messages start with. top_level_keys: the keys of
  // the document's top level, for the hint when one is written under a table.
  TomlReader(std::string source, const Keys& top_level_keys)
      : source_(std::move(source)), top_level_keys_(&top_level_keys) {}

  [[nodiscard]] const std::string& source() const { return source_; }
  [[nodiscard]] const Keys& top_level_keys() const { return *top_level_keys_; }

  [[noreturn]] void fail(const toml::source_position& at, const std::string& problem) const;
  [[noreturn]] void fail(const toml::node& n, const std::string& problem) const;

  double number(const toml::node& n, const std::string& label, Check check = Check::any) const;
  std::int64_t integer(const toml::node& n, const std::string& label, std::int64_t min,
                       std::int64_t max) const;
  bool boolean(const toml::node& n, const std::string& label) const;
  std::string string(const toml::node& n, const std::string& label) const;
  const toml::array& array_of(const toml::node& n, const std::string& label,
                              const char* shape) const;
  const toml::table& table_of(const toml::node& n, const std::string& label,
                              const char* shape = "a table") const;
  // An array of exactly `size` numbers.
  std::vector<double> numbers(const toml::node& n, const std::string& label, std::size_t size,
                              const char* shape) const;
  Vec2 vec2(const toml::node& n, const std::string& label) const;
  static std::string unknown_choice(const std::string& label, const std::string& got,
                                    const Keys& valid);

  template <class E, std::size_t N>
  E choice(const toml::node& n, const std::string& label,
           const std::array<Choice<E>, N>& choices) const {
    const std::string s = string(n, label);
    for (const Choice<E>& c : choices) {
      if (c.name == s) return c.value;
    }
    fail(n, unknown_choice(label, s, names(choices)));
  }

 private:
  std::string source_;
  const Keys* top_level_keys_;
};

// A table of the document, with what messages call it ("[[bodies]]") and the
// prefix of its keys' labels ("law." for the keys of an inline `law` table).
class Tbl {
 public:
  Tbl(const TomlReader& reader, const toml::table& table, std::string context,
      std::string prefix = "")
      : r_(&reader), t_(&table), context_(std::move(context)), prefix_(std::move(prefix)) {}

  [[nodiscard]] const toml::table& table() const { return *t_; }
  [[nodiscard]] const std::string& context() const { return context_; }
  [[nodiscard]] std::string label(std::string_view key) const { return prefix_ + std::string(key); }
  [[nodiscard]] const toml::node* find(std::string_view key) const { return t_->get(key); }
  // Where a key that is there is written (the key itself, not its value).
  [[nodiscard]] toml::source_position key_at(std::string_view key) const {
    const auto it = t_->find(key);
    return it != t_->end() ? it->first.source().begin : t_->source().begin;
  }

  // Fails at the first key (in the file's order) that is not one of these.
  void allow(const Keys& keys) const;
  // The value of a key that must be there.
  [[nodiscard]] const toml::node& require(std::string_view key) const;

  [[nodiscard]] double number(std::string_view key, double fallback,
                              Check check = Check::any) const;
  [[nodiscard]] bool boolean(std::string_view key, bool fallback) const;
  [[nodiscard]] std::string string(std::string_view key, std::string fallback) const;
  [[nodiscard]] Vec2 vec2(std::string_view key, Vec2 fallback) const;
  template <class E, std::size_t N>
  [[nodiscard]] E choice(std::string_view key, const std::array<Choice<E>, N>& choices,
                         E fallback) const;
  // An optional sub-table (a [table] or an inline { ... }).
  [[nodiscard]] const toml::table* table(std::string_view key) const;
  // An optional array.
  [[nodiscard]] const toml::array* array(std::string_view key) const;

 private:
  const TomlReader* r_;
  const toml::table* t_;
  std::string context_;
  std::string prefix_;
};

template <class E, std::size_t N>
E Tbl::choice(std::string_view key, const std::array<Choice<E>, N>& choices, E fallback) const {
  const toml::node* n = find(key);
  return n != nullptr ? r_->choice(*n, label(key), choices) : fallback;
}

}  // namespace calder::scene_file_detail
